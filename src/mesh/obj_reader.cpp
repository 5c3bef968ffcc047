// The native reader of plain OBJ files (mesh_check.h, readPlainObj). Assimp's OBJ importer
// spends most of a large file's load: its parser, one vertex per corner and then its
// post-processing copies. For the files that hold only vertices, normals and triangles, this
// reader gives the mesh that importer gives, its numbers taken as Assimp's parser takes them but
// kept as the nearest doubles, and leaves every other file to Assimp.
#include <assimp/fast_atof.h>

#include <array>
#include <charconv>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mesh_check.h"

namespace quadtri::mesh_check {
namespace {

// Splits at spaces and tabs (what Assimp's OBJ parser separates values by).
size_t splitTokens(std::string_view rest, std::array<std::string_view, 4>& out) {
  size_t n = 0, i = 0;
  while (i < rest.size()) {
    while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t')) ++i;
    const size_t start = i;
    while (i < rest.size() && rest[i] != ' ' && rest[i] != '\t') ++i;
    if (i > start) {
      if (n == out.size()) return n + 1;  // more than this reader takes
      out[n++] = rest.substr(start, i - start);
    }
  }
  return n;
}

// What Assimp's number parser throws here (its own exception type is not exported).
struct NotANumber {
  template <typename... Text>
  explicit NotANumber(Text&&...) {}
};

// A number of the syntax Assimp's OBJ importer takes, as the nearest double (Assimp's parser
// would give a float, and its own sums of the digits may be off by more than rounding); nullopt
// unless Assimp's parser takes the whole token.
std::optional<double> number(std::string_view token) {
  std::string_view digits = token;
  if (digits.size() > 1 && digits[0] == '+') digits.remove_prefix(1);
  double value = 0;
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
  // The common case: a decimal number both parsers take whole (the file's lines were checked
  // to hold finite numbers, validateObj), read once.
  if (ptr == end && ec == std::errc()) return value;
  // Otherwise Assimp's parser decides whether the token is a number at all.
  double assimp = 0;
  try {
    const char* stop = Assimp::fast_atoreal_move<double, NotANumber>(token.data(), assimp);
    if (stop != token.data() + token.size()) return std::nullopt;
  } catch (const NotANumber&) {
    return std::nullopt;
  }
  if (ptr == end && ec == std::errc::result_out_of_range)
    return std::strtod(std::string(digits).c_str(), nullptr);  // 0, a denormal or infinite
  return assimp;  // a form from_chars does not take whole ("1.e5" is one Assimp takes)
}

// A 1-based or negative (relative) index among `count` elements, 0-based; nullopt when invalid.
std::optional<size_t> objIndex(std::string_view text, size_t count) {
  long index = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, index);
  if (ec != std::errc() || ptr != end || index == 0) return std::nullopt;
  const long resolved = index > 0 ? index - 1 : long(count) + index;
  if (resolved < 0 || size_t(resolved) >= count) return std::nullopt;
  return size_t(resolved);
}

}  // namespace

std::optional<ObjCorners> readPlainObj(std::string_view text) {
  ObjCorners out;
  std::vector<Point3>& v = out.points;
  std::vector<Point3>& vn = out.normals;
  int withNormals = -1;  // unknown until the first face; then 0 or 1 for every face
  std::array<std::string_view, 4> tokens;
  size_t next = 0;
  while (next < text.size()) {
    const size_t newline = std::min(text.find('\n', next), text.size());
    std::string_view line = text.substr(next, newline - next);
    next = newline + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    // A comment runs from '#' to the end of the line, after values too (as the check reads it).
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) {
      line = line.substr(0, hash);
      while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    }
    if (line.empty()) continue;
    // Other control characters and indented lines: left to Assimp.
    for (const char c : line)
      if (c == '\r' || c == '\v' || c == '\f' || c == '\0') return std::nullopt;
    if (line[0] == ' ' || line[0] == '\t') {
      if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
      return std::nullopt;
    }
    const size_t keyEnd = std::min(line.find_first_of(" \t"), line.size());
    const std::string_view key = line.substr(0, keyEnd);
    const size_t n = splitTokens(line.substr(keyEnd), tokens);
    // Assimp counts a number that starts with '.' as no value, and then drops the whole line.
    if (key == "v" || key == "vn" || key == "vt")
      for (size_t k = 0; k < std::min(n, tokens.size()); ++k)
        if (tokens[k][0] == '.') return std::nullopt;
    if (key == "v" || key == "vn") {
      if (n != 3) return std::nullopt;
      Point3 p;
      for (size_t k = 0; k < 3; ++k) {
        const std::optional<double> x = number(tokens[k]);
        if (!x) return std::nullopt;
        p[k] = *x;
      }
      (key == "v" ? v : vn).push_back(p);
    } else if (key == "f") {
      if (n != 3) return std::nullopt;
      for (int k = 0; k < 3; ++k) {
        // i, i/j, i//k or i/j/k; texture coordinates are not kept.
        const std::string_view corner = tokens[k];
        const size_t slash1 = corner.find('/');
        const size_t slash2 =
            slash1 == std::string_view::npos ? slash1 : corner.find('/', slash1 + 1);
        const std::optional<size_t> vi = objIndex(corner.substr(0, slash1), v.size());
        if (!vi) return std::nullopt;
        const int has = slash2 != std::string_view::npos ? 1 : 0;
        if (withNormals != -1 && withNormals != has) return std::nullopt;
        withNormals = has;
        out.pointOf.push_back(uint32_t(*vi));
        if (has) {
          const std::optional<size_t> ni = objIndex(corner.substr(slash2 + 1), vn.size());
          if (!ni) return std::nullopt;
          out.normalOf.push_back(uint32_t(*ni));
        }
      }
    } else if (key != "vt" && key != "s") {
      return std::nullopt;  // objects, groups, materials, lines, points, ...: Assimp's
    }
  }
  // More than 32-bit indices can count: Assimp's to refuse.
  if (out.pointOf.empty() || out.points.size() > std::numeric_limits<uint32_t>::max() ||
      out.normals.size() > std::numeric_limits<uint32_t>::max())
    return std::nullopt;
  return out;
}

}  // namespace quadtri::mesh_check
