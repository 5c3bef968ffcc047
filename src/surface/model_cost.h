// Private to the surface layer: what a model costs in memory per input triangle, kept with the
// model's name and factory in model.cpp's table and read by model_memory.cpp.
#pragma once

#include <string_view>

namespace quadtri {

/// Peak resident bytes per input triangle beyond loading the mesh, measured with
/// `/usr/bin/time -f %M` as the slope between two sizes of one shape (icospheres of 20,480 and
/// 81,920 triangles for `convert --model M -o x.obj`, `-o x.json` and `analyze --model M`; for
/// the directly traced quadric-implicit-robust and quadric-g1, `render` on tori of 40,960 and
/// 81,920 triangles, scripts/measure-first-pixel.sh; quadric-g1's split between triangles and
/// regions from those and a 1,000,000-triangle torus, where the region count is capped).
struct ModelCost {
  bool inputTriangles = false;  ///< traced and written as the input triangles (no tessellation)
  double traced = 0;            ///< Render, when not tessellated: the patches and their geometry
  double json = 0;              ///< ConvertJson: one patch as a JSON object and its text
  double latticeMesh = 0;       ///< ConvertMesh: per lattice triangle of the tessellated surface
  /// Render, for quadric-g1: per ray-tracing region (a BezierSubPatch, its copy while the blocks
  /// of the build are joined, its Embree primitive and BVH share), of which a mesh has as many
  /// as defaultSubPatchBudget gives its pieces, and one per piece at least (past the budget's
  /// cap, where the regions are written in place without the copy). Beside it, `traced` is
  /// what does not grow with the regions.
  double perRegion = 0;
  /// ConvertMeshStreamed: the model itself beside the lattice walk and one block of the
  /// streamed surface (saveTessellation), measured as the slope of `convert icosphere:6|7 -o
  /// x.ply` at level 8 less `flat`'s and the walk's, and charged about 15% above that (the
  /// welded models of lowest cost 33% above: a creased million-triangle cube needed it).
  double streamed = 0;
};

/// The cost of the model named `name`; nullptr for a name that is no model.
const ModelCost* modelCost(std::string_view name);

}  // namespace quadtri
