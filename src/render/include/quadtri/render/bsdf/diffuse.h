// Lambertian reflection.
#pragma once

#include "quadtri/render/bsdf/bsdf.h"

namespace quadtri {

/// Ideal diffuse reflector: f = R/π on the front side, sampled with a cosine-weighted hemisphere
/// so the weight f·cos θo / pdf is exactly R. One-sided: zero unless wi.z > 0 and wo.z > 0.
class Diffuse final : public Bsdf {
 public:
  /// `reflectance` R per channel in [0, 1]; anything else throws Error (it would create energy).
  explicit Diffuse(const Color& reflectance);

  Color eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  std::optional<BsdfSample> sample(const Vec3& wi, const Vec2& u, double uLobe) const override;
  bool isDelta() const override { return false; }
  std::string toString() const override;

  const Color& reflectance() const { return reflectance_; }

 private:
  Color reflectance_;
};

}  // namespace quadtri
