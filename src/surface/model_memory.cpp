#include "quadtri/surface/model_memory.h"

#include <fmt/format.h>

#include <algorithm>

#include "model_cost.h"
#include "quadtri/surface/bezier_intersect.h"
#include "quadtri/surface/model.h"

namespace quadtri {
namespace {

// The input triangles written to OBJ/PLY, and a lattice triangle traced by Embree (its share
// of vertices, the triangle, the BVH).
constexpr double kInputTriangleMesh = 150, kLatticeTriangleRender = 170;

}  // namespace

uint64_t modelBytesPerTriangle(std::string_view model, const Tessellation& tessellation,
                               ModelUse use) {
  const ModelCost* cost = modelCost(model);
  if (!cost) {
    // Unknown: the dearest of every model (makeModel refuses the name afterwards anyway).
    uint64_t most = 0;
    for (const std::string& name : modelNames())
      most = std::max(most, modelBytesPerTriangle(name, tessellation, use));
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

CappedModelBytes modelCappedBytes(std::string_view model, ModelUse use) {
  const ModelCost* cost = modelCost(model);
  if (!cost) {
    CappedModelBytes most;
    for (const std::string& name : modelNames()) {
      const CappedModelBytes c = modelCappedBytes(name, use);
      most.perTriangle = std::max(most.perTriangle, c.perTriangle);
      most.cap = std::max(most.cap, c.cap);
    }
    return most;
  }
  if (use != ModelUse::Render || cost->perRegion <= 0) return {};
  // defaultSubPatchBudget's share per piece and its cap, on G1Model's three pieces per triangle.
  return {uint64_t(double(3 * kSubPatchesPerPiece) * cost->perRegion),
          uint64_t(double(kMaxSubPatchBudget) * cost->perRegion)};
}

void chargeResolvedTessellation(MemoryBudget& budget, std::string_view model,
                                const Tessellation& requested, const Tessellation& resolved,
                                ModelUse use, uint64_t triangles, const std::string& name) {
  if (requested.kind != Tessellation::Kind::Adaptive) return;
  const uint64_t charged = modelBytesPerTriangle(model, requested, use);
  const uint64_t needed = modelBytesPerTriangle(model, resolved, use);
  if (needed <= charged) return;
  MemoryBudget extra;
  extra.bytesPerTriangle = needed - charged;
  chargeMemory(
      budget, modelBytes(extra, triangles), name,
      fmt::format("tessellating its {} triangles at level {} (auto)", triangles, resolved.level));
}

void setModelBytes(MemoryBudget& budget, std::string_view model, const Tessellation& tessellation,
                   ModelUse use, bool dearest) {
  const uint64_t perTriangle = modelBytesPerTriangle(model, tessellation, use);
  const CappedModelBytes capped = modelCappedBytes(model, use);
  if (!dearest) budget.bytesPerTriangle = budget.cappedBytesPerTriangle = budget.cappedBytes = 0;
  budget.bytesPerTriangle = std::max(budget.bytesPerTriangle, perTriangle);
  budget.cappedBytesPerTriangle = std::max(budget.cappedBytesPerTriangle, capped.perTriangle);
  budget.cappedBytes = std::max(budget.cappedBytes, capped.cap);
}

}  // namespace quadtri
