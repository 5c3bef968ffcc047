// Private to the surface layer: the test of quadric-implicit-robust's overlap rounds (which
// cells of triangles that share no vertex overlap), on a grid of the cells' cores' boxes.
// A template over the functions that build a triangle's core and flat core, which the model
// keeps no array of.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "quadtri/math/parallel.h"
#include "quadtri/math/vec.h"
#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/surface/robust_cell.h"

namespace quadtri::robust_overlap {

// Oriented face normals closer than this cosine (60°) say that two triangles lie on the same
// side of the solid: no thin part separates them (between two sheets of a solid that face the
// same way lies one that faces the other way, whose cell the test still meets).
constexpr double kSameSideCos = 0.5;

// Per triangle: its cell overlaps the cell of a triangle it shares no vertex with, unless the
// two triangles themselves (their flat cores, flatCore(t)) do, face the same way (kSameSideCos), or
// belong to different parts (connected across edges, `part`): separate solids, such as the bones of
// bones.off, that touch or pass through each other, where their patches may cross as their
// triangles do; each part stays closed (and crack_rate counts hits of triangles that share no
// vertex as separate crossings). Of an overlapping pair only the triangle whose patch reaches
// farther (relative to its size) is flagged, unless `both`. Only pairs with a core that
// `changed` are tested. Candidate pairs from a uniform grid of the cells' boxes (`boxes`, those
// of core(t); spacing: the mean edge length); a cell itself is built (core(t)) only for the
// pairs whose boxes meet, so that no array of cells is held (656 bytes a triangle).
template <class Core, class FlatCore>
std::vector<char> overlappingCells(const TriangleMesh& mesh, const std::vector<Bounds3>& boxes,
                                   const Core& core, const FlatCore& flatCore,
                                   const std::vector<Vec3>& faceNormals,
                                   const std::vector<uint32_t>& part,
                                   const std::vector<double>& reach,
                                   const std::vector<char>& changed, bool both) {
  const size_t n = boxes.size();
  std::vector<char> out(n, 0);
  const double spacing = mesh.meanEdgeLength();
  if (!(spacing > 0.0)) return out;
  Bounds3 all;
  for (size_t t = 0; t < n; ++t)
    if (!boxes[t].empty()) all.extend(boxes[t]);
  if (all.empty()) return out;
  using Key = std::array<int64_t, 3>;
  const auto cellAt = [&](const Vec3& p, double size) {
    const Vec3 r = (p - all.lo) / size;
    return Key{int64_t(std::floor(r.x())), int64_t(std::floor(r.y())), int64_t(std::floor(r.z()))};
  };
  const auto cellOf = [&](const Vec3& p) { return cellAt(p, spacing); };
  // A box spanning more than 4096 cells of the mean edge's size is far larger than the mesh's
  // triangles: it is shrunk, not put in the grid.
  std::vector<size_t> first(n + 1, 0);
  parallelFor(size_t(0), n, [&](size_t t) {
    if (boxes[t].empty()) return;
    const Key lo = cellOf(boxes[t].lo), hi = cellOf(boxes[t].hi);
    const int64_t size = (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    if (size > 4096) out[t] = 1;
  });
  // The grid as one sorted array of (grid cell, triangle) entries, each cell's index packed in
  // 42 bits per axis of one 128-bit integer, so that sorting compares integers: each cell's
  // triangles are a run of it, in increasing order. Its cells are the mean edge's size, coarser
  // only where the mesh spans more than 2^42 of them (which pairs are found does not depend on
  // the cells' size: every pair of boxes that meet is found in the cell of their overlap's lower
  // corner; but cells coarser than the triangles would hold many, and the pairs within a cell
  // are tested two by two, so 21 bits, which a mesh with one stray triangle far away exceeds,
  // were too few).
  __extension__ typedef unsigned __int128 CellKey;
  constexpr int kAxisBits = 42;
  constexpr int64_t kAxisCells = int64_t(1) << kAxisBits;
  const double gridSpacing =
      std::max(spacing, (all.hi - all.lo).maxCoeff() / double(kAxisCells - 2));
  const auto pack = [](int64_t x, int64_t y, int64_t z) {
    const auto clamp = [](int64_t c) {
      return CellKey(uint64_t(std::clamp<int64_t>(c, 0, kAxisCells - 1)));
    };
    return (clamp(x) << (2 * kAxisBits)) | (clamp(y) << kAxisBits) | clamp(z);
  };
  const auto gridCell = [&](const Vec3& p) {
    const Key k = cellAt(p, gridSpacing);
    return pack(k[0], k[1], k[2]);
  };
  parallelFor(size_t(0), n, [&](size_t t) {
    if (boxes[t].empty() || out[t]) return;
    const Key lo = cellAt(boxes[t].lo, gridSpacing), hi = cellAt(boxes[t].hi, gridSpacing);
    first[t + 1] = size_t((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1));
  });
  for (size_t t = 0; t < n; ++t) first[t + 1] += first[t];
  struct Entry {
    CellKey key;
    uint32_t t;
    bool operator<(const Entry& o) const { return key != o.key ? key < o.key : t < o.t; }
  };
  std::vector<Entry> grid(first[n]);
  parallelFor(size_t(0), n, [&](size_t t) {
    if (first[t + 1] == first[t]) return;
    const Key lo = cellAt(boxes[t].lo, gridSpacing), hi = cellAt(boxes[t].hi, gridSpacing);
    size_t i = first[t];
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z) grid[i++] = Entry{pack(x, y, z), uint32_t(t)};
  });
  parallelSort(grid.begin(), grid.end());
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t begin = 0; begin < grid.size();) {
    size_t end = begin + 1;
    while (end < grid.size() && grid[end].key == grid[begin].key) ++end;
    const CellKey key = grid[begin].key;
    for (size_t i = begin; i < end; ++i)
      for (size_t j = i + 1; j < end; ++j) {
        const uint32_t a = grid[i].t, b = grid[j].t;
        bool shared = false;
        for (uint32_t va : mesh.triangles[a])
          for (uint32_t vb : mesh.triangles[b]) shared |= va == vb;
        // A pair neither of whose cores changed since the last round was found apart there.
        if (shared || (!changed[a] && !changed[b])) continue;
        const Bounds3& ba = boxes[a];
        const Bounds3& bb = boxes[b];
        if ((ba.hi.array() < bb.lo.array()).any() || (bb.hi.array() < ba.lo.array()).any())
          continue;
        // Test each pair once: in the grid cell of the overlap's lower corner.
        if (gridCell(ba.lo.cwiseMax(bb.lo)) != key) continue;
        pairs.emplace_back(a, b);
      }
    begin = end;
  }
  std::vector<char> hit(pairs.size(), 0);
  parallelFor(size_t(0), pairs.size(), [&](size_t i) {
    const auto [a, b] = pairs[i];
    if (faceNormals[a].dot(faceNormals[b]) > kSameSideCos || part[a] != part[b]) return;
    const double tolerance = 1e-9 * std::min(mesh.meanEdgeLength(a), mesh.meanEdgeLength(b));
    // Triangles that cross each other (or nearly) keep crossing whatever their patches do.
    hit[i] = cellsOverlap(core(a), core(b), tolerance) &&
             !cellsOverlap(flatCore(a), flatCore(b), tolerance);
  });
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (!hit[i]) continue;
    const auto [a, b] = pairs[i];
    const double ra = reach[a] / mesh.meanEdgeLength(a), rb = reach[b] / mesh.meanEdgeLength(b);
    if (both || !(ra < rb)) out[a] = 1;
    if (both || ra < rb) out[b] = 1;
  }
  return out;
}

}  // namespace quadtri::robust_overlap
