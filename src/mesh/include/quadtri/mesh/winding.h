// The winding of a mesh's connected parts, from its adjacency alone.
#pragma once

#include <cstdint>
#include <vector>

#include "quadtri/mesh/topology.h"
#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// Connected parts across edges of exactly two sides (boundary and non-manifold edges join
/// nothing), and each triangle's winding relative to its part's first triangle: two triangles
/// that share such an edge are consistent when they run along it in opposite directions.
struct WindingParts {
  /// Each part's triangles, the first (lowest index) first; parts in the order of it.
  std::vector<std::vector<uint32_t>> parts;
  /// Per triangle: +1 when it winds as its part's first triangle, -1 against it.
  std::vector<int8_t> relative;
  /// Per part: no two of its triangles' labels contradict each other (false: a Möbius strip).
  std::vector<char> orientable;
};

WindingParts windingParts(const TriangleMesh& mesh, const MeshTopology& topo);

}  // namespace quadtri
