#include "quadtri/render/bsdf/twosided.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"

namespace quadtri {
namespace {

Vec3 mirrored(const Vec3& w) {
  return Vec3(w.x(), w.y(), -w.z());
}

void validateNested(const std::shared_ptr<const Bsdf>& bsdf) {
  if (!bsdf) fail("twosided: needs a nested bsdf");
  if (bsdf->transmits())
    fail("twosided: the nested bsdf must not transmit light, got {}", bsdf->toString());
}

}  // namespace

TwoSided::TwoSided(std::shared_ptr<const Bsdf> both) : TwoSided(both, both) {}

TwoSided::TwoSided(std::shared_ptr<const Bsdf> front, std::shared_ptr<const Bsdf> back)
    : front_(std::move(front)), back_(std::move(back)) {
  validateNested(front_);
  validateNested(back_);
}

Color TwoSided::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z() >= 0.0) return front_->eval(wi, wo);
  return back_->eval(mirrored(wi), mirrored(wo));
}

double TwoSided::pdf(const Vec3& wi, const Vec3& wo) const {
  if (wi.z() >= 0.0) return front_->pdf(wi, wo);
  return back_->pdf(mirrored(wi), mirrored(wo));
}

std::optional<BsdfSample> TwoSided::sample(const Vec3& wi, const Vec2& u, double uLobe) const {
  if (wi.z() >= 0.0) return front_->sample(wi, u, uLobe);
  std::optional<BsdfSample> s = back_->sample(mirrored(wi), u, uLobe);
  if (s) s->wo = mirrored(s->wo);
  return s;
}

std::string TwoSided::toString() const {
  if (front_ == back_) return fmt::format("<bsdf type=\"twosided\">{}</bsdf>", front_->toString());
  return fmt::format("<bsdf type=\"twosided\">{}{}</bsdf>", front_->toString(), back_->toString());
}

}  // namespace quadtri
