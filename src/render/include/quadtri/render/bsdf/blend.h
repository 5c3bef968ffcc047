// A linear blend of two BSDFs, as Mitsuba 3's blendbsdf: (1 − weight)·first + weight·second.
#pragma once

#include <memory>

#include "quadtri/render/bsdf/bsdf.h"

namespace quadtri {

/// f = (1 − w) f₀ + w f₁, sampled by picking BSDF 1 with probability w (from uLobe) and the
/// other one otherwise. The pdf of a direction is the same mixture of the two pdfs; a direction
/// drawn from a Dirac lobe keeps its lobe's weight, with the discrete probability times the
/// chance of picking its BSDF.
class Blend final : public Bsdf {
 public:
  /// Throws Error for a null BSDF or a weight outside [0, 1].
  Blend(std::shared_ptr<const Bsdf> first, std::shared_ptr<const Bsdf> second, double weight);
  Color eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  std::optional<BsdfSample> sample(const Vec3& wi, const Vec2& u, double uLobe) const override;
  bool isDelta() const override { return first_->isDelta() && second_->isDelta(); }
  bool transmits() const override { return first_->transmits() || second_->transmits(); }
  std::string toString() const override;

 private:
  std::shared_ptr<const Bsdf> first_, second_;
  double weight_;
};

}  // namespace quadtri
