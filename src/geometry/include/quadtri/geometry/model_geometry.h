// The render geometry of a surface model: what the renderer and the crack-rate analysis trace.
#pragma once

#include <vector>

#include "quadtri/geometry/accel.h"
#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/surface/bezier_triangle.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/quadric_patch.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

/// A model as render primitives: triangles (its mesh, or its tessellation), quadric patches or
/// Bézier pieces.
struct ModelGeometry {
  TriangleMesh triangles;                               ///< empty for Implicit and Bezier models
  const std::vector<QuadricPatch>* patches = nullptr;   ///< renderPatches(), for Implicit models
  const std::vector<BezierTriangle>* bezier = nullptr;  ///< bezierPieces(), for Bezier models
  /// For Implicit and Bezier models, the model's mesh: patch t and a Bézier piece stand for
  /// their triangle, an edge bridge for the two patches it joins (QuadricPatch::joins).
  const TriangleMesh* mesh = nullptr;
  bool shadingNormals = false;  ///< the triangles are rendered with their vertex normals
  bool liftRayOrigins = false;  ///< SurfaceModel::liftsRayOrigins() (shading-offset)
  /// SurfaceModel::patchMemoryBytes() for Implicit and Bezier models (for Bezier, the pieces'
  /// own size when the model reports none).
  size_t patchBytes = 0;

  /// Triangles, patches or pieces handed to Embree.
  size_t primitiveCount() const;
  /// Bytes of render geometry: float3 positions and uint3 indices as Embree gets them, plus
  /// float3 normals (and their uint3 indices when they are not the position indices) when
  /// rendered with them; or the patch or piece records.
  size_t bytes() const;
};

/// InputTriangles → the mesh; Tessellated → tessellate(model, tessellation); Implicit → the
/// model's render patches; Bezier → its pieces (both referenced: the model must outlive the
/// result; Error when a Bezier model has no pieces or one names no triangle of the mesh).
ModelGeometry modelGeometry(const SurfaceModel& model, const Tessellation& tessellation);

/// Adds the geometry to `accel` (one triangle geometry or one user geometry); returns its id.
/// The patches and pieces are referenced, so `geometry`'s model must outlive `accel`.
uint32_t addModelGeometry(Accel& accel, const ModelGeometry& geometry);

/// Shorthand for addModelGeometry(accel, modelGeometry(model, tessellation)).
uint32_t addModelGeometry(Accel& accel, const SurfaceModel& model,
                          const Tessellation& tessellation);

}  // namespace quadtri
