// Each subcommand registers its options on the CLI11 app and returns what to run.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>

namespace quadtri::cli {

using Action = std::function<int()>;

/// Adds `--max-memory BYTES|NNG|NNM` to a subcommand; the returned function gives the limit in
/// bytes once parsed (default: kDefaultMemoryShare of physicalMemoryBytes(), memory_limit.h).
std::function<uint64_t()> addMaxMemoryOption(CLI::App& sub);

Action addAnalyzeCommand(CLI::App& app);
Action addConvergenceCommand(CLI::App& app);
Action addConvertCommand(CLI::App& app);
Action addFigureCommand(CLI::App& app);
Action addMergeCommand(CLI::App& app);
Action addMeshCommand(CLI::App& app);
Action addRenderCommand(CLI::App& app);
Action addReproduceCommand(CLI::App& app);
Action addStudyCommand(CLI::App& app);

}  // namespace quadtri::cli
