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
// quadric-g1's pieces per triangle (G1Model: a Clough–Tocher split), each a region at least.
constexpr double kG1PiecesPerTriangle = 3;

// Steps along each edge of a patch's points (an Adaptive tessellation's lowest level, 1).
int edgeSteps(const Tessellation& t) {
  if (t.kind == Tessellation::Kind::Adaptive) return 1;
  return t.kind == Tessellation::Kind::ThesisGrid ? t.level - 1 : t.level;
}

// The lattice walk of a streamed surface, per input triangle: its first point's number, its
// share of the slots of the mesh's vertices (half a vertex) and of its edges' inner points
// (one and a half edges).
double walkBytes(const Tessellation& t) {
  return 4.0 + 2.0 + 6.0 * double(edgeSteps(t) - 1);
}

// A streamed surface's block: per patch, its points (position and normal, in double) and
// triangles with their normal indices; at most kTessellationBlockPoints points with their triangles
// (about two per point), and the text of a window of OBJ lines (8 × 16,384 lines of at most about
// 80 bytes). An Adaptive tessellation's block is charged at its highest level: the cap bounds it
// anyway.
CappedModelBytes streamBlockBytes(const Tessellation& t) {
  const Tessellation highest = t.kind == Tessellation::Kind::Adaptive
                                   ? Tessellation{Tessellation::Kind::Lattice, t.level}
                                   : t;
  const double side = double(edgeSteps(highest) + 1);
  const double points =
      t.kind == Tessellation::Kind::ThesisGrid ? side * side : side * (side + 1.0) / 2.0;
  // Triangles and, where creases give extra normals, their normal indices (24 bytes each) and
  // the extra normals with their points' positions (at most one per point: 48 bytes more).
  const double block = double(kTessellationBlockPoints) * (96.0 + 2.0 * 24.0) + 8 * 16384 * 80.0;
  return {uint64_t(points * 96.0 + double(highest.trianglesPerPatch()) * 24.0), uint64_t(block)};
}

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
    case ModelUse::ConvertMeshStreamed:
      return uint64_t(cost->inputTriangles ? kInputTriangleMesh
                                           : cost->streamed + walkBytes(tessellation));
    case ModelUse::Render:
      // A region per piece whatever the budget (modelCappedBytes charges the rest).
      if (cost->perRegion > 0)
        return uint64_t(cost->traced + kG1PiecesPerTriangle * cost->perRegion);
      return uint64_t(cost->traced > 0 ? cost->traced : lattice * kLatticeTriangleRender);
  }
  return 0;
}

CappedModelBytes modelCappedBytes(std::string_view model, ModelUse use,
                                  const Tessellation& tessellation) {
  const ModelCost* cost = modelCost(model);
  if (!cost) {
    CappedModelBytes most;
    for (const std::string& name : modelNames()) {
      const CappedModelBytes c = modelCappedBytes(name, use, tessellation);
      most.perTriangle = std::max(most.perTriangle, c.perTriangle);
      most.cap = std::max(most.cap, c.cap);
      most.floor = std::max(most.floor, c.floor);
    }
    return most;
  }
  if (use == ModelUse::ConvertMeshStreamed && !cost->inputTriangles)
    return streamBlockBytes(tessellation);
  if (use != ModelUse::Render || cost->perRegion <= 0) return {};
  // defaultSubPatchBudget's share per piece beyond the first region (charged per triangle: a
  // piece is one region at least, also past the cap) and its cap, on G1Model's three pieces
  // per triangle. Past the cap this charges up to the cap more than the pieces get.
  // A small mesh gets the budget's floor (kMinSubPatchBudget regions) however few its pieces.
  return {uint64_t(kG1PiecesPerTriangle * double(kSubPatchesPerPiece - 1) * cost->perRegion),
          uint64_t(double(kMaxSubPatchBudget) * cost->perRegion),
          uint64_t(double(kMinSubPatchBudget) * cost->perRegion)};
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
  const CappedModelBytes capped = modelCappedBytes(model, use, tessellation);
  if (!dearest)
    budget.bytesPerTriangle = budget.cappedBytesPerTriangle = budget.cappedBytes =
        budget.cappedFloorBytes = 0;
  budget.bytesPerTriangle = std::max(budget.bytesPerTriangle, perTriangle);
  budget.cappedBytesPerTriangle = std::max(budget.cappedBytesPerTriangle, capped.perTriangle);
  budget.cappedBytes = std::max(budget.cappedBytes, capped.cap);
  budget.cappedFloorBytes = std::max(budget.cappedFloorBytes, capped.floor);
}

}  // namespace quadtri
