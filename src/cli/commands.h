// Each subcommand registers its options on the CLI11 app and returns what to run.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace quadtri::cli {

using Action = std::function<int()>;

/// For an output file: its folder must exist before any work starts, not only when the file is
/// written (after a render of hours, say).
inline CLI::Validator outputFile() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        const std::filesystem::path path(value);
        const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
        std::error_code ec;
        if (!std::filesystem::is_directory(folder, ec))
          return value + ": the folder " + folder.string() + " does not exist";
        return {};
      },
      "FILE");
}

/// For an unsigned option: CLI11 reads "-5" into one as 2^64 - 5, so a sign is refused.
inline CLI::Validator wholeNumber() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        const size_t start = value.find_first_not_of(" \t");
        if (start != std::string::npos && value[start] == '-')
          return "expected a whole number, 0 or more, got " + value;
        return {};
      },
      "UINT");
}

/// wholeNumber, and not 0 (a count that must be positive, such as --lines).
inline CLI::Validator positiveWholeNumber() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        const size_t start = value.find_first_not_of(" \t");
        const size_t end = value.find_last_not_of(" \t");
        const bool zero =
            start != std::string::npos && value.find_first_not_of('0', start) > end;  // only zeros
        if (start != std::string::npos && (value[start] == '-' || zero))
          return "expected a whole number, 1 or more, got " + value;
        return {};
      },
      "UINT");
}

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
