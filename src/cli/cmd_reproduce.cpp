// `quadtri reproduce --quick|--full [--out DIR]`: the thesis' chapter 5 results (RESULTS.md),
// with the speed and memory targets checked; a missed target prints FAIL and exits 1.
#include <fmt/core.h>

#include "commands.h"
#include "quadtri/math/error.h"
#include "quadtri/report/reproduce.h"

namespace quadtri::cli {

Action addReproduceCommand(CLI::App& app) {
  struct Options {
    bool quick = false, full = false, modelsOnly = false, quiet = false;
    ReproduceOptions reproduce;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "reproduce",
      "Reproduce the thesis' chapter 5 figures and tables into DIR/RESULTS.md, DIR/images and "
      "DIR/results, and check the speed and memory targets (exit 1 when one is missed)");
  CLI::Option* quick =
      sub->add_flag("--quick", opt->quick, "Small images, few samples: minutes (the default)");
  sub->add_flag("--full", opt->full, "The scenes' own settings and the teapot in table 5.1: hours")
      ->excludes(quick);
  sub->add_option("--out", opt->reproduce.out, "Folder of RESULTS.md, images/ and results/")
      ->capture_default_str();
  sub->add_option("--root", opt->reproduce.root,
                  "The repository: scenes/thesis/, data/ (teapot.obj, icospheres written there)")
      ->capture_default_str();
  sub->add_option("--work", opt->reproduce.work, "Folder of intermediate files")
      ->capture_default_str();
  sub->add_option("--commit", opt->reproduce.commit, "Commit named in RESULTS.md")
      ->capture_default_str();
  sub->add_option("--threads", opt->reproduce.threads, "Render threads (0: all)")
      ->capture_default_str();
  sub->add_option("--lines", opt->reproduce.lines,
                  "Random lines per crack rate of the every-model measurements")
      ->capture_default_str()
      ->check(positiveWholeNumber());
  sub->add_option("--levels", opt->reproduce.levels,
                  "Refinement levels 0..L of the convergence study")
      ->capture_default_str();
  sub->add_flag("--models-only", opt->modelsOnly,
                "Only the every-model measurements (DIR/results/models.md, models_*.csv, "
                "images/convergence.png)");
  sub->add_flag("-q,--quiet", opt->quiet, "No progress lines on stderr");
  return [opt]() {
    if (opt->reproduce.levels < 0) fail("--levels {}: expected 0 or more", opt->reproduce.levels);
    if (opt->reproduce.threads < 0) fail("--threads expects a positive number");
    ReproduceOptions options = opt->reproduce;
    options.full = opt->full;
    options.command = opt->modelsOnly ? "quadtri reproduce --models-only" : "quadtri reproduce";
    if (!opt->quiet)
      options.log = [](const std::string& line) {
        fmt::print(stderr, "{}\n", line);
        std::fflush(stderr);
      };
    const ReproduceResult result = opt->modelsOnly ? measureModels(options) : reproduce(options);
    for (const auto& path : result.written) fmt::print("wrote {}\n", path.string());
    for (const TargetCheck& check : result.targets)
      fmt::print("{}: {}: {}\n", check.pass ? "pass" : "FAIL", check.target, check.measured);
    const std::vector<std::string> failed = failLines(result.targets);
    if (!failed.empty())
      fmt::print("{} of {} targets missed\n", failed.size(), result.targets.size());
    return failed.empty() ? 0 : 1;
  };
}

}  // namespace quadtri::cli
