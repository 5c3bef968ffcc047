#include "quadtri/mesh/mesh_io_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "mesh_check.h"
#include "quadtri/io/memory_limit.h"
#include "quadtri/math/error.h"
#include "quadtri/math/large_array.h"

namespace quadtri {
namespace mesh_check {

std::optional<uint64_t> parseCount(std::string_view word) {
  uint64_t value = 0;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, value);
  if (ec != std::errc() || ptr != end || word.empty() || word[0] == '-') return std::nullopt;
  return value;
}

uint64_t mulAdd(uint64_t a, uint64_t b, uint64_t c) {
  constexpr uint64_t kMax = std::numeric_limits<uint64_t>::max();
  if (a != 0 && b > (kMax - c) / a) return kMax;
  return a * b + c;
}

void checkAssimpCount(const std::string& name, const std::string& format, uint64_t count,
                      std::string_view what) {
  if (count > kMaxAssimpCount)
    fail("{}: the {} header declares {} {}, more than the {} Assimp can count", name, format, count,
         what, kMaxAssimpCount);
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> w;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) w.push_back(line.substr(start, i - start));
  }
  return w;
}

bool parseFinite(std::string_view word) {
  if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);  // from_chars takes no '+'
  double value = 0.0;
  const char* end = word.data() + word.size();
  auto [ptr, ec] = std::from_chars(word.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

MemoryStream::Buffer::Buffer(std::string_view bytes) {
  char* begin = const_cast<char*>(bytes.data());  // read only: no put area is set
  setg(begin, begin, begin + bytes.size());
}

MemoryStream::Buffer::pos_type MemoryStream::Buffer::seekoff(off_type off,
                                                             std::ios_base::seekdir dir,
                                                             std::ios_base::openmode which) {
  const off_type size = egptr() - eback();
  const off_type base = dir == std::ios_base::beg   ? 0
                        : dir == std::ios_base::cur ? gptr() - eback()
                                                    : size;
  if (!(which & std::ios_base::in) || off < -base || off > size - base) return off_type(-1);
  setg(eback(), eback() + (base + off), egptr());
  return base + off;
}

MemoryStream::Buffer::pos_type MemoryStream::Buffer::seekpos(pos_type pos,
                                                             std::ios_base::openmode which) {
  return seekoff(off_type(pos), std::ios_base::beg, which);
}

MemoryStream::MemoryStream(std::string_view bytes) : std::istream(nullptr), buffer_(bytes) {
  rdbuf(&buffer_);
}

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace mesh_check

namespace {

using namespace mesh_check;

// OFF: [ST][C][N]OFF, the vertex and face counts, then one vertex per line and one face
// "k i1 .. ik" per line (off_reader.cpp reads it). The counts must fit in the file's size;
// with `body`, every vertex and face line is checked as well (readOffBody, allocating nothing).
MeshFileInfo inspectOff(const std::filesystem::path& path, std::string_view bytes, bool body) {
  const std::string name = path.string();
  const uint64_t fileBytes = bytes.size();
  const OffHeader h = readOffHeader(name, bytes);
  // A vertex is a line of its numbers, each at least a digit and a separator; a face is at
  // least its vertex count and a separator.
  const uint64_t numbers = 3 + (h.normals ? 3 : 0) + (h.colours ? 1 : 0) + (h.texcoords ? 2 : 0);
  const uint64_t perVertex = 2 * numbers, perFace = 2;
  const uint64_t need = mulAdd(h.vertices, perVertex, mulAdd(h.faces, perFace));
  // The last line may end without its separator.
  if (need > 0 && need - 1 > fileBytes - std::min<uint64_t>(fileBytes, h.bodyOffset))
    fail(
        "{}: the OFF header declares {} vertices and {} faces, which take at least {} bytes "
        "({} per vertex, {} per face); the file has {} bytes",
        name, h.vertices, h.faces, need, perVertex, perFace, fileBytes);
  if (body) readOffBody(name, bytes, h, nullptr);
  MeshFileInfo info;
  info.format = "OFF";
  info.fileBytes = fileBytes;
  info.vertices = h.vertices;
  info.normals = h.normals ? h.vertices : 0;  // NOFF: one per vertex
  info.faces = h.faces;
  info.corners = 3 * h.faces;
  info.triangles = h.faces;
  return info;
}

// ASCII STL: every facet ... endfacet holds exactly three `vertex` entries of three numbers
// (Assimp leaks its mesh when it throws on one that does not); returns the facets.
uint64_t checkAsciiStlFacets(std::istream& in, const std::string& name) {
  uint64_t facets = 0;
  int vertices = 0;
  bool open = false;
  std::string word;
  while (in >> word) {
    if (word == "facet") {
      if (open)
        fail("{}: facet {} starts before facet {} ends ('endfacet')", name, facets + 2, facets + 1);
      open = true;
      vertices = 0;
    } else if (word == "vertex") {
      if (!open || ++vertices > 3)
        fail("{}: facet {}: a vertex {}, expected three inside each facet ... endfacet", name,
             facets + 1, open ? "beyond the third" : "outside a facet");
      for (int k = 0; k < 3; ++k)
        if (!(in >> word) || !parseFinite(word))
          fail("{}: facet {}, vertex {}: coordinate {} is not a finite number", name, facets + 1,
               vertices, k + 1);
    } else if (word == "endfacet") {
      if (!open || vertices != 3)
        fail("{}: facet {} has {} vertices, expected 3", name, facets + 1, vertices);
      open = false;
      ++facets;
    }
  }
  if (open) fail("{}: facet {} has no 'endfacet'", name, facets + 1);
  return facets;
}

// STL: binary when the size is exactly 84 + 50 × the count at byte 80 (as Assimp decides, but
// without its 32-bit wrap), ASCII when it starts with "solid".
MeshFileInfo inspectStl(const std::filesystem::path& path, std::string_view bytes) {
  const std::string name = path.string();
  const uint64_t fileBytes = bytes.size();
  MemoryStream in(bytes);
  std::array<char, 84> header{};
  in.read(header.data(), header.size());
  const size_t got = size_t(in.gcount());
  uint32_t count = 0;
  std::memcpy(&count, header.data() + 80, sizeof(count));  // little-endian, as on x86 and ARM
  const uint64_t binaryBytes = 84 + 50 * uint64_t(count);
  std::string_view start(header.data(), got);
  while (!start.empty() && std::isspace(static_cast<unsigned char>(start.front())))
    start.remove_prefix(1);
  const bool solid = start.substr(0, 5) == "solid";
  MeshFileInfo info;
  info.fileBytes = fileBytes;
  if (got == 84 && binaryBytes == fileBytes) {
    info.format = "STL binary";
    info.faces = count;
  } else if (got == 84 && uint32_t(binaryBytes) == uint32_t(fileBytes)) {
    // Assimp's test for binary STL computes 84 + 50 × count in 32 bits, and this count wraps
    // to the file's size: refused here, where the sum does not wrap.
    fail(
        "{}: the binary STL header declares {} triangles, which take 84 + 50 × {} = {} bytes; "
        "the file has {} bytes",
        name, count, count, binaryBytes, fileBytes);
  } else if (solid) {
    info.format = "STL ascii";
    in.clear();
    in.seekg(0);
    info.faces = checkAsciiStlFacets(in, name);
  } else if (got == 84) {
    fail(
        "{}: the binary STL header declares {} triangles, which take 84 + 50 × {} = {} bytes; "
        "the file has {} bytes (and does not start with 'solid', so it is no ASCII STL)",
        name, count, count, binaryBytes, fileBytes);
  } else {
    fail(
        "{}: {} bytes, expected an ASCII STL (starting with 'solid') or a binary STL (an "
        "80-byte header, a triangle count and 50 bytes per triangle)",
        name, fileBytes);
  }
  checkAssimpCount(name, info.format, 3 * info.faces, "vertices");
  info.vertices = 3 * info.faces;
  info.corners = 3 * info.faces;
  info.triangles = info.faces;
  return info;
}

// Checks one face-vertex index against the `count` elements defined above it; returns an error
// text (what was wrong, expected what) or "" when the index is valid. The valid case, every
// index of a large file, formats nothing.
std::string checkObjIndex(std::string_view text, long count, const char* what, const char* plural) {
  long index = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, index);
  if (ec == std::errc() && ptr == end && index != 0) {
    const long resolved = index > 0 ? index : count + index + 1;
    if (resolved >= 1 && resolved <= count) return {};
  }
  const std::string range = count == 0 ? fmt::format("a {} defined above (none yet)", what)
                                       : fmt::format(
                                             "1..{} or -{}..-1 (OBJ refers only to {} "
                                             "defined above)",
                                             count, count, plural);
  if (ec == std::errc::result_out_of_range && ptr == end)
    return fmt::format("{} index {} is out of range, expected {}", what, text, range);
  if (ec != std::errc() || ptr != end)
    return fmt::format("{} index '{}' is not an integer, expected {}", what, text, range);
  return fmt::format("{} index {} is out of range, expected {}", what, index, range);
}

// isspace in the C locale, inline.
constexpr bool isSpace(char c) {
  return c == ' ' || (c >= '\t' && c <= '\r');
}

// Splits a line into whitespace-separated words, reusing `w`'s storage.
void splitWords(std::string_view line, std::vector<std::string_view>& w) {
  w.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSpace(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !isSpace(line[i])) ++i;
    if (i > start) w.push_back(line.substr(start, i - start));
  }
}

// Our own checks on an OBJ file before Assimp reads it, so that an error names its line:
// Assimp accepts or misreports some bad input (a coordinate that is no number, a short face,
// an index past the vertices). Returns the counts. Lines end at '\n' (as std::getline ends
// them); nothing is allocated per line.
MeshFileInfo validateObj(const std::filesystem::path& path, std::string_view text) {
  const std::string name = path.string();
  long counts[3] = {0, 0, 0};  // v, vt, vn defined so far
  MeshFileInfo info;
  info.format = "OBJ";
  info.fileBytes = text.size();
  std::vector<std::string_view> w;
  size_t next = 0;
  for (long lineNo = 1; next < text.size(); ++lineNo) {
    const size_t newline = std::min(text.find('\n', next), text.size());
    std::string_view line = text.substr(next, newline - next);
    next = newline + 1;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    splitWords(line, w);
    if (w.empty()) continue;
    const std::string_view key = w[0];
    if (key == "v" || key == "vn" || key == "vt") {
      const size_t n = w.size() - 1;
      // v: x y z [w] or x y z r g b (vertex colours); vt: u [v [w]]; vn: x y z.
      bool countOk = n >= 1 && n <= 3;
      const char* expected = "1 to 3 numbers";
      if (key == "v") {
        countOk = n == 3 || n == 4 || n == 6;
        expected = "x y z, x y z w or x y z r g b";
      } else if (key == "vn") {
        countOk = n == 3;
        expected = "3 numbers";
      }
      if (!countOk)
        fail("{}:{}: '{}' line has {} values, expected {}", name, lineNo, key, n, expected);
      for (size_t i = 1; i < w.size(); ++i)
        if (!parseFinite(w[i]))
          fail("{}:{}: '{}' value '{}' is not a finite number, expected {}", name, lineNo, key,
               w[i], expected);
      ++counts[key == "v" ? 0 : key == "vt" ? 1 : 2];
    } else if (key == "f") {
      if (w.size() < 4)
        fail("{}:{}: face has {} vertices, expected at least 3", name, lineNo, w.size() - 1);
      for (size_t i = 1; i < w.size(); ++i) {
        const std::string_view vertex = w[i];
        // i, i/j, i//k or i/j/k: the first part is required, empty parts only as in i//k.
        std::array<std::string_view, 4> parts;
        size_t partCount = 0;
        for (size_t start = 0;;) {
          const size_t slash = vertex.find('/', start);
          if (partCount < parts.size())
            parts[partCount] = vertex.substr(start, slash - std::min(slash, start));
          ++partCount;
          if (slash == std::string_view::npos) break;
          start = slash + 1;
        }
        const bool shapeOk = partCount <= 3 && !parts[0].empty() && !parts[partCount - 1].empty() &&
                             !(partCount == 2 && parts[1].empty());
        if (!shapeOk)
          fail("{}:{}: face vertex '{}' is malformed, expected i, i/j, i//k or i/j/k", name, lineNo,
               vertex);
        static constexpr const char* kinds[3] = {"vertex", "texcoord", "normal"};
        static constexpr const char* plurals[3] = {"vertices", "texcoords", "normals"};
        for (size_t k = 0; k < partCount; ++k) {
          if (parts[k].empty()) continue;  // the texcoord of i//k
          const std::string error = checkObjIndex(parts[k], counts[k], kinds[k], plurals[k]);
          if (!error.empty()) fail("{}:{}: face vertex '{}': {}", name, lineNo, vertex, error);
        }
      }
      ++info.faces;
      info.corners += w.size() - 1;
      info.triangles += w.size() - 3;
    }
    // Every other keyword (o, g, s, usemtl, mtllib, l, p, ...) is left to Assimp.
  }
  info.vertices = uint64_t(counts[0]);
  info.normals = uint64_t(counts[2]);
  info.texcoords = uint64_t(counts[1]);
  return info;
}

}  // namespace

namespace mesh_check {

std::string readMeshFile(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const uint64_t fileBytes = std::filesystem::file_size(path, ec);
  if (ec) fail("{}: cannot read the file's size ({})", name, ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open file", name);
  std::string bytes;
  resizeLarge(bytes, size_t(fileBytes));
  in.read(bytes.data(), std::streamsize(bytes.size()));
  if (uint64_t(in.gcount()) != fileBytes)
    fail("{}: cannot read the file ({} of its {} bytes read)", name, in.gcount(), fileBytes);
  return bytes;
}

}  // namespace mesh_check

MeshFileInfo inspectMeshFile(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".off")
    fail("{}: unsupported mesh format '{}': expected .obj, .ply, .stl or .off", path.string(), ext);
  return inspectMeshBytes(path, readMeshFile(path));
}

MeshFileInfo mesh_check::inspectMeshBytes(const std::filesystem::path& path, std::string_view bytes,
                                          bool offBody, std::string* plyAssimpText) {
  const std::string name = path.string();
  const std::string ext = lowerExtension(path);
  MeshFileInfo info;
  if (ext == ".obj")
    info = validateObj(path, bytes);
  else if (ext == ".off")
    info = inspectOff(path, bytes, offBody);
  else if (ext == ".ply")
    info = mesh_check::inspectPly(path, bytes, plyAssimpText);
  else if (ext == ".stl")
    info = inspectStl(path, bytes);
  else
    fail("{}: unsupported mesh format '{}': expected .obj, .ply, .stl or .off", name, ext);
  info.loadBytes = estimateLoadBytes(info);
  return info;
}

uint64_t estimateLoadBytes(const MeshFileInfo& info) {
  // Bytes per element beyond the file itself, held twice: the loader reads it into memory once
  // for the checks and for Assimp, which copies it into its own buffer. Assimp's
  // arrays before and after triangulation and pre-transformation, TriangleMesh's positions,
  // normals and triangles with the maps that weld them. Measured with getrusage's peak
  // resident size on a 1,310,720-triangle icosphere in each format, which these reproduce
  // within 15%: OBJ 394 MiB, OFF 217, binary PLY 277, ASCII PLY 277, binary STL 310, ASCII
  // STL 446 (the file buffers included). STL declares 3 unwelded vertices per facet.
  struct Costs {
    double vertex, face, other;
  };
  // Since the native OBJ and OFF readers keep doubles (24 bytes a point or normal, welded by
  // 24-byte keys), their vertices and normals cost 24 to 36 bytes more than these measurements
  // of 12-byte floats gave; Assimp's formats pay the wider welding keys only (12 bytes).
  Costs c{84, 160, 56};  // OBJ; `other`: vn and vt lines
  if (info.format == "OFF")
    c = {84, 110, 48};  // `other`: NOFF's normals
  else if (info.format.rfind("PLY", 0) == 0)
    c = {72, 165, 24};  // `other`: elements other than vertex and face
  else if (info.format.rfind("STL", 0) == 0)
    c = {36, 130, 0};
  const double others = double(info.normals + info.texcoords + info.otherElements);
  // An ASCII PLY file is given to Assimp rewritten (inspectPly): one more copy of about its size.
  const double copies = info.format == "PLY ascii" ? 3.0 : 2.0;
  const double bytes = copies * double(info.fileBytes) + c.vertex * double(info.vertices) +
                       c.face * double(info.triangles) + c.other * others;
  return bytes >= 0x1p63 ? uint64_t(1) << 63 : uint64_t(bytes);
}

void chargeMemory(MemoryBudget& budget, uint64_t bytes, const std::string& name,
                  const std::string& what) {
  const uint64_t total = budget.usedBytes + std::min(bytes, ~budget.usedBytes);
  if (budget.maxBytes > 0 && total > budget.maxBytes) {
    const std::string before =
        budget.usedBytes > 0
            ? fmt::format(" (on top of the {} charged before it)", formatBytes(budget.usedBytes))
            : std::string();
    fail("{}: {} needs about {}{}, over the {} limit of {}; raise it with {} BYTES|NNG|NNM", name,
         what, formatBytes(bytes), before, budget.option, formatBytes(budget.maxBytes),
         budget.option);
  }
  budget.usedBytes = total;
}

uint64_t modelBytes(const MemoryBudget& budget, uint64_t triangles) {
  const uint64_t capped =
      std::min(std::max(mulAdd(triangles, budget.cappedBytesPerTriangle), budget.cappedFloorBytes),
               budget.cappedBytes);
  return mulAdd(triangles, budget.bytesPerTriangle, capped);
}

std::string describeModelBytes(const MemoryBudget& budget) {
  std::string text = formatBytes(budget.bytesPerTriangle) + " per triangle";
  if (budget.cappedBytesPerTriangle > 0 && budget.cappedBytes > 0)
    text += fmt::format(
        " and {} more per triangle{} up to {}", formatBytes(budget.cappedBytesPerTriangle),
        budget.cappedFloorBytes > 0 ? ", at least " + formatBytes(budget.cappedFloorBytes) + ","
                                    : std::string(),
        formatBytes(budget.cappedBytes));
  return text;
}

void chargeMeshFile(MemoryBudget& budget, const MeshFileInfo& info,
                    const std::filesystem::path& path) {
  const uint64_t model = modelBytes(budget, info.triangles);
  const uint64_t bytes = info.loadBytes + std::min(model, ~info.loadBytes);
  chargeMemory(budget, bytes, path.string(),
               fmt::format("loading its {} vertices and {} faces ({}){}", info.vertices, info.faces,
                           formatBytes(info.loadBytes),
                           model > 0 ? fmt::format(" and building {} ({})",
                                                   describeModelBytes(budget), formatBytes(model))
                                     : std::string()));
}

}  // namespace quadtri
