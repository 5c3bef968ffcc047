#include "quadtri/surface/patch_table.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>

#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {
namespace {

using Kind = RecordField::Kind;

Kind numberKind(const nlohmann::json& v) {
  if (v.is_boolean()) return Kind::Bool;
  if (v.is_number_integer()) return Kind::Int;
  return Kind::Float;
}

Kind mergeKind(Kind a, Kind b) {
  if (a == Kind::Unknown) return b;
  if (b == Kind::Unknown || a == b) return a;
  return Kind::Float;  // int and float (or bool) mixed
}

// The leaf shape of one value: its list dimensions and number kind.
RecordField leafOf(const nlohmann::json& v, const std::string& key) {
  RecordField n;
  n.present = true;
  if (!v.is_array()) {
    n.kind = v.is_null() ? Kind::Float : numberKind(v);
    return n;
  }
  n.dims.push_back(int64_t(v.size()));
  if (v.empty()) {
    n.unknownInner = true;
    return n;
  }
  RecordField inner = leafOf(v[0], key);
  for (size_t i = 1; i < v.size(); ++i) {
    const RecordField other = leafOf(v[i], key);
    if (other.dims != inner.dims || other.unknownInner != inner.unknownInner)
      fail("patch JSON '{}': not a rectangular list of numbers", key);
    inner.kind = mergeKind(inner.kind, other.kind);
  }
  n.kind = inner.kind;
  n.unknownInner = inner.unknownInner;
  n.dims.insert(n.dims.end(), inner.dims.begin(), inner.dims.end());
  return n;
}

void merge(RecordField& into, const nlohmann::json& v, const std::string& key, bool& sawNull);

void mergeObject(RecordField& into, const nlohmann::json& object, bool& sawNull) {
  into.kind = Kind::Object;
  into.present = true;
  for (const auto& entry : object.items()) {
    const std::string& k = entry.key();
    if (entry.value().is_string()) continue;
    const auto it = std::find_if(into.children.begin(), into.children.end(),
                                 [&](const RecordField& c) { return c.name == k; });
    const size_t i = size_t(it - into.children.begin());
    if (it == into.children.end()) {
      into.children.emplace_back();
      into.children.back().name = k;
    }
    merge(into.children[i], entry.value(), k, sawNull);
  }
}

// Merges the shape of a leaf (a number or list, present) into a present leaf `into`. `later`
// may stand for one record or for several (a part's layout): the result is the same either way.
void mergeLeaf(RecordField& into, const RecordField& later, const std::string& key) {
  if (into.dims.empty() != later.dims.empty())
    fail("patch JSON '{}': a number in one record, a list in another", key);
  into.kind = mergeKind(into.kind, later.kind);
  if (later.dims.empty()) return;
  // Variable: not every record's list has the same length.
  if (into.dims[0] != later.dims[0] || later.variable) into.variable = true;
  const int64_t outer = std::max(into.dims[0], later.dims[0]);
  if (into.unknownInner) {
    into.dims = later.dims;
    into.unknownInner = later.unknownInner;
  } else if (!later.unknownInner && !std::equal(into.dims.begin() + 1, into.dims.end(),
                                                later.dims.begin() + 1, later.dims.end())) {
    fail("patch JSON '{}': lists of different shapes in different records", key);
  }
  into.dims[0] = outer;
}

void merge(RecordField& into, const nlohmann::json& v, const std::string& key, bool& sawNull) {
  if (v.is_object()) {
    if (into.present && into.kind != Kind::Object)
      fail("patch JSON '{}': an object in one record, a number or list in another", key);
    mergeObject(into, v, sawNull);
    return;
  }
  if (into.kind == Kind::Object)
    fail("patch JSON '{}': an object in one record, a number or list in another", key);
  if (v.is_null()) sawNull = true;
  if (v.is_null() && into.present) return;
  RecordField leaf = leafOf(v, key);
  if (!into.present) {
    leaf.name = into.name;
    into = std::move(leaf);
    return;
  }
  mergeLeaf(into, leaf, key);
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
  if (into.kind != Kind::Object) return mergeLeaf(into, later, later.name);
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

void writeNumber(const RecordField& node, const nlohmann::json& v, char* at) {
  if (node.kind == Kind::Bool) {
    const bool b = v.is_boolean() ? v.get<bool>() : (v.is_number() && v.get<double>() != 0.0);
    std::memcpy(at, &b, 1);
  } else if (node.kind == Kind::Int) {
    const int64_t i = v.is_number() ? v.get<int64_t>() : 0;
    std::memcpy(at, &i, 8);
  } else {
    const double d = v.is_number() || v.is_boolean() ? v.get<double>()
                                                     : std::numeric_limits<double>::quiet_NaN();
    std::memcpy(at, &d, 8);
  }
}

void writeList(const RecordField& node, const nlohmann::json& v, size_t level, char* at) {
  if (level == node.dims.size() || !v.is_array()) {
    if (level == node.dims.size()) writeNumber(node, v, at);
    return;
  }
  size_t stride = node.kind == Kind::Bool ? 1 : 8;
  for (size_t l = level + 1; l < node.dims.size(); ++l) stride *= size_t(node.dims[l]);
  const size_t n = std::min(v.size(), size_t(node.dims[level]));
  for (size_t i = 0; i < n; ++i) writeList(node, v[i], level + 1, at + i * stride);
}

void fillField(const RecordField& node, const nlohmann::json* v, char* base) {
  if (node.kind == Kind::Object) {
    for (const RecordField& child : node.children) {
      const nlohmann::json* item = nullptr;
      if (v && v->is_object()) {
        auto it = v->find(child.name);
        if (it != v->end()) item = &*it;
      }
      fillField(child, item, base);
    }
    return;
  }
  char* at = base + node.offset;
  if (!v || v->is_null()) {
    if (node.kind == Kind::Float && !node.variable) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      for (size_t i = 0; i < valueBytes(node) / 8; ++i) std::memcpy(at + 8 * i, &nan, 8);
    }
    return;
  }
  writeList(node, *v, 0, at);
  if (node.variable) {
    const int64_t count = v->is_array() ? int64_t(std::min(v->size(), size_t(node.dims[0]))) : 0;
    std::memcpy(base + node.countOffset, &count, 8);
  }
}

}  // namespace

void RecordLayout::add(const nlohmann::json& record) {
  mergeObject(root_, record, sawNull_);
}

void RecordLayout::merge(const RecordLayout& later) {
  mergeFields(root_, later.root_);
  sawNull_ |= later.sawNull_;
}

void RecordLayout::finish() {
  root_.kind = Kind::Object;
  itemSize_ = layout(root_, 0, true);
}

void RecordLayout::fill(const nlohmann::json& record, char* out) const {
  std::memset(out, 0, itemSize_);
  fillField(root_, &record, out);
}

RecordLayout RecordLayout::fromFields(RecordField root) {
  RecordLayout l;
  l.root_ = std::move(root);
  l.itemSize_ = layout(l.root_, 0, false);
  return l;
}

RecordLayout recordLayout(const std::vector<nlohmann::json>& records, const nlohmann::json& empty) {
  RecordLayout l;
  if (records.empty()) l.add(empty);
  for (const nlohmann::json& r : records) l.add(r);
  l.finish();
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
