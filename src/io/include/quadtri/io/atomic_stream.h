// An output written as a stream, never held whole in memory, that still appears atomically.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace quadtri {

/// Calls write(out) with a binary stream to a temporary file beside `path` (through a buffer of
/// 1 MiB), then renames it to `path` (writeAtomically, atomic_file.h). A stream error or an
/// exception from write leaves nothing behind.
void writeStreamAtomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream& out)>& write);

}  // namespace quadtri
