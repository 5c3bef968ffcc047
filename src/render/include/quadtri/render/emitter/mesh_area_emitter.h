// Mitsuba's `area` emitter on a triangle mesh.
#pragma once

#include <memory>
#include <vector>

#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/render/emitter/emitter.h"

namespace quadtri {

/// Uniform radiance L leaving the front (winding-normal) side of every triangle. Points are
/// sampled uniformly by area: a triangle with probability area/total through a CDF, then
/// uniform barycentrics, so the solid-angle pdf is d² / (A_total · |cos θ_light|).
class MeshAreaEmitter final : public Emitter {
 public:
  /// `mesh` is in world space and must have positive total area.
  MeshAreaEmitter(std::shared_ptr<const TriangleMesh> mesh, const Color& radiance);
  std::optional<LightSample> sampleLi(const Vec3& ref, const Vec2& u) const override;
  double pdfLi(const Vec3& ref, const Vec3& direction, const Vec3& lightPoint,
               const Vec3& lightNormal) const override;
  Color eval(const Vec3& normal, const Vec3& w) const override;
  /// Φ = π L A (one-sided Lambertian emitter).
  double power(const Bounds3& sceneBounds) const override;
  std::string toString() const override;

 private:
  std::shared_ptr<const TriangleMesh> mesh_;
  Color radiance_;
  std::vector<double> cdf_;  ///< cumulative triangle areas, normalised to end at 1
  double totalArea_ = 0.0;
};

}  // namespace quadtri
