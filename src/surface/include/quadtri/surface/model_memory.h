// What a model costs in memory per input triangle, for refusing a mesh before it is converted.
#pragma once

#include <cstdint>
#include <string_view>

#include "quadtri/mesh/mesh_io_check.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

/// What the model is built for: its tessellated surface built whole (`analyze`'s views),
/// `convert` to OBJ/PLY, streamed (the model, the lattice walk and one block,
/// saveTessellation), `convert` to JSON
/// (every patch as a JSON object), or tracing it (`render`, and `analyze`, which traces it for
/// its crack rate): its tessellation and Embree's geometry.
enum class ModelUse { ConvertMesh, ConvertMeshStreamed, ConvertJson, Render };

/// Estimated peak bytes per input triangle of building `model` on a mesh and using it: its
/// patch records, its tessellation (trianglesPerPatch() lattice triangles per patch, each with
/// its share of welded vertices and normals, for OBJ/PLY output and for tracing tessellated
/// models), the JSON of its patches, or the geometry Embree traces. Measured as peak resident
/// memory on icospheres of 20k and 82k triangles; an estimate, within a factor of 2 of what
/// those measurements found. An unknown name costs what the dearest model costs (makeModel
/// refuses it later).
uint64_t modelBytesPerTriangle(std::string_view model, const Tessellation& tessellation,
                               ModelUse use);

/// The part of a model's cost that grows with the mesh only up to a cap, beside
/// modelBytesPerTriangle: the regions quadric-g1 traces beyond one per piece
/// (defaultSubPatchBudget: 2 per piece, three pieces per triangle, at most 2^21 per mesh; the
/// first region of each piece is in modelBytesPerTriangle), when it is rendered; the block of a
/// streamed surface (its points, triangles and text, about kTessellationBlockPoints points at
/// most). Zero for every other model and use; an unknown name costs the dearest model's.
struct CappedModelBytes {
  uint64_t perTriangle = 0;  ///< while below the cap
  uint64_t cap = 0;          ///< per mesh
  uint64_t floor = 0;        ///< per mesh, however few its triangles
};
CappedModelBytes modelCappedBytes(std::string_view model, ModelUse use,
                                  const Tessellation& tessellation = {});

/// Makes `budget` charge each mesh loaded with it what `model` costs for `use` (its
/// bytesPerTriangle and capped bytes); with `dearest`, only raises them (several models, one at a
/// time, on one mesh).
void setModelBytes(MemoryBudget& budget, std::string_view model, const Tessellation& tessellation,
                   ModelUse use, bool dearest = false);

/// For an Adaptive `requested` tessellation, which setModelBytes charges at level 1: charges
/// `budget` what the lattice it resolved to (`resolved`) costs beyond that, on `triangles` input
/// triangles of `model` (`name` names the mesh in the error). Throws as chargeMemory does when
/// that is over the limit, before the tessellation is built. Nothing for other tessellations.
void chargeResolvedTessellation(MemoryBudget& budget, std::string_view model,
                                const Tessellation& requested, const Tessellation& resolved,
                                ModelUse use, uint64_t triangles, const std::string& name);

}  // namespace quadtri
