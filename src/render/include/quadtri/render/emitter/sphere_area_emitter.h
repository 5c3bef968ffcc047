// Mitsuba's `area` emitter on an analytic sphere.
#pragma once

#include "quadtri/render/emitter/emitter.h"

namespace quadtri {

/// Uniform radiance L leaving a sphere on the side its normals face (outwards, or inwards when
/// flipped). Sampled by the cone of directions the sphere subtends from the reference point
/// (uniform over the whole sphere of directions from inside), whose pdf is 1/solid angle.
class SphereAreaEmitter final : public Emitter {
 public:
  SphereAreaEmitter(const Vec3& center, double radius, bool flipNormals, const Color& radiance);
  std::optional<LightSample> sampleLi(const Vec3& ref, const Vec2& u) const override;
  double pdfLi(const Vec3& ref, const Vec3& direction, const Vec3& lightPoint,
               const Vec3& lightNormal) const override;
  Color eval(const Vec3& normal, const Vec3& w) const override;
  /// Φ = π L · 4π r².
  double power(const Bounds3& sceneBounds) const override;
  std::string toString() const override;

 private:
  Vec3 center_;
  double radius_;
  double orientation_;  ///< +1: emits outwards, −1: inwards
  Color radiance_;
};

}  // namespace quadtri
