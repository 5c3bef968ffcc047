#include "quadtri/geometry/model_geometry.h"

#include "quadtri/math/error.h"

namespace quadtri {

size_t ModelGeometry::primitiveCount() const {
  if (bezier) return bezier->size();
  return patches ? patches->size() : triangles.triangleCount();
}

size_t ModelGeometry::bytes() const {
  if (patches || bezier) return patchBytes;
  constexpr size_t kTriple = 3 * sizeof(float);
  size_t total = (triangles.positions.size() + triangles.triangles.size()) * kTriple;
  if (shadingNormals && triangles.hasNormals()) {
    total += triangles.normals.size() * kTriple;
    if (triangles.normalIndices != triangles.triangles)
      total += triangles.normalIndices.size() * kTriple;
  }
  return total;
}

ModelGeometry modelGeometry(const SurfaceModel& model, const Tessellation& tessellation) {
  ModelGeometry g;
  switch (model.representation()) {
    case Representation::InputTriangles:
      g.triangles = model.mesh();
      g.shadingNormals = model.interpolatesShadingNormals();
      g.liftRayOrigins = g.shadingNormals && model.liftsRayOrigins();
      break;
    case Representation::Tessellated:
      g.triangles = tessellate(model, tessellation);
      g.shadingNormals = true;
      break;
    case Representation::Implicit:
      g.patches = &model.renderPatches();
      g.mesh = &model.mesh();
      g.patchBytes = model.patchMemoryBytes();
      if (model.quadricPatches().size() != model.patchCount() ||
          g.patches->size() < model.patchCount())
        fail("model '{}': {} quadric patches for {} triangles", model.name(),
             model.quadricPatches().size(), model.patchCount());
      break;
    case Representation::Bezier:
      g.bezier = &model.bezierPieces();
      g.mesh = &model.mesh();
      if (g.bezier->empty())
        fail("model '{}': a Bezier model without Bézier pieces ({} triangles)", model.name(),
             model.patchCount());
      for (size_t i = 0; i < g.bezier->size(); ++i)
        if ((*g.bezier)[i].triangle >= model.patchCount())
          fail("model '{}': Bézier piece {} names triangle {} of {}", model.name(), i,
               (*g.bezier)[i].triangle, model.patchCount());
      g.patchBytes = model.patchMemoryBytes();
      if (g.patchBytes == 0) g.patchBytes = g.bezier->size() * sizeof(BezierTriangle);
      break;
  }
  return g;
}

uint32_t addModelGeometry(Accel& accel, const ModelGeometry& geometry) {
  if (geometry.bezier) return accel.addBezierTriangles(*geometry.bezier);
  return geometry.patches ? accel.addQuadricPatches(*geometry.patches, geometry.mesh)
                          : accel.addTriangles(geometry.triangles);
}

uint32_t addModelGeometry(Accel& accel, const SurfaceModel& model,
                          const Tessellation& tessellation) {
  return addModelGeometry(accel, modelGeometry(model, tessellation));
}

}  // namespace quadtri
