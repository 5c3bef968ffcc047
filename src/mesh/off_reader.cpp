// The native reader of ASCII OFF files (mesh_check.h, readOffHeader and readOffBody). Assimp's
// OFF importer failed on a comment right after a number (`0.9 0 0#red`), read some closed
// meshes of the corpus as open and read past its buffers on short lines; this reader reads an
// OFF file as scripts/corpus-manifest.py does, and names the line of anything it cannot read.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "mesh_check.h"
#include "quadtri/math/error.h"

namespace quadtri::mesh_check {
namespace {

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// A line as an error quotes it: at most 80 bytes, control bytes as '?'.
std::string quoted(std::string_view line) {
  std::string out(line.substr(0, 80));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  if (line.size() > 80) out += "...";
  return out;
}

// The words of one line (its comment already cut off), one at a time.
class Words {
 public:
  explicit Words(std::string_view line) : p_(line.data()), end_(line.data() + line.size()) {}
  /// The next word; false when the line has no more.
  bool next(std::string_view& word) {
    while (p_ < end_ && isBlank(*p_)) ++p_;
    if (p_ == end_) return false;
    const char* start = p_;
    while (p_ < end_ && !isBlank(*p_)) ++p_;
    word = std::string_view(start, size_t(p_ - start));
    return true;
  }

 private:
  const char* p_;
  const char* end_;
};

// A decimal number as Python's float() reads it, correctly rounded to a double; false unless the
// word is a number. Non-finite values (nan, inf, or beyond a double's range) are returned as
// such.
bool parseNumber(std::string_view word, double& out) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-' && word[1] != '+') word.remove_prefix(1);
  double value = 0.0;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, value);
  if (ptr != end || word.empty()) return false;
  if (ec == std::errc::result_out_of_range) {
    // Below the smallest double (0 or a denormal) or above the largest (infinite): strtod's
    // value, on a NUL-terminated copy.
    value = std::strtod(std::string(word).c_str(), nullptr);
  } else if (ec != std::errc()) {
    return false;
  }
  out = value;
  return true;
}

// An unsigned integer (a leading '+' allowed); false otherwise.
bool parseIndex(std::string_view word, uint64_t& out) {
  if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, out);
  return ec == std::errc() && ptr == end && !word.empty() && word[0] != '-';
}

// The header's words, across lines, '#' comments skipped; keeps the line of each word.
class HeaderWords {
 public:
  explicit HeaderWords(std::string_view bytes) : bytes_(bytes) {}
  /// The next word ("" at the end of the file), and its line.
  std::string_view next(uint64_t& line) {
    for (;;) {
      while (at_ < bytes_.size() && (isBlank(bytes_[at_]) || bytes_[at_] == '\n'))
        if (bytes_[at_++] == '\n') ++line_;
      if (at_ < bytes_.size() && bytes_[at_] == '#') {
        while (at_ < bytes_.size() && bytes_[at_] != '\n') ++at_;
        continue;
      }
      break;
    }
    const size_t start = at_;
    while (at_ < bytes_.size() && !isBlank(bytes_[at_]) && bytes_[at_] != '\n' &&
           bytes_[at_] != '#')
      ++at_;
    line = line_;
    return bytes_.substr(start, at_ - start);
  }
  /// The next word when it is on the current line, else "" (nothing is consumed).
  std::string_view peekOnLine() const {
    size_t i = at_;
    while (i < bytes_.size() && isBlank(bytes_[i])) ++i;
    size_t end = i;
    while (end < bytes_.size() && !isBlank(bytes_[end]) && bytes_[end] != '\n' &&
           bytes_[end] != '#')
      ++end;
    return bytes_.substr(i, end - i);
  }
  /// Skips to the start of the next line; returns its byte offset (the file's size at the end).
  size_t nextLine() {
    while (at_ < bytes_.size() && bytes_[at_] != '\n') ++at_;
    if (at_ < bytes_.size()) {
      ++at_;
      ++line_;
    }
    return at_;
  }
  uint64_t line() const { return line_; }

 private:
  std::string_view bytes_;
  size_t at_ = 0;
  uint64_t line_ = 1;
};

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
  return true;
}

// Polygons of more corners than this are fanned whatever their shape: ear clipping takes up to
// k^3 steps on a polygon of k corners.
constexpr size_t kMaxEarClipCorners = 64;

// Appends the k - 2 triangles of a polygon (indices into `points`, k ≥ 3) to `corners`. A
// polygon that is convex in the plane of its Newell normal (every triangle then faces that
// normal) is fanned from its first corner; one that is not (its fan would fold over itself) is
// cut into ears in that plane, which keeps every triangle inside it. The triangles use only the
// polygon's corners and keep its winding, so its edges are the ones its fan would give.
void triangulate(const std::vector<uint32_t>& polygon, const std::vector<Point3>& points,
                 std::vector<uint32_t>& corners) {
  const size_t k = polygon.size();
  const auto fan = [&](size_t first) {
    for (size_t j = first + 1; j + 1 < k; ++j)
      corners.insert(corners.end(), {polygon[0], polygon[j], polygon[j + 1]});
  };
  if (k == 3 || k > kMaxEarClipCorners) return fan(0);
  // Newell's normal, then the polygon in the plane of its largest component, wound
  // counter-clockwise.
  double n[3] = {0, 0, 0};
  for (size_t i = 0; i < k; ++i) {
    const Point3& a = points[polygon[i]];
    const Point3& b = points[polygon[(i + 1) % k]];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  const int axis = std::abs(n[0]) >= std::abs(n[1]) && std::abs(n[0]) >= std::abs(n[2]) ? 0
                   : std::abs(n[1]) >= std::abs(n[2])                                   ? 1
                                                                                        : 2;
  if (!(std::abs(n[axis]) > 0)) return fan(0);  // no area: nothing to keep inside
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  const double flip = n[axis] > 0 ? 1.0 : -1.0;
  std::array<std::array<double, 2>, kMaxEarClipCorners> p;
  for (size_t i = 0; i < k; ++i) {
    const Point3& q = points[polygon[i]];
    p[i] = {flip * q[size_t(u)], q[size_t(w)]};
  }
  const auto cross = [&](size_t a, size_t b, size_t c) {
    return (p[b][0] - p[a][0]) * (p[c][1] - p[a][1]) - (p[b][1] - p[a][1]) * (p[c][0] - p[a][0]);
  };
  bool convex = true;
  for (size_t i = 0; i < k && convex; ++i) convex = cross((i + k - 1) % k, i, (i + 1) % k) >= 0;
  if (convex) return fan(0);
  // Ear clipping: corner i is an ear when it turns left and no other corner left lies in its
  // triangle (corners at the same point as one of its three excepted).
  std::array<size_t, kMaxEarClipCorners> prev, next;
  for (size_t i = 0; i < k; ++i) {
    prev[i] = (i + k - 1) % k;
    next[i] = (i + 1) % k;
  }
  const auto same = [&](size_t a, size_t b) { return p[a] == p[b]; };
  const auto isEar = [&](size_t i) {
    const size_t a = prev[i], c = next[i];
    if (!(cross(a, i, c) > 0)) return false;
    for (size_t j = next[c]; j != a; j = next[j]) {
      if (same(j, a) || same(j, i) || same(j, c)) continue;
      if (cross(a, i, j) >= 0 && cross(i, c, j) >= 0 && cross(c, a, j) >= 0) return false;
    }
    return true;
  };
  size_t left = k, i = 0, tried = 0;
  while (left > 3) {
    if (!isEar(i)) {
      i = next[i];
      if (++tried < left) continue;
      // No ear (the polygon crosses itself in this plane): the rest is fanned from corner i.
      for (size_t j = next[i]; next[j] != i; j = next[j])
        corners.insert(corners.end(), {polygon[i], polygon[j], polygon[next[j]]});
      return;
    }
    corners.insert(corners.end(), {polygon[prev[i]], polygon[i], polygon[next[i]]});
    next[prev[i]] = next[i];
    prev[next[i]] = prev[i];
    i = prev[i];
    --left;
    tried = 0;
  }
  corners.insert(corners.end(), {polygon[prev[i]], polygon[i], polygon[next[i]]});
}
}  // namespace

OffHeader readOffHeader(const std::string& name, std::string_view bytes) {
  OffHeader h;
  HeaderWords in(bytes);
  uint64_t line = 0;
  const std::string_view first = in.next(line);
  if (first.empty())
    fail("{}: the file is empty: expected the OFF keyword and the vertex and face counts", name);
  // [ST][C][N][4][n]OFF, each prefix at most once and in this order.
  std::string_view key = first;
  const auto take = [&](std::string_view prefix) {
    if (key.substr(0, prefix.size()) != prefix) return false;
    key.remove_prefix(prefix.size());
    return true;
  };
  h.texcoords = take("ST");
  h.colours = take("C");
  h.normals = take("N");
  const bool homogeneous = take("4");
  const bool dimension = take("n");
  std::string_view vertexWord;
  if (key == "OFF") {
    h.keyword = std::string(first);
    if (homogeneous || dimension)
      fail(
          "{}:{}: '{}': homogeneous (4OFF) and n-dimensional (nOFF) vertices are not supported; "
          "expected OFF, COFF, NOFF, CNOFF or an ST prefix of these",
          name, line, first);
    if (equalsIgnoringCase(in.peekOnLine(), "binary"))
      fail("{}:{}: binary OFF is not supported, expected an ASCII OFF file", name, line);
    vertexWord = in.next(line);
  } else {
    // The keyword is optional: a file may start with its counts.
    uint64_t count = 0;
    if (!parseIndex(first, count))
      fail(
          "{}:{}: expected the OFF keyword ([ST][C][N]OFF) or the vertex and face counts, "
          "found '{}'",
          name, line, quoted(first));
    h.texcoords = h.colours = h.normals = false;
    vertexWord = first;
  }
  uint64_t faceLine = line;
  const std::string_view faceWord = in.next(faceLine);
  if (!parseIndex(vertexWord, h.vertices) || !parseIndex(faceWord, h.faces))
    fail(
        "{}:{}: the OFF header's counts are '{} {}', expected the vertex and face counts "
        "(unsigned integers) after the OFF keyword",
        name, line, quoted(vertexWord), quoted(faceWord));
  h.countsLine = faceLine;
  // The rest of the counts' line (the edge count, which nothing needs) is skipped.
  h.bodyOffset = in.nextLine();
  h.bodyLine = in.line();
  if (faceLine == in.line()) ++h.bodyLine;  // the file ended on the counts' line
  return h;
}

OffBody readOffBody(const std::string& name, std::string_view bytes, const OffHeader& h,
                    OffMesh* out) {
  // Indices and counts are 32-bit (a file this large fails its size check first, inspectOff).
  constexpr uint64_t kMax = std::numeric_limits<uint32_t>::max();
  if (h.vertices > kMax || h.faces > kMax)
    fail(
        "{}:{}: the OFF header declares {} vertices and {} faces, more than the {} 32-bit "
        "indices can count",
        name, h.countsLine, h.vertices, h.faces, kMax);
  OffBody body;
  if (out) {
    // No more than the rest of the file can hold (6 bytes a vertex, 2 a face at the least),
    // whatever the header says, so that no count makes this allocate more than the file's size.
    const uint64_t rest = bytes.size() - std::min(h.bodyOffset, bytes.size());
    const size_t vertices = size_t(std::min(h.vertices, rest / 6 + 1));
    out->points.reserve(vertices);
    if (h.normals) out->normals.reserve(vertices);
    out->corners.reserve(3 * size_t(std::min(h.faces, rest / 2 + 1)));
  }
  const size_t need = h.normals ? 6 : 3;
  std::vector<uint32_t> polygon;
  uint64_t v = 0, f = 0, lineNo = h.bodyLine;
  size_t at = std::min(h.bodyOffset, bytes.size());
  for (; (v < h.vertices || f < h.faces) && at < bytes.size(); ++lineNo) {
    const char* start = bytes.data() + at;
    const char* newline = static_cast<const char*>(std::memchr(start, '\n', bytes.size() - at));
    const size_t length = newline ? size_t(newline - start) : bytes.size() - at;
    at += length + 1;
    const std::string_view line(start, length);
    const char* hash = static_cast<const char*>(std::memchr(start, '#', length));
    Words words(hash ? line.substr(0, size_t(hash - start)) : line);
    std::string_view word;
    if (!words.next(word)) continue;  // blank or a comment
    if (v < h.vertices) {
      // x y z, then nx ny nz for NOFF; colours and texture coordinates after them are not read.
      double x[6] = {};
      const char* needs =
          h.normals ? "3 finite coordinates and 3 normal components" : "3 finite coordinates";
      for (size_t k = 0; k < need; ++k) {
        if (k > 0 && !words.next(word))
          fail("{}:{}: vertex {} needs {}: '{}'", name, lineNo, v, needs, quoted(line));
        if (!parseNumber(word, x[k]))
          fail("{}:{}: vertex {} needs {}: '{}' is not a number: '{}'", name, lineNo, v, needs,
               quoted(word), quoted(line));
        // A normal that is not finite is replaced by its face's, as in every format.
        if (k < 3 && !std::isfinite(x[k]))
          fail("{}:{}: vertex {} needs {}: '{}' is not finite: '{}'", name, lineNo, v, needs,
               quoted(word), quoted(line));
      }
      if (out) {
        out->points.push_back({x[0], x[1], x[2]});
        if (h.normals) out->normals.push_back({x[3], x[4], x[5]});
      }
      ++v;
      continue;
    }
    // k i1 .. ik, then an optional colour that is not read.
    uint64_t k = 0;
    if (!parseIndex(word, k))
      fail("{}:{}: face {}: expected its vertex count, found '{}': '{}'", name, lineNo, f,
           quoted(word), quoted(line));
    polygon.clear();
    for (uint64_t j = 0; j < k; ++j) {
      if (!words.next(word))
        fail("{}:{}: face {}: expected {} vertex indices after its count, found {}: '{}'", name,
             lineNo, f, k, j, quoted(line));
      uint64_t index = 0;
      if (!parseIndex(word, index) || index >= h.vertices)
        fail("{}:{}: face {}: index '{}' is not a vertex (0 to {})", name, lineNo, f, quoted(word),
             h.vertices == 0 ? std::string("none: the file declares no vertices")
                             : std::to_string(h.vertices - 1));
      polygon.push_back(uint32_t(index));
    }
    if (k < 3) {
      // A point or a line: no surface (and a face of no vertex at all).
      ++body.droppedFaces;
      if (k == 0 && body.firstEmptyFaceLine == 0) body.firstEmptyFaceLine = lineNo;
    } else {
      body.triangles += k - 2;
      if (out) triangulate(polygon, out->points, out->corners);
    }
    ++f;
  }
  if (v < h.vertices || f < h.faces)
    fail(
        "{}: the OFF header declares {} vertices and {} faces, the file holds {} and {} (it ends "
        "at line {})",
        name, h.vertices, h.faces, v, f, lineNo - 1);
  return body;
}

OffMesh readOff(const std::string& name, std::string_view bytes) {
  OffMesh mesh;
  mesh.header = readOffHeader(name, bytes);
  mesh.body = readOffBody(name, bytes, mesh.header, &mesh);
  return mesh;
}

}  // namespace quadtri::mesh_check
