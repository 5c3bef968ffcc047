// Makes one-sided reflectors look the same from both sides of a surface.
#pragma once

#include <memory>

#include "quadtri/render/bsdf/bsdf.h"

namespace quadtri {

/// Two-sided adapter: for wi.z ≥ 0 the front BSDF sees (wi, wo); for wi.z < 0 the back BSDF
/// sees both directions mirrored through the surface, (x, y, −z), and sampled directions are
/// mirrored back. Transmission between the sides stays zero, as the nested BSDFs are one-sided.
class TwoSided final : public Bsdf {
 public:
  /// The same BSDF on both sides; null or transmitting BSDFs throw Error (a dielectric is already
  /// two-sided, and mirroring it would turn refraction into reflection).
  explicit TwoSided(std::shared_ptr<const Bsdf> both);
  /// Different BSDFs on the front (+z) and back (−z) sides, as Mitsuba's twosided with two.
  TwoSided(std::shared_ptr<const Bsdf> front, std::shared_ptr<const Bsdf> back);

  Color eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  std::optional<BsdfSample> sample(const Vec3& wi, const Vec2& u, double uLobe) const override;
  bool isDelta() const override { return front_->isDelta() && back_->isDelta(); }
  std::string toString() const override;

 private:
  std::shared_ptr<const Bsdf> front_, back_;
};

}  // namespace quadtri
