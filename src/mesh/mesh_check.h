// Private to the mesh layer: the pieces that the checks of mesh_io_check.cpp (OBJ, OFF, STL)
// and ply_check.cpp (PLY) share. Every check throws Error naming the file, and the line or the
// element, before Assimp reads the file.
#pragma once

#include <assimp/vector3.h>

#include <cstdint>
#include <filesystem>
#include <istream>
#include <limits>
#include <optional>
#include <streambuf>
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

/// inspectMeshFile on the file's bytes, already read (readMeshFile): what loadMesh does, so the
/// file is read once for the checks and the reader. `path` names the file in errors and gives
/// its format by extension.
MeshFileInfo inspectMeshBytes(const std::filesystem::path& path, std::string_view bytes);

/// The whole file; throws Error naming it when it cannot be read.
std::string readMeshFile(const std::filesystem::path& path);

/// A plain OBJ file as Assimp's OBJ importer lays it out: one vertex per face corner, in face
/// order (triangle f is vertices 3f, 3f+1, 3f+2); vertex i at the file's v line pointOf[i] and,
/// when the file's faces give normals, with its vn line normalOf[i] (0-based).
struct ObjCorners {
  std::vector<aiVector3D> points, normals;
  std::vector<uint32_t> pointOf, normalOf;
};

/// Reads an OBJ file natively (any bytes are safe; its result is meant for a file that
/// validateObj accepts, inspectMeshBytes, which may run at the same time), when it holds
/// only what this reader gives exactly as Assimp does: v lines of three numbers, vn, vt, faces of
/// three corners, every one with a normal or none, s lines, blank lines and comments at the
/// start of a line. Numbers are parsed by Assimp's own parser (fast_atoreal_move). Returns
/// nullopt for anything else (objects, groups, materials, polygons, lines, homogeneous or
/// coloured vertices, ...), which Assimp then reads. `text` must end in a NUL (std::string's).
std::optional<ObjCorners> readPlainObj(std::string_view text);

/// A seekable input stream over bytes in memory: the checks read the loader's one copy of the
/// file through it (the bytes must outlive the stream).
class MemoryStream : public std::istream {
 public:
  explicit MemoryStream(std::string_view bytes);

 private:
  class Buffer : public std::streambuf {
   public:
    explicit Buffer(std::string_view bytes);

   protected:
    pos_type seekoff(off_type off, std::ios_base::seekdir dir,
                     std::ios_base::openmode which) override;
    pos_type seekpos(pos_type pos, std::ios_base::openmode which) override;
  };
  Buffer buffer_;
};

/// PLY: the header, each declared count against the file's size, and the body element by
/// element (ply_check.cpp). `bytes` is the whole file, named `path` in errors.
MeshFileInfo inspectPly(const std::filesystem::path& path, std::string_view bytes);

}  // namespace quadtri::mesh_check
