#include "quadtri/render/emitter/point_emitter.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"

namespace quadtri {

PointEmitter::PointEmitter(const Vec3& position, const Color& intensity)
    : position_(position), intensity_(intensity) {
  if (!allFinite(position) || !intensity.allFinite() || (intensity < 0.0).any())
    fail("point emitter: expected a finite position and a finite, non-negative intensity");
}

std::optional<LightSample> PointEmitter::sampleLi(const Vec3& ref, const Vec2&) const {
  const Vec3 toLight = position_ - ref;
  const double dist2 = toLight.squaredNorm();
  if (!(dist2 > 0.0)) return std::nullopt;
  LightSample s;
  s.distance = std::sqrt(dist2);
  s.direction = toLight / s.distance;
  s.radiance = intensity_ / dist2;
  s.pdf = 1.0;
  s.point = position_;
  s.delta = true;
  return s;
}

double PointEmitter::power(const Bounds3&) const {
  return 4.0 * kPi * luminance(intensity_);
}

std::string PointEmitter::toString() const {
  return fmt::format("point(position=[{}, {}, {}], intensity=[{}, {}, {}])", position_.x(),
                     position_.y(), position_.z(), intensity_[0], intensity_[1], intensity_[2]);
}

}  // namespace quadtri
