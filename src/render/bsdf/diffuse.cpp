#include "quadtri/render/bsdf/diffuse.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"
#include "quadtri/render/sampling/warp.h"

namespace quadtri {

Diffuse::Diffuse(const Color& reflectance) : reflectance_(reflectance) {
  for (int c = 0; c < 3; ++c)
    if (!(reflectance[c] >= 0.0 && reflectance[c] <= 1.0))
      fail("diffuse: reflectance must lie in [0, 1] per channel, got ({}, {}, {})", reflectance[0],
           reflectance[1], reflectance[2]);
}

Color Diffuse::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z() <= 0.0 || wo.z() <= 0.0) return Color::Zero();
  return reflectance_ * (wo.z() / kPi);
}

double Diffuse::pdf(const Vec3& wi, const Vec3& wo) const {
  if (wi.z() <= 0.0 || wo.z() <= 0.0) return 0.0;
  return squareToCosineHemispherePdf(wo);
}

std::optional<BsdfSample> Diffuse::sample(const Vec3& wi, const Vec2& u, double) const {
  if (wi.z() <= 0.0) return std::nullopt;
  BsdfSample s;
  s.wo = squareToCosineHemisphere(u);
  s.pdf = squareToCosineHemispherePdf(s.wo);
  // The disk's rim maps to wo.z = 0, where f·cos θo and the pdf both vanish.
  if (!(s.wo.z() > 0.0)) return std::nullopt;
  s.weight = reflectance_;
  return s;
}

std::string Diffuse::toString() const {
  return fmt::format(
      "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"{}, {}, {}\"/></bsdf>",
      reflectance_[0], reflectance_[1], reflectance_[2]);
}

}  // namespace quadtri
