// One patch's data as a small tree of named numbers (README, "Patch JSON"): what a model writes
// for `quadtri convert -o x.json` and what the binary patch table (patch_table.h) packs. A model
// fills one per patch into storage the caller reuses, so writing a million patches allocates no
// JSON tree per patch; toJson() gives the nlohmann::json that the JSON output dumps.
#pragma once

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "quadtri/math/vec.h"

namespace quadtri {

class PatchRecord {
 public:
  enum class Type : uint8_t { Object, Array, Bool, Int, Float, Null };
  /// A node of the tree: the root object is kRoot.
  using Ref = uint32_t;
  static constexpr Ref kRoot = 0, kNone = ~Ref(0);

  PatchRecord() { clear(); }
  /// Back to an empty root object, keeping the storage.
  void clear();

  // Building. A member set on an object replaces one of the same key; an object's members are
  // kept sorted by key (as nlohmann::json sorts them), an array's elements in order.
  Ref setObject(Ref object, std::string_view key) { return member(object, key, Type::Object); }
  Ref setArray(Ref object, std::string_view key) { return member(object, key, Type::Array); }
  void set(Ref object, std::string_view key, double v) {
    node(member(object, key, Type::Float)).number = v;
  }
  void setInt(Ref object, std::string_view key, int64_t v);
  void setBool(Ref object, std::string_view key, bool v);
  void set(Ref object, std::string_view key, const Vec3& v) {
    fill(setArray(object, key), v.data(), 3);
  }
  void set(Ref object, std::string_view key, const double* v, size_t n) {
    fill(setArray(object, key), v, n);
  }
  Ref pushObject(Ref array) { return element(array, Type::Object); }
  Ref pushArray(Ref array) { return element(array, Type::Array); }
  void push(Ref array, double v) { node(element(array, Type::Float)).number = v; }
  void pushInt(Ref array, int64_t v);
  void push(Ref array, const Vec3& v) { fill(pushArray(array), v.data(), 3); }
  void push(Ref array, const double* v, size_t n) { fill(pushArray(array), v, n); }

  // Reading.
  Type type(Ref r) const { return nodes_[r].type; }
  /// The key of an object's member (empty for an array element or the root).
  std::string_view key(Ref r) const { return {keys_.data() + nodes_[r].key, nodes_[r].keyLength}; }
  /// Members or elements.
  size_t size(Ref r) const { return nodes_[r].count; }
  Ref first(Ref r) const { return nodes_[r].first; }
  Ref next(Ref r) const { return nodes_[r].next; }
  /// An object's member by key, or kNone.
  Ref find(Ref object, std::string_view key) const;
  bool isNumber(Ref r) const { return type(r) == Type::Int || type(r) == Type::Float; }
  /// A number or bool as a double (a bool: 0 or 1).
  double number(Ref r) const;
  /// A number as an integer (a float truncated), a bool as 0 or 1.
  int64_t integer(Ref r) const;
  bool boolean(Ref r) const { return nodes_[r].integer != 0; }

  /// The same data as a JSON value: numbers as floats, integers as integers.
  nlohmann::json toJson(Ref r = kRoot) const;
  /// Appends toJson(r).dump() to `out`, the same bytes, without building the JSON value.
  void dump(std::string& out, Ref r = kRoot) const;
  /// The record of a JSON object (strings are left out); throws Error for anything else.
  static PatchRecord fromJson(const nlohmann::json& object);

 private:
  struct Node {
    Type type = Type::Null;
    uint32_t key = 0, keyLength = 0;
    Ref first = kNone, last = kNone, next = kNone;
    uint32_t count = 0;
    int64_t integer = 0;
    double number = 0.0;
  };
  Node& node(Ref r) { return nodes_[r]; }
  Ref newNode(Type type);
  Ref member(Ref object, std::string_view key, Type type);
  Ref element(Ref array, Type type);
  void fill(Ref array, const double* v, size_t n);
  void addJson(Ref parent, std::string_view key, const nlohmann::json& value);

  std::vector<Node> nodes_;
  std::string keys_;
};

}  // namespace quadtri
