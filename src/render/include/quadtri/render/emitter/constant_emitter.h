// Mitsuba's `constant` emitter: radiance L arriving from every direction.
#pragma once

#include "quadtri/render/emitter/emitter.h"

namespace quadtri {

/// A uniform environment; sampled uniformly over the sphere of directions (pdf 1/4π).
class ConstantEmitter final : public Emitter {
 public:
  explicit ConstantEmitter(const Color& radiance);
  std::optional<LightSample> sampleLi(const Vec3& ref, const Vec2& u) const override;
  /// 1/(4π) for every direction.
  double pdfLi(const Vec3&, const Vec3&, const Vec3&, const Vec3&) const override;
  Color eval(const Vec3&, const Vec3&) const override { return radiance_; }
  bool isEnvironment() const override { return true; }
  /// Flux entering the bounding sphere (radius R) of the scene: π L · 4π R².
  double power(const Bounds3& sceneBounds) const override;
  std::string toString() const override;

 private:
  Color radiance_;
};

}  // namespace quadtri
