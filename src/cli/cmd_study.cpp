// `quadtri study [MANIFEST|FOLDER] --out DIR`: every model on every mesh of a corpus
// (report/study.h), with study.csv and summary.md.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <filesystem>

#include "commands.h"
#include "normal_flags.h"
#include "quadtri/math/error.h"
#include "quadtri/report/study.h"
#include "quadtri/surface/model.h"
#include "render_flags.h"

namespace quadtri::cli {

Action addStudyCommand(CLI::App& app) {
  struct Options {
    std::string source = "data/corpus-manifest.csv", corpus, out, shard = "1/1";
    NormalFlags normals;
    RenderFlags flags;
    bool quiet = false;
    AnalysisOptions analysis;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "study",
      "Measure every model on every mesh of a corpus manifest or folder, as analyze does; "
      "writes study.csv (one row per mesh and model) and summary.md (one row per model)");
  sub->add_option("source", opt->source,
                  "Manifest (CSV with name and path columns, paths relative to --corpus) or a "
                  "folder of .obj/.off/.ply/.stl files (searched recursively)")
      ->capture_default_str();
  sub->add_option("--corpus", opt->corpus,
                  "Folder the manifest's paths are relative to (default: $QUADTRI_CORPUS, else "
                  "./corpus)");
  sub->add_option("--out", opt->out, "Output folder for study.csv and summary.md")->required();
  opt->flags.add(sub, kModelListFlag | kSeedFlag | kThreadsFlag,
                 "Seed of the crack-rate lines (default 1)");
  sub->add_option("--lines", opt->analysis.crack.lines, "Random lines per crack rate")
      ->capture_default_str()
      ->check(positiveWholeNumber());
  addNormalFlags(sub, opt->normals,
                 "Vertex normals: file (as given; angle-weighted and split at --crease-angle when "
                 "missing), average (thesis eq. 2.8) or angle (angle-weighted, split at "
                 "--crease-angle)");
  sub->add_option("--shard", opt->shard,
                  "I/N: only the meshes whose 0-based index i has i % N == I-1")
      ->capture_default_str();
  sub->add_flag("-q,--quiet", opt->quiet, "No progress lines on stderr");
  return [opt]() {
    namespace fs = std::filesystem;
    const RenderSettings settings = opt->flags.settings();
    StudyOptions options;
    options.models = opt->flags.models();
    options.analysis = opt->analysis;
    if (settings.seed) options.analysis.crack.seed = *settings.seed;
    options.normals = opt->normals.options();
    options.threads = settings.threads;
    options.shard = StudyShard::parse(opt->shard);

    std::vector<StudyMesh> meshes;
    std::string from;
    if (fs::is_directory(opt->source)) {
      meshes = meshesInFolder(opt->source);
      from = fmt::format("folder {}", opt->source);
    } else {
      // Not a folder: a manifest, which must then exist (a file, or a pipe: <(...)).
      if (!fs::exists(opt->source))
        fail("{}: neither a folder of meshes nor a manifest file", opt->source);
      std::string corpus = opt->corpus;
      if (corpus.empty()) {
        const char* env = std::getenv("QUADTRI_CORPUS");
        corpus = env && *env ? env : "corpus";
      }
      if (!fs::is_directory(corpus))
        fail("--corpus {}: not a folder (fetch the meshes with scripts/fetch-corpus.sh)", corpus);
      meshes = readCorpusManifest(opt->source, corpus);
      from = fmt::format("manifest {}, corpus {}", opt->source, corpus);
    }
    if (!opt->quiet)
      options.onProgress = [](const StudyProgress& p) {
        if (p.finished)
          fmt::print(stderr, "study: {}/{} meshes done: {}{}\n", p.done, p.total, p.mesh,
                     p.failedModels ? fmt::format(" ({} models failed)", p.failedModels) : "");
        else
          fmt::print(stderr, "study: {}/{} meshes done, starting {}\n", p.done, p.total, p.mesh);
      };
    const std::vector<StudyRow> rows = runStudy(meshes, options);
    const std::string what =
        fmt::format("From {}; shard {}; {} crack-rate lines, seed {}; normals {}.", from,
                    opt->shard, options.analysis.crack.lines, options.analysis.crack.seed,
                    opt->normals.source.empty() ? std::string("file") : opt->normals.source);
    for (const fs::path& path : writeStudy(opt->out, rows, what))
      fmt::print("wrote {}\n", path.string());
    size_t failed = 0;
    for (const StudyRow& row : rows) failed += !row.error.empty();
    fmt::print("{} rows ({} meshes of {} in shard {}), {} with an error\n", rows.size(),
               rows.size() / std::max<size_t>(1, options.models.empty() ? modelNames().size()
                                                                        : options.models.size()),
               meshes.size(), opt->shard, failed);
    return 0;
  };
}

}  // namespace quadtri::cli
