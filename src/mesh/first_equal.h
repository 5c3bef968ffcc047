// Numbering equal points, shared by the mesh reader (welding) and writer (PLY vertices).
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "quadtri/math/large_array.h"

namespace quadtri::mesh_detail {

// Numbers equal points by first appearance, as inserting them in order into a std::map keyed by
// their coordinates would (exact equality; -0 equals +0 and the first one's sign is kept):
// returns first, first[i] the least index j with points[j] == points[i]. An open-addressing
// hash table of indices instead of the map: one pass in order, the same answer on any machine.
template <typename T>
std::vector<uint32_t> firstEqual(const std::vector<std::array<T, 3>>& points) {
  const size_t n = points.size();
  size_t capacity = 16;
  while (capacity < 2 * n) capacity *= 2;
  const size_t mask = capacity - 1;
  std::vector<uint32_t> slots = largeVector(capacity, ~0u), first = largeVector<uint32_t>(n);
  const auto hash = [](const std::array<T, 3>& p) {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (const T c : p) {
      // +0 for -0, so that equal points hash alike.
      const double d = c == T(0) ? 0.0 : double(c);
      uint64_t bits = 0;
      std::memcpy(&bits, &d, sizeof(bits));
      h = (h ^ bits) * 0xff51afd7ed558ccdull;
      h ^= h >> 32;
    }
    return size_t(h);
  };
  for (size_t i = 0; i < n; ++i) {
    const std::array<T, 3>& p = points[i];
    for (size_t s = hash(p) & mask;; s = (s + 1) & mask) {
      if (slots[s] == ~0u) {
        slots[s] = uint32_t(i);
        first[i] = uint32_t(i);
        break;
      }
      const std::array<T, 3>& q = points[slots[s]];
      if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2]) {
        first[i] = slots[s];
        break;
      }
    }
  }
  return first;
}

}  // namespace quadtri::mesh_detail
