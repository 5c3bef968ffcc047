// `quadtri merge TILES... -o image.exr`: assembles the tiles of `render --tile/--crop`;
// `quadtri merge SHARDS.csv... -o study.csv`: joins the study.csv files of `study --shard`.
#include <fmt/core.h>

#include <filesystem>

#include "commands.h"
#include "quadtri/math/error.h"
#include "quadtri/render/tiles.h"
#include "quadtri/report/study.h"

namespace quadtri::cli {

Action addMergeCommand(CLI::App& app) {
  struct Options {
    std::vector<std::string> tiles;
    std::string output;
    bool allowUnfinished = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "merge",
      "Assemble the EXR tiles of `render --tile I/N` or `--crop` into the whole film, checking "
      "that they are of one render and cover the film exactly once; or join the study.csv "
      "files of `study --shard I/N`");
  sub->add_option("tiles", opt->tiles, "Tile images (.exr), or study.csv shards (.csv)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("-o,--output", opt->output,
                  "Assembled image (.exr, or .png), or the joined study (.csv)")
      ->required()
      ->check(outputFile());
  sub->add_flag("--allow-unfinished", opt->allowUnfinished,
                "Merge tiles that --time or a signal cut short, their unfinished pixels black "
                "(refused otherwise)");
  return [opt]() {
    size_t csv = 0;
    for (const std::string& t : opt->tiles) csv += std::filesystem::path(t).extension() == ".csv";
    if (csv == opt->tiles.size()) {
      if (std::filesystem::path(opt->output).extension() != ".csv")
        fail("output {}: study shards merge into a .csv file", opt->output);
      std::vector<std::filesystem::path> shards(opt->tiles.begin(), opt->tiles.end());
      const size_t rows = mergeStudyShards(shards, opt->output);
      fmt::print("wrote {}: {} rows from {} shards\n", opt->output, rows, shards.size());
      return 0;
    }
    if (csv != 0) fail("merge: give either image tiles (.exr) or study shards (.csv), not both");
    const std::string ext = std::filesystem::path(opt->output).extension().string();
    if (ext != ".exr" && ext != ".png")
      fail("output {}: expected a .exr or .png file", opt->output);
    std::vector<std::filesystem::path> tiles(opt->tiles.begin(), opt->tiles.end());
    const MergeSummary summary = mergeTiles(tiles, opt->output, {opt->allowUnfinished});
    if (summary.nonFiniteReplaced)
      fmt::print(stderr, "warning: {}: {} non-finite values written as 0\n", opt->output,
                 summary.nonFiniteReplaced);
    if (summary.unfinishedPixels)
      fmt::print(stderr, "warning: {}: {} pixels of cut-short tiles are black\n", opt->output,
                 summary.unfinishedPixels);
    fmt::print("wrote {}: {} tiles, {}x{}\n", opt->output, summary.tiles, summary.width,
               summary.height);
    return 0;
  };
}

}  // namespace quadtri::cli
