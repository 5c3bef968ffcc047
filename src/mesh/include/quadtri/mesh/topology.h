// Edge adjacency of a welded triangle mesh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// A (triangle, local edge k) pair; local edge k joins corners k and (k+1)%3.
using EdgeSide = std::pair<uint32_t, uint8_t>;

/// The sides of one edge: a view into its MeshTopology's flat array, ordered by triangle and
/// then by local edge.
class EdgeSides {
 public:
  EdgeSides() = default;
  EdgeSides(const EdgeSide* first, const EdgeSide* last) : first_(first), last_(last) {}
  const EdgeSide* begin() const { return first_; }
  const EdgeSide* end() const { return last_; }
  size_t size() const { return size_t(last_ - first_); }
  bool empty() const { return first_ == last_; }
  const EdgeSide& operator[](size_t i) const { return first_[i]; }
  const EdgeSide& front() const { return *first_; }

 private:
  const EdgeSide* first_ = nullptr;
  const EdgeSide* last_ = nullptr;
};

/// One undirected edge (a < b) and the triangle sides that use it.
struct Edge {
  uint32_t a = 0, b = 0;
  EdgeSides sides;
};

/// Built once per mesh from one array of half-edges ordered by their edge (a counting sort on
/// the lower vertex, in linear time; no hash map, no allocation per edge); edges are numbered
/// in the order of their first side. Movable, not copyable (the
/// edges point into its own array of sides).
struct MeshTopology {
  std::vector<Edge> edges;
  /// edgeOf[t][k] is the index in `edges` of local edge k of triangle t.
  std::vector<std::array<uint32_t, 3>> edgeOf;

  explicit MeshTopology(const TriangleMesh& mesh);
  MeshTopology(const MeshTopology&) = delete;
  MeshTopology& operator=(const MeshTopology&) = delete;
  MeshTopology(MeshTopology&&) = default;
  MeshTopology& operator=(MeshTopology&&) = default;

  size_t boundaryEdgeCount() const;
  size_t nonManifoldEdgeCount() const;
  /// Closed: every edge has exactly two sides.
  bool isClosed() const { return boundaryEdgeCount() == 0 && nonManifoldEdgeCount() == 0; }

 private:
  std::vector<EdgeSide> sides_;  ///< every edge's sides, edge after edge
};

}  // namespace quadtri
