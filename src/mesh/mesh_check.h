// Private to the mesh layer: the pieces that the checks of mesh_io_check.cpp (OBJ, OFF, STL)
// and ply_check.cpp (PLY) share. Every check throws Error naming the file, and the line or the
// element, before Assimp reads the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadtri/mesh/mesh_io_check.h"

namespace quadtri::mesh_check {

/// Assimp's element counters are 32-bit.
constexpr uint64_t kMaxAssimpCount = std::numeric_limits<uint32_t>::max();

/// Parses a whole word as an unsigned count; nullopt when it is not one (or over 2^64).
std::optional<uint64_t> parseCount(std::string_view word);

/// a × b + c without wrapping: saturates at 2^64 - 1 (a count that large never fits anyway).
uint64_t mulAdd(uint64_t a, uint64_t b, uint64_t c = 0);

/// Refuses counts over what Assimp's 32-bit counters hold: it would read them wrapped.
void checkAssimpCount(const std::string& name, const std::string& format, uint64_t count,
                      std::string_view what);

/// Splits a line into whitespace-separated words.
std::vector<std::string_view> words(std::string_view line);

/// Whether the whole word is a finite decimal number (a leading '+' allowed).
bool parseFinite(std::string_view word);

/// PLY: the header, each declared count against the file's size, and the body element by
/// element (ply_check.cpp).
MeshFileInfo inspectPly(const std::filesystem::path& path, uint64_t fileBytes);

}  // namespace quadtri::mesh_check
