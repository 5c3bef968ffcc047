#include "quadtri/surface/model_memory.h"

#include <algorithm>

namespace quadtri {
namespace {

// Peak resident bytes per input triangle beyond loading the mesh, measured with
// `/usr/bin/time -f %M` on icospheres of 20,480 and 81,920 triangles (the slope between them):
// `convert --model M -o x.obj`, `convert -o x.json` and `analyze --model M`.
struct ModelCost {
  std::string_view name;
  bool inputTriangles;  ///< traced and written as the input triangles (no tessellation)
  double traced;        ///< Render, when not tessellated: the patches and their geometry
  double json;          ///< ConvertJson: one patch as a JSON object and its text
  double latticeMesh;   ///< ConvertMesh: per lattice triangle of the tessellated surface
};
constexpr ModelCost kCosts[] = {
    {"flat", true, 100, 800, 0},
    {"shading", true, 100, 800, 0},
    {"shading-offset", true, 100, 800, 0},
    {"quadric-edges", false, 0, 4500, 290},
    {"quadric-param", false, 0, 4200, 290},
    {"quadric-implicit", false, 700, 7800, 290},
    {"quadric-edges-eq42", false, 0, 4500, 350},  // not welded: a vertex per patch corner
    {"quadric-implicit-robust", false, 3500, 9800, 310},
    {"phong", false, 0, 1900, 290},
    {"pn", false, 0, 6100, 290},
    {"nagata", false, 0, 2500, 290},
};
// The input triangles written to OBJ/PLY, and a lattice triangle traced by Embree (its share
// of vertices, the triangle, the BVH).
constexpr double kInputTriangleMesh = 150, kLatticeTriangleRender = 170;

}  // namespace

uint64_t modelBytesPerTriangle(std::string_view model, const Tessellation& tessellation,
                               ModelUse use) {
  const ModelCost* cost = nullptr;
  for (const ModelCost& c : kCosts)
    if (c.name == model) cost = &c;
  if (!cost) {
    // Unknown: the dearest of every model (makeModel refuses the name afterwards anyway).
    uint64_t most = 0;
    for (const ModelCost& c : kCosts)
      most = std::max(most, modelBytesPerTriangle(c.name, tessellation, use));
    return most;
  }
  const double lattice = double(tessellation.trianglesPerPatch());
  switch (use) {
    case ModelUse::ConvertJson:
      return uint64_t(cost->json);
    case ModelUse::ConvertMesh:
      return uint64_t(cost->inputTriangles ? kInputTriangleMesh : lattice * cost->latticeMesh);
    case ModelUse::Render:
      return uint64_t(cost->traced > 0 ? cost->traced : lattice * kLatticeTriangleRender);
  }
  return 0;
}

}  // namespace quadtri
