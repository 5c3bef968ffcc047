#include "quadtri/render/emitter/constant_emitter.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"
#include "quadtri/render/sampling/warp.h"

namespace quadtri {

ConstantEmitter::ConstantEmitter(const Color& radiance) : radiance_(radiance) {
  if (!radiance.allFinite() || (radiance < 0.0).any())
    fail("constant emitter: expected a finite, non-negative radiance");
}

std::optional<LightSample> ConstantEmitter::sampleLi(const Vec3&, const Vec2& u) const {
  LightSample s;
  s.direction = squareToUniformSphere(u);
  s.distance = kInfinity;
  s.pdf = squareToUniformSpherePdf(s.direction);
  s.radiance = radiance_;
  return s;
}

double ConstantEmitter::pdfLi(const Vec3&, const Vec3& direction, const Vec3&, const Vec3&) const {
  return squareToUniformSpherePdf(direction);
}

double ConstantEmitter::power(const Bounds3& sceneBounds) const {
  const double radius = std::max(0.5 * sceneBounds.diagonal().norm(), 1e-3);
  return kPi * luminance(radiance_) * 4.0 * kPi * radius * radius;
}

std::string ConstantEmitter::toString() const {
  return fmt::format("constant(radiance=[{}, {}, {}])", radiance_[0], radiance_[1], radiance_[2]);
}

}  // namespace quadtri
