#include "patch_records.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

#include "quadtri/math/error.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri::python {

namespace {

template <typename Json>
py::object toPythonImpl(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null:
      return py::none();
    case Json::value_t::boolean:
      return py::bool_(value.template get<bool>());
    case Json::value_t::number_integer:
      return py::int_(value.template get<int64_t>());
    case Json::value_t::number_unsigned:
      return py::int_(value.template get<uint64_t>());
    case Json::value_t::number_float:
      return py::float_(value.template get<double>());
    case Json::value_t::string:
      return py::str(value.template get<std::string>());
    case Json::value_t::array: {
      py::list list;
      for (const auto& item : value) list.append(toPythonImpl(item));
      return list;
    }
    case Json::value_t::object: {
      py::dict dict;
      for (const auto& [key, item] : value.items()) dict[py::str(key)] = toPythonImpl(item);
      return dict;
    }
    default:
      return py::none();
  }
}

// The shape of one field across records.
struct Node {
  enum class Kind { Unknown, Bool, Int, Float, Object } kind = Kind::Unknown;
  bool present = false;       // a value other than a string was seen
  std::vector<int64_t> dims;  // list dimensions, empty for a scalar
  bool unknownInner = false;  // only empty lists seen: the dimensions after the first unknown
  bool variable = false;      // the first dimension differs between records
  // Kind::Object: childNames[i] names children[i] (a vector of the incomplete Node is allowed,
  // a pair holding one is not).
  std::vector<std::string> childNames;
  std::vector<Node> children;
  size_t offset = 0, countOffset = 0;  // set by layout()
};

Node::Kind numberKind(const nlohmann::json& v) {
  if (v.is_boolean()) return Node::Kind::Bool;
  if (v.is_number_integer()) return Node::Kind::Int;
  return Node::Kind::Float;
}

Node::Kind mergeKind(Node::Kind a, Node::Kind b) {
  if (a == Node::Kind::Unknown) return b;
  if (b == Node::Kind::Unknown || a == b) return a;
  return Node::Kind::Float;  // int and float (or bool) mixed
}

// The leaf shape of one value: its list dimensions and number kind.
Node leafOf(const nlohmann::json& v, const std::string& key) {
  Node n;
  n.present = true;
  if (!v.is_array()) {
    n.kind = v.is_null() ? Node::Kind::Float : numberKind(v);
    return n;
  }
  n.dims.push_back(int64_t(v.size()));
  if (v.empty()) {
    n.unknownInner = true;
    return n;
  }
  Node inner = leafOf(v[0], key);
  for (size_t i = 1; i < v.size(); ++i) {
    const Node other = leafOf(v[i], key);
    if (other.dims != inner.dims || other.unknownInner != inner.unknownInner)
      fail("patch JSON '{}': not a rectangular list of numbers", key);
    inner.kind = mergeKind(inner.kind, other.kind);
  }
  n.kind = inner.kind;
  n.unknownInner = inner.unknownInner;
  n.dims.insert(n.dims.end(), inner.dims.begin(), inner.dims.end());
  return n;
}

void merge(Node& into, const nlohmann::json& v, const std::string& key);

void mergeObject(Node& into, const nlohmann::json& object) {
  into.kind = Node::Kind::Object;
  into.present = true;
  for (const auto& entry : object.items()) {
    const std::string& k = entry.key();
    if (entry.value().is_string()) continue;
    const auto it = std::find(into.childNames.begin(), into.childNames.end(), k);
    const size_t i = size_t(it - into.childNames.begin());
    if (it == into.childNames.end()) {
      into.childNames.push_back(k);
      into.children.emplace_back();
    }
    merge(into.children[i], entry.value(), k);
  }
}

void merge(Node& into, const nlohmann::json& v, const std::string& key) {
  if (v.is_object()) {
    if (into.present && into.kind != Node::Kind::Object)
      fail("patch JSON '{}': an object in one record, a number or list in another", key);
    mergeObject(into, v);
    return;
  }
  if (into.kind == Node::Kind::Object)
    fail("patch JSON '{}': an object in one record, a number or list in another", key);
  if (v.is_null() && into.present) return;
  const Node leaf = leafOf(v, key);
  if (!into.present) {
    into = leaf;
    return;
  }
  if (into.dims.empty() != leaf.dims.empty())
    fail("patch JSON '{}': a number in one record, a list in another", key);
  into.kind = mergeKind(into.kind, leaf.kind);
  if (leaf.dims.empty()) return;
  if (into.dims[0] != leaf.dims[0]) into.variable = true;
  const int64_t outer = std::max(into.dims[0], leaf.dims[0]);
  if (into.unknownInner) {
    into.dims = leaf.dims;
    into.unknownInner = leaf.unknownInner;
  } else if (!leaf.unknownInner && !std::equal(into.dims.begin() + 1, into.dims.end(),
                                               leaf.dims.begin() + 1, leaf.dims.end())) {
    fail("patch JSON '{}': lists of different shapes in different records", key);
  }
  into.dims[0] = outer;
}

// Fixed shapes, then byte offsets (packed, as numpy lays out a dtype given as a list).
size_t layout(Node& node, const std::string& key, size_t offset) {
  node.offset = offset;
  if (node.kind == Node::Kind::Object) {
    size_t at = offset;
    for (size_t i = 0; i < node.children.size(); ++i)
      at = layout(node.children[i], node.childNames[i], at);
    return at;
  }
  if (key == "planes" && !node.dims.empty()) {
    node.dims = {QuadricPatch::kMaxPlanes, 4};
    node.unknownInner = false;
    node.variable = true;
    node.kind = Node::Kind::Float;
  }
  if (node.unknownInner) node.unknownInner = false;  // every list empty: shape (0,)
  if (node.kind == Node::Kind::Unknown) node.kind = Node::Kind::Float;
  size_t count = 1;
  for (int64_t d : node.dims) count *= size_t(d);
  size_t at = offset + count * (node.kind == Node::Kind::Bool ? 1 : 8);
  if (node.variable) {
    node.countOffset = at;
    at += 8;
  }
  return at;
}

py::object dtypeOf(const Node& node) {
  py::list fields;
  for (size_t i = 0; i < node.children.size(); ++i) {
    const std::string& key = node.childNames[i];
    const Node& child = node.children[i];
    if (child.kind == Node::Kind::Object) {
      fields.append(py::make_tuple(key, dtypeOf(child)));
      continue;
    }
    const char* type = child.kind == Node::Kind::Bool  ? "?"
                       : child.kind == Node::Kind::Int ? "<i8"
                                                       : "<f8";
    if (child.dims.empty()) {
      fields.append(py::make_tuple(key, type));
    } else {
      py::tuple shape(child.dims.size());
      for (size_t d = 0; d < child.dims.size(); ++d) shape[d] = py::int_(child.dims[d]);
      fields.append(py::make_tuple(key, type, shape));
    }
    if (child.variable) fields.append(py::make_tuple(key + "_count", "<i8"));
  }
  return py::module_::import("numpy").attr("dtype")(fields);
}

void writeNumber(const Node& node, const nlohmann::json& v, char* at) {
  if (node.kind == Node::Kind::Bool) {
    const bool b = v.is_boolean() ? v.get<bool>() : (v.is_number() && v.get<double>() != 0.0);
    std::memcpy(at, &b, 1);
  } else if (node.kind == Node::Kind::Int) {
    const int64_t i = v.is_number() ? v.get<int64_t>() : 0;
    std::memcpy(at, &i, 8);
  } else {
    const double d = v.is_number() || v.is_boolean() ? v.get<double>()
                                                     : std::numeric_limits<double>::quiet_NaN();
    std::memcpy(at, &d, 8);
  }
}

void writeList(const Node& node, const nlohmann::json& v, size_t level, char* at) {
  if (level == node.dims.size() || !v.is_array()) {
    if (level == node.dims.size()) writeNumber(node, v, at);
    return;
  }
  size_t stride = node.kind == Node::Kind::Bool ? 1 : 8;
  for (size_t l = level + 1; l < node.dims.size(); ++l) stride *= size_t(node.dims[l]);
  const size_t n = std::min(v.size(), size_t(node.dims[level]));
  for (size_t i = 0; i < n; ++i) writeList(node, v[i], level + 1, at + i * stride);
}

void fill(const Node& node, const nlohmann::json* v, char* base) {
  if (node.kind == Node::Kind::Object) {
    for (size_t i = 0; i < node.children.size(); ++i) {
      const std::string& key = node.childNames[i];
      const Node& child = node.children[i];
      const nlohmann::json* item = nullptr;
      if (v && v->is_object()) {
        auto it = v->find(key);
        if (it != v->end()) item = &*it;
      }
      fill(child, item, base);
    }
    return;
  }
  char* at = base + node.offset;
  if (!v || v->is_null()) {
    if (node.kind == Node::Kind::Float && !node.variable) {
      size_t count = 1;
      for (int64_t d : node.dims) count *= size_t(d);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      for (size_t i = 0; i < count; ++i) std::memcpy(at + 8 * i, &nan, 8);
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

py::object toPython(const nlohmann::json& value) {
  return toPythonImpl(value);
}

py::object toPython(const nlohmann::ordered_json& value) {
  return toPythonImpl(value);
}

py::array recordsFromJson(const std::vector<nlohmann::json>& records, const nlohmann::json& empty) {
  Node root;
  root.kind = Node::Kind::Object;
  if (records.empty()) mergeObject(root, empty);
  for (const nlohmann::json& r : records) mergeObject(root, r);
  const size_t itemSize = layout(root, "", 0);
  const py::dtype dtype = py::reinterpret_borrow<py::dtype>(dtypeOf(root));
  if (size_t(dtype.itemsize()) != itemSize)
    fail("internal: record layout of {} bytes, numpy's dtype has {}", itemSize, dtype.itemsize());
  py::array out(dtype, std::vector<py::ssize_t>{py::ssize_t(records.size())});
  char* data = static_cast<char*>(out.mutable_data());
  if (!records.empty()) std::memset(data, 0, records.size() * itemSize);
  for (size_t i = 0; i < records.size(); ++i) fill(root, &records[i], data + i * itemSize);
  return out;
}

}  // namespace quadtri::python
