// Internal to src/scene: what the triangle-mesh shape plugins share when they build.
#pragma once

#include <memory>
#include <string>

#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/scene/plugin.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

class SurfaceModel;

/// Places a mesh in the world: positions by M, normals by M⁻ᵀ. A mirroring M (det < 0) or
/// flip_normals reverses the winding, so face and shading normals keep pointing the same way.
void transformMesh(TriangleMesh& mesh, const Mat4& toWorld, bool flipNormals);

/// Places `mesh` by the shape's to_world and flip_normals, converts it with `model` and adds it
/// to the scene with the shape's BSDF and area radiance; returns the converted model.
std::shared_ptr<const SurfaceModel> addMeshShape(ShapeBuildContext& context, TriangleMesh mesh,
                                                 const std::string& model,
                                                 const Tessellation& tessellation);

}  // namespace quadtri
