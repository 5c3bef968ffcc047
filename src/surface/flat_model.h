// `flat` and `shading`: the input triangles themselves.
#pragma once

#include "surface/model.h"

namespace quadtri {

/// The input triangles. `flat` renders with geometric normals; `shading` (the thesis' baseline
/// "Triángulos shading") renders the same geometry with interpolated shading normals. Both have
/// the flat triangle as their geometric surface, so their analysis is identical.
class FlatModel final : public SurfaceModel {
 public:
  FlatModel(std::shared_ptr<const TriangleMesh> mesh, bool interpolateNormals)
      : SurfaceModel(std::move(mesh)), shading_(interpolateNormals) {}
  std::string_view name() const override { return shading_ ? "shading" : "flat"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  Representation representation() const override { return Representation::InputTriangles; }
  bool interpolatesShadingNormals() const override { return shading_; }
  nlohmann::json patchJson(size_t t) const override;

 private:
  bool shading_;
};

}  // namespace quadtri
