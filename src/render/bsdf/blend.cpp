#include "quadtri/render/bsdf/blend.h"

#include <fmt/format.h>

#include <algorithm>

#include "quadtri/math/error.h"

namespace quadtri {

Blend::Blend(std::shared_ptr<const Bsdf> first, std::shared_ptr<const Bsdf> second, double weight)
    : first_(std::move(first)), second_(std::move(second)), weight_(weight) {
  if (!first_ || !second_) fail("blendbsdf: needs two nested bsdfs");
  if (!(weight_ >= 0.0 && weight_ <= 1.0)) fail("blendbsdf: weight {} is not in [0, 1]", weight_);
}

Color Blend::eval(const Vec3& wi, const Vec3& wo) const {
  return (1.0 - weight_) * first_->eval(wi, wo) + weight_ * second_->eval(wi, wo);
}

double Blend::pdf(const Vec3& wi, const Vec3& wo) const {
  return (1.0 - weight_) * first_->pdf(wi, wo) + weight_ * second_->pdf(wi, wo);
}

std::optional<BsdfSample> Blend::sample(const Vec3& wi, const Vec2& u, double uLobe) const {
  // uLobe picks the BSDF and, rescaled to [0, 1), is reused for the lobe inside it.
  const bool second = uLobe < weight_;
  const double chance = second ? weight_ : 1.0 - weight_;
  if (!(chance > 0.0)) return std::nullopt;
  const double rest = std::min(second ? uLobe / weight_ : (uLobe - weight_) / (1.0 - weight_),
                               0x1.fffffffffffffp-1);
  std::optional<BsdfSample> s = (second ? second_ : first_)->sample(wi, u, rest);
  if (!s) return std::nullopt;
  if (s->delta) {
    // f = chance·f_lobe and the probability chance·p_lobe: the lobe's own weight.
    s->pdf *= chance;
    return s;
  }
  // A continuous direction: the other BSDF may have drawn it too.
  s->pdf = pdf(wi, s->wo);
  if (!(s->pdf > 0.0)) return std::nullopt;
  s->weight = eval(wi, s->wo) / s->pdf;
  return s;
}

std::string Blend::toString() const {
  return fmt::format("<bsdf type=\"blendbsdf\" weight={}>{}{}</bsdf>", weight_, first_->toString(),
                     second_->toString());
}

}  // namespace quadtri
