// Outputs are written to a temporary file beside the target and renamed into place, so an error
// never leaves a half-written file behind.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace quadtri {

/// Calls write(tmp) with a temporary path in the target's folder that keeps the target's
/// extension (image writers choose the format from it), then renames tmp to `path`. If write
/// throws, the temporary file is removed and the exception propagates.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& tmp)>& write);

/// Removes every temporary file a writeAtomically call has open at this moment, in any thread.
/// Async-signal-safe (it only reads a fixed table and calls unlink), for a signal handler that
/// ends the process at once and must leave no temporary file behind.
void removeTemporaryFilesNow() noexcept;

/// Throws Error, naming the files, when two of `inputs` are one file (given twice, or under two
/// names) or `output` is one of them (a merge would replace an input it reads); `what` names
/// the inputs in the message ("tile", "study shard").
void checkDistinctFiles(const std::vector<std::filesystem::path>& inputs,
                        const std::filesystem::path& output, const std::string& what);

/// Writes `text` to `path` atomically.
void writeTextFile(const std::filesystem::path& path, const std::string& text);

}  // namespace quadtri
