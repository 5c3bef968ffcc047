#include "quadtri/mesh/topology.h"

#include <algorithm>
#include <unordered_map>

namespace quadtri {

MeshTopology::MeshTopology(const TriangleMesh& mesh) {
  std::unordered_map<uint64_t, uint32_t> index;
  index.reserve(mesh.triangles.size() * 2);
  edgeOf.resize(mesh.triangles.size());
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    for (uint8_t k = 0; k < 3; ++k) {
      uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      const uint64_t key = (uint64_t(a) << 32) | b;
      auto [it, inserted] = index.try_emplace(key, uint32_t(edges.size()));
      if (inserted) edges.push_back(Edge{a, b, {}});
      edges[it->second].sides.emplace_back(t, k);
      edgeOf[t][k] = it->second;
    }
  }
}

size_t MeshTopology::boundaryEdgeCount() const {
  return std::count_if(edges.begin(), edges.end(),
                       [](const Edge& e) { return e.sides.size() == 1; });
}

size_t MeshTopology::nonManifoldEdgeCount() const {
  return std::count_if(edges.begin(), edges.end(),
                       [](const Edge& e) { return e.sides.size() > 2; });
}

}  // namespace quadtri
