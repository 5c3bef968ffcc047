#include "quadtri/mesh/winding.h"

namespace quadtri {

WindingParts windingParts(const TriangleMesh& mesh, const MeshTopology& topo) {
  const size_t n = mesh.triangles.size();
  WindingParts w;
  w.relative.assign(n, 0);  // 0: not reached yet
  std::vector<uint32_t> stack;
  for (size_t seed = 0; seed < n; ++seed) {
    if (w.relative[seed] != 0) continue;
    std::vector<uint32_t> part;
    stack.assign(1, uint32_t(seed));
    w.relative[seed] = 1;
    bool orientable = true;
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      part.push_back(t);
      for (int k = 0; k < 3; ++k) {
        const Edge& e = topo.edges[topo.edgeOf[t][k]];
        if (e.sides.size() != 2) continue;
        const EdgeSide other =
            e.sides[0].first == t && e.sides[0].second == k ? e.sides[1] : e.sides[0];
        const uint32_t u = other.first;
        if (u == t) continue;
        // Consistent: u runs from t's edge end to its start.
        const bool sameDirection = mesh.triangles[t][k] == mesh.triangles[u][other.second];
        const int8_t want = int8_t(sameDirection ? -w.relative[t] : w.relative[t]);
        if (w.relative[u] == 0) {
          w.relative[u] = want;
          stack.push_back(u);
        } else if (w.relative[u] != want) {
          orientable = false;
        }
      }
    }
    w.parts.push_back(std::move(part));
    w.orientable.push_back(orientable);
  }
  return w;
}

}  // namespace quadtri
