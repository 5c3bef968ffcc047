#include "quadtri/surface/patch_record.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

#include "quadtri/math/error.h"

namespace quadtri {

void PatchRecord::clear() {
  nodes_.clear();
  keys_.clear();
  newNode(Type::Object);
}

PatchRecord::Ref PatchRecord::newNode(Type type) {
  nodes_.emplace_back();
  nodes_.back().type = type;
  return Ref(nodes_.size() - 1);
}

PatchRecord::Ref PatchRecord::member(Ref object, std::string_view key, Type type) {
  // Sorted insertion: the member before which `key` goes, or the one it replaces.
  Ref before = kNone, at = nodes_[object].first;
  while (at != kNone) {
    const int order = this->key(at).compare(key);
    if (order == 0) {
      Node& n = nodes_[at];
      n.type = type;
      n.first = n.last = kNone;
      n.count = 0;
      n.integer = 0;
      n.number = 0.0;
      return at;
    }
    if (order > 0) break;
    before = at;
    at = nodes_[at].next;
  }
  const Ref r = newNode(type);
  Node& n = nodes_[r];
  n.key = uint32_t(keys_.size());
  n.keyLength = uint32_t(key.size());
  keys_.append(key);
  n.next = at;
  Node& o = nodes_[object];
  if (before == kNone)
    o.first = r;
  else
    nodes_[before].next = r;
  if (at == kNone) o.last = r;
  ++o.count;
  return r;
}

PatchRecord::Ref PatchRecord::element(Ref array, Type type) {
  const Ref r = newNode(type);
  Node& a = nodes_[array];
  if (a.last == kNone)
    a.first = r;
  else
    nodes_[a.last].next = r;
  a.last = r;
  ++a.count;
  return r;
}

void PatchRecord::setInt(Ref object, std::string_view key, int64_t v) {
  node(member(object, key, Type::Int)).integer = v;
}

void PatchRecord::setBool(Ref object, std::string_view key, bool v) {
  node(member(object, key, Type::Bool)).integer = v ? 1 : 0;
}

void PatchRecord::pushInt(Ref array, int64_t v) {
  node(element(array, Type::Int)).integer = v;
}

void PatchRecord::fill(Ref array, const double* v, size_t n) {
  for (size_t i = 0; i < n; ++i) push(array, v[i]);
}

PatchRecord::Ref PatchRecord::find(Ref object, std::string_view key) const {
  for (Ref at = first(object); at != kNone; at = next(at)) {
    const int order = this->key(at).compare(key);
    if (order == 0) return at;
    if (order > 0) break;
  }
  return kNone;
}

double PatchRecord::number(Ref r) const {
  return type(r) == Type::Float ? nodes_[r].number : double(nodes_[r].integer);
}

int64_t PatchRecord::integer(Ref r) const {
  return type(r) == Type::Float ? int64_t(nodes_[r].number) : nodes_[r].integer;
}

nlohmann::json PatchRecord::toJson(Ref r) const {
  switch (type(r)) {
    case Type::Object: {
      nlohmann::json j = nlohmann::json::object();
      for (Ref at = first(r); at != kNone; at = next(at)) j[std::string(key(at))] = toJson(at);
      return j;
    }
    case Type::Array: {
      nlohmann::json j = nlohmann::json::array();
      for (Ref at = first(r); at != kNone; at = next(at)) j.push_back(toJson(at));
      return j;
    }
    case Type::Bool:
      return boolean(r);
    case Type::Int:
      return nodes_[r].integer;
    case Type::Float:
      return nodes_[r].number;
    case Type::Null:
      break;
  }
  return nullptr;
}

namespace {

// A key as nlohmann::json's dump() writes it: plain keys directly, anything that needs escaping
// through the library itself.
void dumpKey(std::string& out, std::string_view key) {
  const bool plain = std::all_of(key.begin(), key.end(), [](char c) {
    return c >= 0x20 && c < 0x7f && c != '"' && c != '\\';
  });
  if (plain) {
    out += '"';
    out += key;
    out += '"';
  } else {
    out += nlohmann::json(std::string(key)).dump();
  }
}

}  // namespace

void PatchRecord::dump(std::string& out, Ref r) const {
  switch (type(r)) {
    case Type::Object:
    case Type::Array: {
      const bool object = type(r) == Type::Object;
      out += object ? '{' : '[';
      for (Ref at = first(r); at != kNone; at = next(at)) {
        if (at != first(r)) out += ',';
        if (object) {
          dumpKey(out, key(at));
          out += ':';
        }
        dump(out, at);
      }
      out += object ? '}' : ']';
      return;
    }
    case Type::Bool:
      out += boolean(r) ? "true" : "false";
      return;
    case Type::Int: {
      char buffer[24];
      const auto end = std::to_chars(buffer, buffer + sizeof buffer, nodes_[r].integer).ptr;
      out.append(buffer, size_t(end - buffer));
      return;
    }
    case Type::Float: {
      const double x = nodes_[r].number;
      if (!std::isfinite(x)) break;  // dump() writes NaN and infinities as null
      // The shortest round-trip digits, formatted by the routine dump() itself uses.
      char buffer[64];
      const char* end = nlohmann::detail::to_chars(buffer, buffer + sizeof buffer, x);
      out.append(buffer, size_t(end - buffer));
      return;
    }
    case Type::Null:
      break;
  }
  out += "null";
}

void PatchRecord::addJson(Ref parent, std::string_view key, const nlohmann::json& value) {
  const bool inArray = type(parent) == Type::Array;
  const auto add = [&](Type t) { return inArray ? element(parent, t) : member(parent, key, t); };
  if (value.is_object()) {
    const Ref o = add(Type::Object);
    for (const auto& item : value.items())
      if (!item.value().is_string()) addJson(o, item.key(), item.value());
  } else if (value.is_array()) {
    const Ref a = add(Type::Array);
    for (const nlohmann::json& v : value) addJson(a, {}, v);
  } else if (value.is_boolean()) {
    node(add(Type::Bool)).integer = value.get<bool>() ? 1 : 0;
  } else if (value.is_number_integer()) {
    node(add(Type::Int)).integer = value.get<int64_t>();
  } else if (value.is_number()) {
    node(add(Type::Float)).number = value.get<double>();
  } else {
    add(Type::Null);  // null, or a string inside a list: no number
  }
}

PatchRecord PatchRecord::fromJson(const nlohmann::json& object) {
  if (!object.is_object())
    fail("patch JSON: a record must be an object, not {}", object.type_name());
  PatchRecord r;
  for (const auto& item : object.items())
    if (!item.value().is_string()) r.addJson(kRoot, item.key(), item.value());
  return r;
}

}  // namespace quadtri
