// Mitsuba's `point` emitter: an isotropic point of radiant intensity I.
#pragma once

#include "quadtri/render/emitter/emitter.h"

namespace quadtri {

/// Li = I/d² from the single direction towards `position` (a Dirac light).
class PointEmitter final : public Emitter {
 public:
  PointEmitter(const Vec3& position, const Color& intensity);
  std::optional<LightSample> sampleLi(const Vec3& ref, const Vec2& u) const override;
  double pdfLi(const Vec3&, const Vec3&, const Vec3&, const Vec3&) const override { return 0.0; }
  Color eval(const Vec3&, const Vec3&) const override { return Color::Zero(); }
  bool isDelta() const override { return true; }
  /// Φ = 4π I.
  double power(const Bounds3& sceneBounds) const override;
  std::string toString() const override;

 private:
  Vec3 position_;
  Color intensity_;
};

}  // namespace quadtri
