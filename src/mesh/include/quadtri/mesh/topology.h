// Edge adjacency of a welded triangle mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// One undirected edge (a < b) and the triangle sides that use it.
struct Edge {
  uint32_t a = 0, b = 0;
  /// (triangle, local edge k) pairs; local edge k joins corners k and (k+1)%3.
  std::vector<std::pair<uint32_t, uint8_t>> sides;
};

struct MeshTopology {
  std::vector<Edge> edges;
  /// edgeOf[t][k] is the index in `edges` of local edge k of triangle t.
  std::vector<std::array<uint32_t, 3>> edgeOf;

  explicit MeshTopology(const TriangleMesh& mesh);

  size_t boundaryEdgeCount() const;
  size_t nonManifoldEdgeCount() const;
  /// Closed: every edge has exactly two sides.
  bool isClosed() const { return boundaryEdgeCount() == 0 && nonManifoldEdgeCount() == 0; }
};

}  // namespace quadtri
