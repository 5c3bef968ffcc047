// quadtri: quadric triangles from triangle meshes, their analysis and rendering.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <vector>

#include "commands.h"
#include "quadtri/io/stop_signals.h"
#include "quadtri/math/error.h"

int main(int argc, char** argv) {
  CLI::App app{"quadtri: turns triangle meshes into curved quadric triangles and measures them"};
  app.require_subcommand(1);
  std::vector<std::pair<CLI::App*, quadtri::cli::Action>> commands;
  auto add = [&](quadtri::cli::Action (*registerFn)(CLI::App&)) {
    const size_t before = app.get_subcommands({}).size();
    quadtri::cli::Action action = registerFn(app);
    commands.emplace_back(app.get_subcommands({})[before], std::move(action));
  };
  add(&quadtri::cli::addAnalyzeCommand);
  add(&quadtri::cli::addConvergenceCommand);
  add(&quadtri::cli::addConvertCommand);
  add(&quadtri::cli::addFigureCommand);
  add(&quadtri::cli::addMergeCommand);
  add(&quadtri::cli::addMeshCommand);
  add(&quadtri::cli::addRenderCommand);
  add(&quadtri::cli::addReproduceCommand);
  add(&quadtri::cli::addStudyCommand);
  // A signal ends any command at once without leaving a temporary file behind; `render` takes
  // SIGINT, SIGTERM and SIGHUP over while it renders, to write what it has first.
  quadtri::exitCleanlyOnStopSignals();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints and succeeds; anything else is a mistake in the command line, reported as
    // every other error is (CLI11's own exit codes, 100 and up, read like crashes to a script).
    if (e.get_exit_code() == int(CLI::ExitCodes::Success)) return app.exit(e);
    std::fprintf(stderr, "quadtri: error: %s\nRun with --help for more information.\n", e.what());
    return 1;
  }
  try {
    for (auto& [sub, action] : commands)
      if (sub->parsed()) return action();
  } catch (const quadtri::Error& e) {
    std::fprintf(stderr, "quadtri: error: %s\n", e.what());
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {
    // A folder that cannot be made or a file that cannot be opened: the system's words name it.
    std::fprintf(stderr, "quadtri: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "quadtri: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
