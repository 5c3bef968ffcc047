#include "quadtri/surface/patch_table.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <fstream>
#include <limits>
#include <span>
#include <string_view>

#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {
namespace {

using Kind = RecordField::Kind;

using Ref = PatchRecord::Ref;
using Type = PatchRecord::Type;
constexpr Ref kNone = PatchRecord::kNone;

Kind numberKind(const PatchRecord& r, Ref v) {
  if (r.type(v) == Type::Bool) return Kind::Bool;
  if (r.type(v) == Type::Int) return Kind::Int;
  return Kind::Float;
}

Kind mergeKind(Kind a, Kind b) {
  if (a == Kind::Unknown) return b;
  if (b == Kind::Unknown || a == b) return a;
  return Kind::Float;  // int and float (or bool) mixed
}

// The leaf shape of one value, its list dimensions and number kind, found without allocating
// (a layout sees every record's every field).
struct LeafShape {
  static constexpr int kMaxDims = 8;
  std::array<int64_t, kMaxDims> dims{};
  int ndim = 0;
  Kind kind = Kind::Unknown;
  bool unknownInner = false;  // only empty lists at the innermost level seen
  std::span<const int64_t> list() const { return {dims.data(), size_t(ndim)}; }
};

Kind scalarKind(const PatchRecord& r, Ref v) {
  return r.type(v) == Type::Null ? Kind::Float : numberKind(r, v);
}

void shapeOf(const PatchRecord& r, Ref v, std::string_view key, LeafShape& s) {
  s.unknownInner = false;
  if (r.type(v) != Type::Array) {
    s.ndim = 0;
    s.kind = scalarKind(r, v);
    return;
  }
  s.ndim = 1;
  s.dims[0] = int64_t(r.size(v));
  if (r.size(v) == 0) {
    s.kind = Kind::Unknown;
    s.unknownInner = true;
    return;
  }
  // A list of numbers, the common case, without recursing.
  if (r.type(r.first(v)) != Type::Array) {
    s.kind = Kind::Unknown;
    for (Ref e = r.first(v); e != kNone; e = r.next(e)) {
      if (r.type(e) == Type::Array) fail("patch JSON '{}': not a rectangular list of numbers", key);
      s.kind = mergeKind(s.kind, scalarKind(r, e));
    }
    return;
  }
  LeafShape inner, other;
  shapeOf(r, r.first(v), key, inner);
  for (Ref e = r.next(r.first(v)); e != kNone; e = r.next(e)) {
    shapeOf(r, e, key, other);
    if (!std::ranges::equal(other.list(), inner.list()) || other.unknownInner != inner.unknownInner)
      fail("patch JSON '{}': not a rectangular list of numbers", key);
    inner.kind = mergeKind(inner.kind, other.kind);
  }
  if (inner.ndim + 1 > LeafShape::kMaxDims)
    fail("patch JSON '{}': lists nested more than {} deep", key, LeafShape::kMaxDims);
  s.dims[0] = int64_t(r.size(v));
  std::copy_n(inner.dims.begin(), inner.ndim, s.dims.begin() + 1);
  s.ndim = inner.ndim + 1;
  s.kind = inner.kind;
  s.unknownInner = inner.unknownInner;
}

void merge(RecordField& into, const PatchRecord& r, Ref v, std::string_view key, bool& sawNull);

void mergeObject(RecordField& into, const PatchRecord& r, Ref object, bool& sawNull) {
  into.kind = Kind::Object;
  into.present = true;
  // Records usually list the keys in the order the layout has them: try the next one first.
  size_t next = 0;
  for (Ref entry = r.first(object); entry != kNone; entry = r.next(entry)) {
    const std::string_view k = r.key(entry);
    const auto it = next < into.children.size() && into.children[next].name == k
                        ? into.children.begin() + std::ptrdiff_t(next)
                        : std::find_if(into.children.begin(), into.children.end(),
                                       [&](const RecordField& c) { return c.name == k; });
    const size_t i = size_t(it - into.children.begin());
    next = i + 1;
    if (it == into.children.end()) {
      into.children.emplace_back();
      into.children.back().name = k;
    }
    merge(into.children[i], r, entry, k, sawNull);
  }
}

// Merges the shape of a leaf (a number or list, present: its dims, kind, whether only empty
// lists were seen innermost, whether its length already varied) into a present leaf `into`.
// The shape may stand for one record or for several (a part's layout): the result is the same
// either way.
void mergeLeaf(RecordField& into, std::span<const int64_t> dims, Kind kind, bool unknownInner,
               bool variable, std::string_view key) {
  if (into.dims.empty() != dims.empty())
    fail("patch JSON '{}': a number in one record, a list in another", key);
  into.kind = mergeKind(into.kind, kind);
  if (dims.empty()) return;
  // Variable: not every record's list has the same length.
  if (into.dims[0] != dims[0] || variable) into.variable = true;
  const int64_t outer = std::max(into.dims[0], dims[0]);
  if (into.unknownInner) {
    into.dims.assign(dims.begin(), dims.end());
    into.unknownInner = unknownInner;
  } else if (!unknownInner &&
             !std::ranges::equal(std::span<const int64_t>(into.dims).subspan(1), dims.subspan(1))) {
    fail("patch JSON '{}': lists of different shapes in different records", key);
  }
  into.dims[0] = outer;
}

void merge(RecordField& into, const PatchRecord& r, Ref v, std::string_view key, bool& sawNull) {
  if (r.type(v) == Type::Object) {
    if (into.present && into.kind != Kind::Object)
      fail("patch JSON '{}': an object in one record, a number or list in another", key);
    mergeObject(into, r, v, sawNull);
    return;
  }
  if (into.kind == Kind::Object)
    fail("patch JSON '{}': an object in one record, a number or list in another", key);
  const bool null = r.type(v) == Type::Null;
  if (null) sawNull = true;
  if (null && into.present) return;
  LeafShape leaf;
  shapeOf(r, v, key, leaf);
  if (!into.present) {
    into.present = true;
    into.kind = leaf.kind;
    into.dims.assign(leaf.list().begin(), leaf.list().end());
    into.unknownInner = leaf.unknownInner;
    return;
  }
  mergeLeaf(into, leaf.list(), leaf.kind, leaf.unknownInner, false, key);
}

// The fields of a layout of later records merged into `into` (RecordLayout::merge).
void mergeFields(RecordField& into, const RecordField& later) {
  if (!later.present) return;
  if (!into.present) {
    const std::string name = into.name;
    into = later;
    into.name = name;
    return;
  }
  if ((into.kind == Kind::Object) != (later.kind == Kind::Object))
    fail("patch JSON '{}': an object in one record, a number or list in another", later.name);
  if (into.kind != Kind::Object)
    return mergeLeaf(into, later.dims, later.kind, later.unknownInner, later.variable, later.name);
  for (const RecordField& child : later.children) {
    const auto it = std::find_if(into.children.begin(), into.children.end(),
                                 [&](const RecordField& c) { return c.name == child.name; });
    if (it == into.children.end())
      into.children.push_back(child);
    else
      mergeFields(*it, child);
  }
}

size_t valueBytes(const RecordField& f) {
  size_t count = 1;
  for (int64_t d : f.dims) count *= size_t(d);
  return count * (f.kind == Kind::Bool ? 1 : 8);
}

// Fixed shapes (fix: as records were merged), then byte offsets, packed.
size_t layout(RecordField& node, size_t offset, bool fix) {
  node.offset = offset;
  if (node.kind == Kind::Object) {
    size_t at = offset;
    for (RecordField& child : node.children) at = layout(child, at, fix);
    return at;
  }
  if (fix) {
    if (node.name == "planes" && !node.dims.empty()) {
      node.dims = {QuadricPatch::kMaxPlanes, 4};
      node.unknownInner = false;
      node.variable = true;
      node.kind = Kind::Float;
    }
    node.unknownInner = false;  // every list empty: shape (0,)
    if (node.kind == Kind::Unknown) node.kind = Kind::Float;
  }
  size_t at = offset + valueBytes(node);
  if (node.variable) {
    node.countOffset = at;
    at += 8;
  }
  return at;
}

void writeNumber(const RecordField& node, const PatchRecord& r, Ref v, char* at) {
  const bool number = r.isNumber(v), boolean = r.type(v) == Type::Bool;
  if (node.kind == Kind::Bool) {
    const bool b = boolean ? r.boolean(v) : (number && r.number(v) != 0.0);
    std::memcpy(at, &b, 1);
  } else if (node.kind == Kind::Int) {
    const int64_t i = number ? r.integer(v) : 0;
    std::memcpy(at, &i, 8);
  } else {
    const double d = number || boolean ? r.number(v) : std::numeric_limits<double>::quiet_NaN();
    std::memcpy(at, &d, 8);
  }
}

void writeList(const RecordField& node, const PatchRecord& r, Ref v, size_t level, char* at) {
  if (level == node.dims.size() || r.type(v) != Type::Array) {
    if (level == node.dims.size()) writeNumber(node, r, v, at);
    return;
  }
  size_t stride = node.kind == Kind::Bool ? 1 : 8;
  for (size_t l = level + 1; l < node.dims.size(); ++l) stride *= size_t(node.dims[l]);
  const size_t n = std::min(r.size(v), size_t(node.dims[level]));
  Ref e = r.first(v);
  for (size_t i = 0; i < n; ++i, e = r.next(e)) writeList(node, r, e, level + 1, at + i * stride);
}

void fillField(const RecordField& node, const PatchRecord& r, Ref v, char* base) {
  if (node.kind == Kind::Object) {
    const bool object = v != kNone && r.type(v) == Type::Object;
    // The record's members usually come in the layout's order: try the next one first.
    Ref expected = object ? r.first(v) : kNone;
    for (const RecordField& child : node.children) {
      Ref member = kNone;
      if (expected != kNone && r.key(expected) == child.name)
        member = expected;
      else if (object)
        member = r.find(v, child.name);
      expected = member != kNone ? r.next(member) : kNone;
      fillField(child, r, member, base);
    }
    return;
  }
  char* at = base + node.offset;
  if (v == kNone || r.type(v) == Type::Null) {
    if (node.kind == Kind::Float && !node.variable) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      for (size_t i = 0; i < valueBytes(node) / 8; ++i) std::memcpy(at + 8 * i, &nan, 8);
    }
    return;
  }
  writeList(node, r, v, 0, at);
  if (node.variable) {
    const int64_t count =
        r.type(v) == Type::Array ? int64_t(std::min(r.size(v), size_t(node.dims[0]))) : 0;
    std::memcpy(base + node.countOffset, &count, 8);
  }
}

}  // namespace

void RecordLayout::add(const PatchRecord& record) {
  mergeObject(root_, record, PatchRecord::kRoot, sawNull_);
}

void RecordLayout::add(const nlohmann::json& record) {
  add(PatchRecord::fromJson(record));
}

void RecordLayout::merge(const RecordLayout& later) {
  mergeFields(root_, later.root_);
  sawNull_ |= later.sawNull_;
}

void RecordLayout::finish() {
  root_.kind = Kind::Object;
  itemSize_ = layout(root_, 0, true);
}

void RecordLayout::fill(const PatchRecord& record, char* out) const {
  std::memset(out, 0, itemSize_);
  fillField(root_, record, PatchRecord::kRoot, out);
}

void RecordLayout::fill(const nlohmann::json& record, char* out) const {
  fill(PatchRecord::fromJson(record), out);
}

RecordLayout RecordLayout::fromFields(RecordField root) {
  RecordLayout l;
  l.root_ = std::move(root);
  l.itemSize_ = layout(l.root_, 0, false);
  return l;
}

const nlohmann::json& emptyBridgeRecord() {
  static const nlohmann::json empty = {
      {"joins", {0, 0}},
      {"plane", {0.0, 0.0, 0.0, 0.0}},
      {"planes", nlohmann::json::array()},
      {"bounds", {{"min", {0.0, 0.0, 0.0}}, {"max", {0.0, 0.0, 0.0}}}}};
  return empty;
}

}  // namespace quadtri

namespace quadtri {
namespace {

constexpr char kMagic[8] = {'Q', 'T', 'P', 'A', 'T', 'C', 'H', '\0'};
constexpr uint32_t kVersion = 1;
constexpr size_t kFixedHeader = 48;
constexpr uint32_t kMaxName = 256, kMaxDims = 8, kMaxFields = 4096, kMaxDepth = 8;
constexpr uint64_t kMaxDim = uint64_t(1) << 20, kMaxHeader = uint64_t(1) << 24;

static_assert(std::endian::native == std::endian::little,
              "the patch table is written and read as the host lays out numbers");

template <typename T>
void put(std::string& out, T value) {
  const size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

void putText(std::string& out, std::string_view text) {
  put(out, uint32_t(text.size()));
  out.append(text);
}

void putFields(std::string& out, const RecordField& node) {
  put(out, uint32_t(node.children.size()));
  for (const RecordField& f : node.children) {
    putText(out, f.name);
    put(out, uint8_t(f.kind));
    put(out, uint8_t(f.variable ? 1 : 0));
    put(out, uint8_t(f.dims.size()));
    put(out, uint8_t(0));
    for (int64_t d : f.dims) put(out, uint32_t(d));
    if (f.kind == RecordField::Kind::Object) putFields(out, f);
  }
}

// Reads the header's bytes, naming the file and the offset of anything wrong.
class Cursor {
 public:
  Cursor(std::string name, std::string_view bytes) : name_(std::move(name)), bytes_(bytes) {}
  size_t offset() const { return pos_; }
  template <typename T>
  T get(std::string_view what) {
    need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  std::string text(std::string_view what, uint32_t limit) {
    const size_t at = pos_;
    const uint32_t n = get<uint32_t>(what);
    if (n > limit) bad(at, "{} of {} bytes, expected at most {}", what, n, limit);
    need(n, what);
    std::string s(bytes_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  template <typename... Args>
  [[noreturn]] void bad(size_t at, fmt::format_string<Args...> format, Args&&... args) const {
    fail("{}: offset {}: {}", name_, at, fmt::format(format, std::forward<Args>(args)...));
  }

 private:
  void need(size_t n, std::string_view what) const {
    if (bytes_.size() - pos_ < n)
      bad(pos_, "the header ends in {} (a header of {} bytes)", what, bytes_.size());
  }
  std::string name_;
  std::string_view bytes_;
  size_t pos_ = 0;
};

void getFields(Cursor& in, RecordField& node, uint32_t depth, uint32_t& total) {
  const size_t at = in.offset();
  const uint32_t count = in.get<uint32_t>("a field count");
  total += count;
  if (total > kMaxFields) in.bad(at, "{} fields, expected at most {}", total, kMaxFields);
  for (uint32_t i = 0; i < count; ++i) {
    const size_t fieldAt = in.offset();
    RecordField f;
    f.name = in.text("a field name", kMaxName);
    const uint8_t kind = in.get<uint8_t>("a field kind");
    const uint8_t variable = in.get<uint8_t>("a field's variable flag");
    const uint8_t ndim = in.get<uint8_t>("a field's dimension count");
    in.get<uint8_t>("a field's padding");
    if (kind > uint8_t(RecordField::Kind::Object) || variable > 1 || ndim > kMaxDims)
      in.bad(fieldAt,
             "field '{}': kind {}, variable {}, {} dimensions; expected kind 0 to 3 (bool, "
             "int64, float64, nested), variable 0 or 1 and at most {} dimensions",
             f.name, kind, variable, ndim, kMaxDims);
    f.kind = RecordField::Kind(kind);
    f.variable = variable == 1;
    uint64_t values = 1;
    for (uint8_t d = 0; d < ndim; ++d) {
      const uint32_t dim = in.get<uint32_t>("a field's dimensions");
      values *= std::max<uint64_t>(dim, 1);
      if (dim > kMaxDim || values > kMaxDim)
        in.bad(fieldAt, "field '{}': dimensions over {} values", f.name, kMaxDim);
      f.dims.push_back(dim);
    }
    if (f.kind == RecordField::Kind::Object) {
      if (ndim != 0 || f.variable)
        in.bad(fieldAt, "field '{}': a nested record with dimensions or a count", f.name);
      if (depth + 1 > kMaxDepth) in.bad(fieldAt, "fields nested deeper than {}", kMaxDepth);
      getFields(in, f, depth + 1, total);
    } else if (f.variable && ndim == 0) {
      in.bad(fieldAt, "field '{}': a count without a list", f.name);
    }
    node.children.push_back(std::move(f));
  }
}

uint64_t mulAdd(uint64_t a, uint64_t b, uint64_t c) {
  constexpr uint64_t kMax = std::numeric_limits<uint64_t>::max();
  if (a != 0 && b > (kMax - c) / a) return kMax;
  return a * b + c;
}

}  // namespace

std::string patchTableHeader(const PatchTableInfo& info, const RecordLayout& patches,
                             const RecordLayout& bridges) {
  std::string out(kMagic, sizeof(kMagic));
  put(out, kVersion);
  put(out, uint32_t(0));  // the header's size, set below
  put(out, info.triangles);
  put(out, info.patchCount);
  put(out, info.bridgeCount);
  put(out, uint32_t(patches.itemSize()));
  put(out, uint32_t(bridges.itemSize()));
  putText(out, info.model);
  putText(out, info.tessellation);
  putFields(out, patches.root());
  putFields(out, bridges.root());
  out.resize((out.size() + 7) / 8 * 8, '\0');
  const uint32_t size = uint32_t(out.size());
  std::memcpy(out.data() + 12, &size, sizeof(size));
  return out;
}

PatchTable readPatchTable(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const uint64_t fileBytes = std::filesystem::file_size(path, ec);
  if (ec) fail("{}: cannot read the file's size ({})", name, ec.message());
  std::ifstream file(path, std::ios::binary);
  if (!file) fail("{}: cannot open file", name);
  if (fileBytes < kFixedHeader)
    fail("{}: {} bytes, expected a quadtri patch table (.qtp) of at least {} bytes", name,
         fileBytes, kFixedHeader);
  std::string head(kFixedHeader, '\0');
  file.read(head.data(), std::streamsize(head.size()));
  if (head.compare(0, sizeof(kMagic), kMagic, sizeof(kMagic)) != 0)
    fail("{}: offset 0: not a quadtri patch table (expected the magic \"QTPATCH\" and a NUL)",
         name);
  uint32_t version = 0, headerBytes = 0;
  std::memcpy(&version, head.data() + 8, 4);
  std::memcpy(&headerBytes, head.data() + 12, 4);
  if (version != kVersion)
    fail("{}: offset 8: version {}, this reader reads version {}", name, version, kVersion);
  if (headerBytes < kFixedHeader || headerBytes > std::min(fileBytes, kMaxHeader) ||
      headerBytes % 8 != 0)
    fail(
        "{}: offset 12: a header of {} bytes, expected a multiple of 8 from {} to the file's "
        "{} bytes",
        name, headerBytes, kFixedHeader, fileBytes);
  head.resize(headerBytes);
  file.read(head.data() + kFixedHeader, std::streamsize(headerBytes - kFixedHeader));
  if (!file) fail("{}: cannot read its header", name);
  Cursor in(name, head);
  in.get<uint64_t>("the magic");
  in.get<uint32_t>("the version");
  in.get<uint32_t>("the header size");
  PatchTable table;
  table.triangles = in.get<uint64_t>("the triangle count");
  table.patchCount = in.get<uint64_t>("the patch count");
  table.bridgeCount = in.get<uint64_t>("the bridge count");
  const uint32_t patchBytes = in.get<uint32_t>("the patch record size");
  const uint32_t bridgeBytes = in.get<uint32_t>("the bridge record size");
  table.model = in.text("the model name", kMaxName);
  table.tessellation = in.text("the tessellation", kMaxName);
  RecordField patchRoot = RecordField::record(), bridgeRoot = RecordField::record();
  uint32_t fields = 0;
  const size_t patchFieldsAt = in.offset();
  getFields(in, patchRoot, 0, fields);
  const size_t bridgeFieldsAt = in.offset();
  getFields(in, bridgeRoot, 0, fields);
  table.patchLayout = RecordLayout::fromFields(std::move(patchRoot));
  table.bridgeLayout = RecordLayout::fromFields(std::move(bridgeRoot));
  if (table.patchLayout.itemSize() != patchBytes)
    fail("{}: offset 40: patch records of {} bytes, but the fields at offset {} take {}", name,
         patchBytes, patchFieldsAt, table.patchLayout.itemSize());
  if (table.bridgeLayout.itemSize() != bridgeBytes)
    fail("{}: offset 44: bridge records of {} bytes, but the fields at offset {} take {}", name,
         bridgeBytes, bridgeFieldsAt, table.bridgeLayout.itemSize());
  const uint64_t expected =
      mulAdd(table.bridgeCount, bridgeBytes, mulAdd(table.patchCount, patchBytes, headerBytes));
  if (expected != fileBytes)
    fail(
        "{}: offset {}: the header declares {} patches of {} bytes and {} bridges of {} bytes "
        "after its {} bytes, {} bytes in all; the file has {}",
        name, std::min(expected, fileBytes), table.patchCount, patchBytes, table.bridgeCount,
        bridgeBytes, headerBytes, expected, fileBytes);
  table.patches.resize(size_t(table.patchCount * patchBytes));
  table.bridges.resize(size_t(table.bridgeCount * bridgeBytes));
  file.read(table.patches.data(), std::streamsize(table.patches.size()));
  file.read(table.bridges.data(), std::streamsize(table.bridges.size()));
  if (!file) fail("{}: cannot read its records", name);
  return table;
}

}  // namespace quadtri
