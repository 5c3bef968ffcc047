// Private to the mesh layer: the pieces that the checks of mesh_io_check.cpp (OBJ, OFF, STL)
// and ply_check.cpp (PLY) share, and the native OBJ and OFF readers (obj_reader.cpp,
// off_reader.cpp). Every check throws Error naming the file, and the line or the element, before
// a reader allocates for the file's elements.
#pragma once

#include <assimp/vector3.h>

#include <array>
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

/// A point or normal as the native readers keep it: the file's number as the nearest double.
using Point3 = std::array<double, 3>;

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

/// The path's extension in lower case, with its dot (".obj"); empty when it has none.
std::string lowerExtension(const std::filesystem::path& path);

/// inspectMeshFile on the file's bytes, already read (readMeshFile): what loadMesh does, so the
/// file is read once for the checks and the reader. `path` names the file in errors and gives
/// its format by extension. With offBody false, an OFF file's header alone is checked: its body
/// is left to readOffBody, which checks it as it reads it. An ASCII PLY file's text for Assimp
/// goes to `plyAssimpText` (inspectPly).
MeshFileInfo inspectMeshBytes(const std::filesystem::path& path, std::string_view bytes,
                              bool offBody = true, std::string* plyAssimpText = nullptr);

/// The whole file; throws Error naming it when it cannot be read.
std::string readMeshFile(const std::filesystem::path& path);

/// A plain OBJ file as Assimp's OBJ importer lays it out: one vertex per face corner, in face
/// order (triangle f is vertices 3f, 3f+1, 3f+2); vertex i at the file's v line pointOf[i] and,
/// when the file's faces give normals, with its vn line normalOf[i] (0-based). The numbers are
/// doubles (Assimp would round them to floats).
struct ObjCorners {
  std::vector<Point3> points, normals;
  std::vector<uint32_t> pointOf, normalOf;
};

/// Reads an OBJ file natively (any bytes are safe; its result is meant for a file that
/// validateObj accepts, inspectMeshBytes, which may run at the same time), when it holds
/// only what this reader gives as Assimp does: v lines of three numbers, vn, vt, faces of
/// three corners, every one with a normal or none, s lines, blank lines and comments (from a
/// `#` to the end of its line). Numbers take the syntax Assimp's parser takes and are read as the
/// nearest doubles (std::from_chars), where Assimp keeps floats. Returns nullopt for anything else
/// (objects, groups, materials, polygons, lines, homogeneous or coloured vertices, ...), which
/// Assimp then reads. `text` must end in a NUL (std::string's).
std::optional<ObjCorners> readPlainObj(std::string_view text);

/// An ASCII OFF file's header (off_reader.cpp): [ST][C][N]OFF, optional, then the vertex and
/// face counts (on the keyword's line or after it; the rest of the counts' line, the edge
/// count, is not read). Its body starts on the next line.
struct OffHeader {
  std::string keyword;  ///< "OFF", "COFF", "NOFF", ...; "" when the file starts with its counts
  bool texcoords = false, colours = false, normals = false;  ///< ST, C and N
  uint64_t vertices = 0, faces = 0;
  uint64_t countsLine = 0;  ///< the line of the face count
  size_t bodyOffset = 0;    ///< the first byte of the line after the counts
  uint64_t bodyLine = 0;    ///< its line number, from 1
};

/// What the body held beyond its vertices.
struct OffBody {
  uint64_t triangles = 0;           ///< n - 2 per face of n ≥ 3 corners
  uint64_t droppedFaces = 0;        ///< faces of fewer than 3 corners (points, lines): dropped
  uint64_t firstEmptyFaceLine = 0;  ///< the line of the first face of 0 corners, 0 if none
};

/// An OFF file as read: positions (and NOFF's normals, one per position) as the correctly
/// rounded doubles, and 3 corners per triangle, indices into `points` (their triangles are only
/// kept when `points` is, OffMesh given to readOffBody).
struct OffMesh {
  OffHeader header;
  OffBody body;
  std::vector<Point3> points, normals;
  std::vector<uint32_t> corners;
};

/// Reads an OFF header; throws Error naming the file and the line when it is not one: not the
/// keyword or counts, binary OFF, 4OFF or nOFF (homogeneous or n-dimensional vertices). Nothing
/// is allocated per element.
OffHeader readOffHeader(const std::string& name, std::string_view bytes);

/// Reads the body after `header` line by line, as scripts/corpus-manifest.py does: blank lines
/// and '#' comments (anywhere on a line) skipped, then one vertex per line (x y z, then nx ny
/// nz for NOFF; anything after is not read), then one face per line "k i1 .. ik" (anything
/// after, a colour, is not read). A face of k ≥ 3 corners becomes k - 2 triangles on its
/// corners, as the manifest counts them: fanned from its first corner when it is convex in the
/// plane of its Newell normal, else cut into ears in that plane (up to 64 corners; a larger one
/// is fanned); one of fewer corners is dropped. Lines after the last face are not read.
/// Throws Error naming the file, the line and what was expected: counts over 2^32 - 1 (32-bit
/// indices), a coordinate that is not a
/// number or not finite as a float, a missing value or index, an index that is no vertex, a
/// file that ends early. With `out` null only checks (nothing is allocated per element).
OffBody readOffBody(const std::string& name, std::string_view bytes, const OffHeader& header,
                    OffMesh* out);

/// readOffHeader and readOffBody into one OffMesh.
OffMesh readOff(const std::string& name, std::string_view bytes);

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
/// element (ply_check.cpp). `bytes` is the whole file, named `path` in errors. With
/// `assimpText`, an ASCII file is also written there as Assimp is to read it (left empty for a
/// binary one): the header's elements and properties alone, then each element on a line of its
/// own with every property present. Assimp 5.2's reader of ASCII PLY reads a line short of its
/// properties on into what is left in its line buffer from longer lines before (a list count of
/// 1.5 billion from an earlier line's digits, fuzz_ply), returns some blank lines as elements and
/// ends an element's properties at a comment, so it is given no such line.
MeshFileInfo inspectPly(const std::filesystem::path& path, std::string_view bytes,
                        std::string* assimpText = nullptr);

}  // namespace quadtri::mesh_check
