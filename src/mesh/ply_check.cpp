// PLY before Assimp reads it: the header, each declared count against the file's size, and
// then the body, element by element. Assimp's PLY importer trusts every list count it reads
// (ASCII or binary) and reserves that many values before it reads them: a count of 10^9 in a
// 2 KB file is 8 GB allocated and then a loop over a buffer that ran out (found by fuzz_ply).
// So every list count is checked here against the bytes left after it.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstring>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "mesh_check.h"
#include "quadtri/math/error.h"

namespace quadtri::mesh_check {
namespace {

// Reads one header line of at most `limit` bytes (without its '\n' or "\r\n"); false at the
// end of the file. A longer line is an error, so a header without line breaks allocates little.
bool readHeaderLine(std::istream& in, std::string& line, const std::string& name, long lineNo,
                    size_t limit = 4096) {
  line.clear();
  for (int c; (c = in.get()) != EOF;) {
    if (c == '\n') {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return true;
    }
    if (line.size() >= limit)
      fail("{}:{}: header line longer than {} bytes, expected a PLY header line", name, lineNo,
           limit);
    line.push_back(char(c));
  }
  return !line.empty();
}

struct PlyType {
  std::string_view name;
  uint8_t bytes;
  bool isSigned, isInteger;
};

constexpr PlyType kPlyTypes[] = {
    {"char", 1, true, true},    {"int8", 1, true, true},     {"uchar", 1, false, true},
    {"uint8", 1, false, true},  {"short", 2, true, true},    {"int16", 2, true, true},
    {"ushort", 2, false, true}, {"uint16", 2, false, true},  {"int", 4, true, true},
    {"int32", 4, true, true},   {"uint", 4, false, true},    {"uint32", 4, false, true},
    {"float", 4, true, false},  {"float32", 4, true, false}, {"double", 8, true, false},
    {"float64", 8, true, false}};

// The PLY scalar type of that name; nullptr when there is none.
const PlyType* plyType(std::string_view name) {
  for (const PlyType& t : kPlyTypes)
    if (t.name == name) return &t;
  return nullptr;
}

struct Property {
  std::string name;
  const PlyType* value = nullptr;
  const PlyType* count = nullptr;  // lists only
};

struct Element {
  std::string name;
  uint64_t count = 0, minBytes = 0;
  long line = 0;
  std::vector<Property> properties;
  bool hasList() const {
    return std::any_of(properties.begin(), properties.end(),
                       [](const Property& p) { return p.count != nullptr; });
  }
};

// Reads the body of a binary PLY in blocks, tracking how many bytes are left in the file.
class BinaryBody {
 public:
  BinaryBody(std::istream& in, uint64_t bytes) : in_(in), left_(bytes) {}
  uint64_t left() const { return left_ + (end_ - pos_); }
  /// Skips `n` bytes; false when fewer are left.
  bool skip(uint64_t n) {
    if (n > left()) return false;
    const uint64_t buffered = end_ - pos_;
    if (n <= buffered) {
      pos_ += size_t(n);
      return true;
    }
    n -= buffered;
    pos_ = end_ = 0;
    in_.seekg(std::streamoff(n), std::ios::cur);
    left_ -= n;
    return true;
  }
  /// Reads `n` ≤ 8 bytes; false when fewer are left.
  bool read(uint8_t* out, size_t n) {
    if (end_ - pos_ < n && !refill()) return false;
    if (end_ - pos_ < n) return false;
    std::memcpy(out, buffer_.data() + pos_, n);
    pos_ += n;
    return true;
  }

 private:
  bool refill() {
    const size_t kept = end_ - pos_;
    std::memmove(buffer_.data(), buffer_.data() + pos_, kept);
    const size_t want = size_t(std::min<uint64_t>(buffer_.size() - kept, left_));
    in_.read(reinterpret_cast<char*>(buffer_.data() + kept), std::streamsize(want));
    const size_t got = size_t(in_.gcount());
    left_ -= got;
    pos_ = 0;
    end_ = kept + got;
    return got > 0;
  }
  std::istream& in_;
  uint64_t left_;
  std::array<uint8_t, 1 << 16> buffer_{};
  size_t pos_ = 0, end_ = 0;
};

// A binary list count as a signed 64-bit value.
int64_t decodeCount(const uint8_t* b, const PlyType& t, bool bigEndian) {
  uint64_t u = 0;
  for (size_t k = 0; k < t.bytes; ++k) u |= uint64_t(b[bigEndian ? t.bytes - 1 - k : k]) << (8 * k);
  if (t.isSigned && t.bytes < 8 && (u >> (8 * t.bytes - 1)) != 0)
    u |= ~uint64_t(0) << (8 * t.bytes);
  return int64_t(u);
}

void checkBinaryBody(std::istream& in, uint64_t bodyBytes, const std::vector<Element>& elements,
                     bool bigEndian, const std::string& name) {
  BinaryBody body(in, bodyBytes);
  for (const Element& e : elements) {
    if (!e.hasList()) {
      // Fixed size: the header check has already compared it with the file.
      body.skip(mulAdd(e.count, e.minBytes));
      continue;
    }
    for (uint64_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        if (!p.count) {
          if (!body.skip(p.value->bytes))
            fail("{}: element '{}' {} of {}: the file ends in property '{}'", name, e.name, i,
                 e.count, p.name);
          continue;
        }
        std::array<uint8_t, 8> raw{};
        if (!body.read(raw.data(), p.count->bytes))
          fail("{}: element '{}' {} of {}: the file ends in the count of list '{}'", name, e.name,
               i, e.count, p.name);
        const int64_t n = decodeCount(raw.data(), *p.count, bigEndian);
        if (n < 0 || !body.skip(mulAdd(uint64_t(n), p.value->bytes)))
          fail(
              "{}: element '{}' {} of {}: list '{}' declares {} values of {} bytes; the file has "
              "{} bytes left",
              name, e.name, i, e.count, p.name, n, p.value->bytes, body.left());
      }
  }
}

// Whether an ASCII word is one whole value of type `t`, as Assimp must read it to stay in step
// with the line: an integer for integer types, any decimal number for float and double, with
// at most one sign. Assimp does not consume a word it cannot read, so one such word shifts every
// value after it, list counts included (fuzz_ply: a ",2.3" made a list count of a coordinate).
// It reads an unsigned type's digits only: "-5" in a uchar would leave the word to a signed
// list count after it, read as 4294967291 values, so a '-' is refused there (and a '+' is
// dropped from the text Assimp is given, checkAsciiBody). Of a "nan(...)"
// it reads the "nan", and the rest would shift the line the same way.
bool asciiValue(std::string_view word, const PlyType& t) {
  const auto sign = [](char c) { return c == '-' || c == '+'; };
  if (!word.empty() && sign(word[0]) &&
      ((t.isInteger && !t.isSigned && word[0] == '-') || word.size() == 1 || sign(word[1])))
    return false;
  if (!word.empty() && word[0] == '+') word.remove_prefix(1);
  const char* end = word.data() + word.size();
  if (t.isInteger) {
    int64_t i = 0;
    const auto [ptr, ec] = std::from_chars(word.data(), end, i);
    return ptr == end && (ec == std::errc() || ec == std::errc::result_out_of_range);
  }
  if (word.find('(') != std::string_view::npos) return false;
  double d = 0.0;
  const auto [ptr, ec] = std::from_chars(word.data(), end, d);
  return ptr == end && (ec == std::errc() || ec == std::errc::result_out_of_range);
}

// What asciiValue wants of a word of type `t`, for errors.
std::string_view expectedValue(const PlyType& t) {
  if (!t.isInteger) return "a number";
  return t.isSigned ? "an integer" : "an unsigned integer";
}

// Whether Assimp reads the whole of a float word: it reads the integer part, and the exponent,
// as 64-bit integers and, where one overflows, stops without consuming the word, so every value
// after it on the line reads the same digits again, a list count included (fuzz_ply: a
// 106-digit coordinate made a list count of billions; an exponent of 23 digits gave a uchar
// list count of 2·10^9). 19 digits never overflow; more may. (The fraction's digits past the
// 15th are skipped.)
bool assimpReadsFloat(std::string_view word) {
  const auto fits = [&](size_t i) {
    while (i < word.size() && word[i] == '0') ++i;
    size_t digits = 0;
    while (i + digits < word.size() && std::isdigit(static_cast<unsigned char>(word[i + digits])))
      ++digits;
    return digits <= 19;
  };
  const size_t start = word.find_first_not_of("+-");
  if (start == std::string_view::npos) return true;
  const size_t e = word.find_first_of("eE");
  return fits(start) && (e == std::string_view::npos || fits(word.find_first_not_of("+-", e + 1)));
}

// ASCII: one element per line, each line holding a value per scalar property and, per list,
// its count and that many values; blank lines are skipped, words past the last property ignored
// and properties past the line's last word absent (Blender 2.77 wrote a vertex list without
// values, assimp-testmodels' PLY/issue623.ply). With `out`, appends each element's line as
// Assimp is to be given it (see inspectPly): its values, an absent scalar as 0 and an absent list
// as the one 0 Assimp gives it, and a '\n'.
void checkAsciiBody(std::istream& in, long lineNo, const std::vector<Element>& elements,
                    const std::string& name, std::string* out) {
  std::string line;
  for (const Element& e : elements)
    for (uint64_t i = 0; i < e.count; ++i) {
      std::vector<std::string_view> w;
      do {
        if (!std::getline(in, line))
          fail("{}: the file ends at element '{}' {} of {}", name, e.name, i, e.count);
        ++lineNo;
        if (line.find('\0') != std::string::npos)
          fail("{}:{}: a NUL byte in an ASCII PLY file", name, lineNo);
        // Separators are spaces and tabs (a trailing \r ends the line).
        for (size_t j = 0; j < line.size(); ++j) {
          const auto c = static_cast<unsigned char>(line[j]);
          if ((c < 0x20 && c != '\t' && !(c == '\r' && j + 1 == line.size())) || c == 0x7f)
            fail("{}:{}: control character 0x{:02x} in an ASCII PLY element, expected numbers",
                 name, lineNo, c);
        }
        w = words(line);
      } while (w.empty());
      size_t k = 0;
      // An element without properties is left out of Assimp's text: it would read its entries'
      // lines as blank ones, of which it skips some (a later coordinate became a list count).
      std::string* const text = e.properties.empty() ? nullptr : out;
      const auto emit = [&](std::string_view word) {
        if (!text) return;
        if (!text->empty() && text->back() != '\n') text->push_back(' ');
        // Assimp reads an unsigned integer's digits only (asciiValue allows no '-' there).
        if (!word.empty() && word[0] == '+') word.remove_prefix(1);
        text->append(word);
      };
      for (const Property& p : e.properties) {
        if (k >= w.size()) {
          if (p.count) emit("1");
          emit("0");
          continue;
        }
        const auto checkFloat = [&](std::string_view word) {
          if (!p.value->isInteger && !assimpReadsFloat(word))
            fail(
                "{}:{}: element '{}' {}: property '{}' is '{}', a number whose integer part or "
                "exponent has more than 19 digits, which Assimp cannot read; expected at most 19",
                name, lineNo, e.name, i, p.name, word.substr(0, 40));
        };
        if (!p.count) {
          if (!asciiValue(w[k], *p.value))
            fail("{}:{}: element '{}' {}: property '{}' is '{}', expected {}", name, lineNo, e.name,
                 i, p.name, w[k], expectedValue(*p.value));
          checkFloat(w[k]);
          emit(w[k]);
          ++k;
          continue;
        }
        const std::optional<uint64_t> n = parseCount(w[k]);
        if (!n || *n > w.size() - k - 1)
          fail(
              "{}:{}: element '{}' {}: list '{}' has count '{}', expected an unsigned integer "
              "followed by that many values on the line",
              name, lineNo, e.name, i, p.name, w[k]);
        emit(w[k]);
        for (size_t j = k + 1; j <= k + size_t(*n); ++j) {
          if (!asciiValue(w[j], *p.value))
            fail("{}:{}: element '{}' {}: list '{}' holds '{}', expected {}", name, lineNo, e.name,
                 i, p.name, w[j], expectedValue(*p.value));
          checkFloat(w[j]);
          emit(w[j]);
        }
        k += 1 + size_t(*n);
      }
      if (text) text->push_back('\n');
    }
}

}  // namespace

MeshFileInfo inspectPly(const std::filesystem::path& path, std::string_view bytes,
                        std::string* assimpText) {
  const std::string name = path.string();
  const uint64_t fileBytes = bytes.size();
  MemoryStream in(bytes);
  std::vector<Element> elements;
  std::string line, format;
  long lineNo = 1;
  if (!readHeaderLine(in, line, name, lineNo) || words(line).size() != 1 || words(line)[0] != "ply")
    fail("{}:1: expected 'ply', the first line of a PLY file", name);
  bool ended = false;
  long objInfoLine = 0;  // an obj_info line since the last element's declaration
  while (!ended && readHeaderLine(in, line, name, ++lineNo)) {
    // The header is text; a NUL byte in it is no PLY header. Nor is another control character
    // but a tab: Assimp separates words by spaces and tabs only and ends a line at \f or NUL,
    // so "end_header\v..." ended the header here and not for Assimp, which then read on
    // without end (fuzz_ply).
    if (line.find('\0') != std::string::npos)
      fail("{}:{}: a NUL byte in the PLY header", name, lineNo);
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
        fail("{}:{}: control character 0x{:02x} in the PLY header, expected text", name, lineNo,
             static_cast<unsigned char>(c));
    const std::vector<std::string_view> w = words(line);
    if (w.empty() || w[0] == "comment") continue;
    if (w[0] == "obj_info") {
      // Assimp skips only 'comment' lines among an element's properties: an obj_info line
      // ends them, and it ignores the property lines after it (fuzz_ply: a list count read
      // from a coordinate, 8 GB reserved). A property after one is refused below.
      if (!elements.empty()) objInfoLine = lineNo;
      continue;
    }
    if (format.empty() && (w[0] == "element" || w[0] == "property"))
      fail("{}:{}: expected the 'format' line before '{}'", name, lineNo, w[0]);
    if (w[0] == "format") {
      // Among an element's properties a format line ends them for Assimp, as obj_info does.
      if (!elements.empty())
        fail("{}:{}: a 'format' line after element '{}', expected it before the first element",
             name, lineNo, elements.back().name);
      if (w.size() != 3 ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
        fail("{}:{}: '{}': expected 'format ascii|binary_little_endian|binary_big_endian 1.0'",
             name, lineNo, line);
      if (!format.empty() && format != w[1])
        fail("{}:{}: a second 'format' line says {}, the first said {}", name, lineNo, w[1],
             format);
      format = std::string(w[1]);
    } else if (w[0] == "element") {
      if (w.size() != 3) fail("{}:{}: '{}': expected 'element NAME COUNT'", name, lineNo, line);
      // Assimp's PLY importer reads the digits that begin an element name it does not know as
      // the element's count (fuzz_ply: 'element 777...777vertexl 3' became a 45 GB allocation).
      if (std::isdigit(static_cast<unsigned char>(w[1][0])))
        fail("{}:{}: element name '{}' begins with a digit, expected a word", name, lineNo, w[1]);
      const std::optional<uint64_t> count = parseCount(w[2]);
      if (!count)
        fail("{}:{}: element {}'s count '{}' is not an unsigned integer", name, lineNo, w[1], w[2]);
      // Assimp's PLY importer frees what it did not allocate when an element repeats
      // (found by fuzz_ply).
      for (const Element& e : elements)
        if (e.name == w[1])
          fail("{}:{}: element '{}' is declared again (first on line {})", name, lineNo, w[1],
               e.line);
      elements.push_back({std::string(w[1]), *count, 0, lineNo, {}});
      objInfoLine = 0;
    } else if (w[0] == "property") {
      if (elements.empty())
        fail("{}:{}: property before any element, expected 'element NAME COUNT' first", name,
             lineNo);
      if (objInfoLine != 0)
        fail(
            "{}:{}: property of element '{}' after the obj_info line {}: expected its properties "
            "together, obj_info lines before the first element or between elements",
            name, lineNo, elements.back().name, objInfoLine);
      const bool list = w.size() >= 2 && w[1] == "list";
      if ((list && w.size() != 5) || (!list && w.size() != 3))
        fail(
            "{}:{}: '{}': expected 'property TYPE NAME' or 'property list COUNT_TYPE "
            "INDEX_TYPE NAME'",
            name, lineNo, line);
      Property p;
      p.name = std::string(w.back());
      for (size_t k = list ? 2 : 1; k + 1 < w.size(); ++k)
        if (!plyType(w[k]))
          fail(
              "{}:{}: property type '{}' is not a PLY type, expected char, uchar, short, "
              "ushort, int, uint, float, double or int8 ... float64",
              name, lineNo, w[k]);
      p.value = plyType(w[list ? 3 : 1]);
      if (list) {
        p.count = plyType(w[2]);
        if (!p.count->isInteger)
          fail("{}:{}: list '{}' has count type '{}', expected an integer type", name, lineNo,
               p.name, w[2]);
      }
      // ASCII: a value is at least a digit and a separator; a list at least its count.
      // Binary: a scalar's size; a list at least its count (it may be empty).
      Element& e = elements.back();
      e.minBytes += format == "ascii" ? 2 : (list ? p.count : p.value)->bytes;
      e.properties.push_back(std::move(p));
    } else if (w[0] == "end_header") {
      ended = true;
    } else if (!elements.empty()) {
      // Assimp ends an element's properties at such a line and skips the properties after it,
      // so it would read the body with another layout than the one checked here (fuzz_ply).
      fail("{}:{}: '{}': expected 'property', 'element', 'comment' or 'end_header'", name, lineNo,
           line);
    }
    // Before the first element, any other line declares nothing and Assimp skips it too
    // (Blender 2.47 wrote a bare comment there, assimp-testmodels' PLY/Wuson.ply).
  }
  if (!ended) fail("{}: the PLY header has no 'end_header' line", name);
  // Assimp's PLY importer reads an element whose name it does not know as holding as many
  // entries as the digits its name begins with (none here: 0), whatever its count says, so an
  // element of another name that holds data shifts every element after it (fuzz_ply: a face
  // list count read from a coordinate, 2 GB reserved). Such elements may only follow the ones
  // Assimp reads.
  const auto assimpKnows = [](const Element& e) {
    return e.name == "vertex" || e.name == "face" || e.name == "tristrips" || e.name == "edge" ||
           e.name == "material";
  };
  for (size_t i = 0; i < elements.size(); ++i) {
    const Element& e = elements[i];
    if (assimpKnows(e) || e.count == 0 || e.minBytes == 0) continue;
    for (size_t j = i + 1; j < elements.size(); ++j)
      if (assimpKnows(elements[j]) && elements[j].count > 0)
        fail(
            "{}:{}: element '{}' holds {} entries before element '{}' (line {}): Assimp reads "
            "vertex, face, tristrips, edge and material elements and takes any other as empty, "
            "which would shift the ones after it; expected other elements after those",
            name, e.line, e.name, e.count, elements[j].name, elements[j].line);
  }
  const uint64_t headerBytes = uint64_t(in.tellg());
  const uint64_t body = fileBytes - std::min(fileBytes, headerBytes);
  uint64_t need = 0;
  for (const Element& e : elements) need = mulAdd(e.count, e.minBytes, need);
  // ASCII's last value may end without its separator.
  const uint64_t slack = format == "ascii" && need > 0 ? 1 : 0;
  if (need - slack > body) {
    std::string what;
    for (const Element& e : elements)
      what +=
          fmt::format("{}{} {} × {} bytes", what.empty() ? "" : ", ", e.count, e.name, e.minBytes);
    fail(
        "{}: the PLY header ({}) declares elements that take at least {} bytes ({}); the "
        "file has {} bytes after its header",
        name, format, need, what, body);
  }
  MeshFileInfo info;
  info.format = "PLY " + format;
  info.fileBytes = fileBytes;
  for (const Element& e : elements) {
    checkAssimpCount(name, info.format, e.count, "'" + e.name + "' elements");
    if (e.name == "vertex")
      info.vertices += e.count;
    else if (e.name == "face")
      info.faces += e.count;
    else
      info.otherElements += e.count;
  }
  std::string* text = format == "ascii" ? assimpText : nullptr;
  if (text) {
    text->clear();
    text->reserve(bytes.size() + 64);
    text->append("ply\nformat ascii 1.0\n");
    for (const Element& e : elements) {
      if (e.properties.empty()) continue;  // and its lines (checkAsciiBody)
      fmt::format_to(std::back_inserter(*text), "element {} {}\n", e.name, e.count);
      for (const Property& p : e.properties)
        if (p.count)
          fmt::format_to(std::back_inserter(*text), "property list {} {} {}\n", p.count->name,
                         p.value->name, p.name);
        else
          fmt::format_to(std::back_inserter(*text), "property {} {}\n", p.value->name, p.name);
    }
    text->append("end_header\n");
  }
  if (format == "ascii")
    checkAsciiBody(in, lineNo, elements, name, text);
  else
    checkBinaryBody(in, body, elements, format == "binary_big_endian", name);
  info.corners = 3 * info.faces;
  info.triangles = info.faces;
  return info;
}

}  // namespace quadtri::mesh_check
