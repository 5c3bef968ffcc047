// `flat`, `shading` and `shading-offset`: the input triangles themselves.
#pragma once

#include "quadtri/surface/model.h"

namespace quadtri {

/// The input triangles. `flat` renders with geometric normals; `shading` (the thesis' baseline
/// "Triángulos shading") renders the same geometry with interpolated shading normals;
/// `shading-offset` is `shading` whose rays leave from origins lifted by the shadow-terminator
/// offset (shading_offset.h). All three have the flat triangle as their geometric surface, so
/// their analysis is identical.
class FlatModel final : public SurfaceModel {
 public:
  enum class Normals {
    Geometric,           ///< flat
    Interpolated,        ///< shading
    InterpolatedOffset,  ///< shading-offset
  };
  FlatModel(std::shared_ptr<const TriangleMesh> mesh, Normals normals)
      : SurfaceModel(std::move(mesh)), normals_(normals) {}
  std::string_view name() const override;
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  Representation representation() const override { return Representation::InputTriangles; }
  bool interpolatesShadingNormals() const override { return normals_ != Normals::Geometric; }
  bool liftsRayOrigins() const override { return normals_ == Normals::InterpolatedOffset; }
  void patchRecord(size_t t, PatchRecord& out) const override;

 private:
  Normals normals_;
};

}  // namespace quadtri
