#include "quadtri/render/bsdf/dielectric.h"

#include <fmt/format.h>

#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/fresnel.h"
#include "quadtri/render/sampling/frame.h"

namespace quadtri {

Dielectric::Dielectric(double intIor, double extIor)
    : intIor_(intIor), extIor_(extIor), eta_(intIor / extIor) {
  if (!(intIor > 0.0 && std::isfinite(intIor)) || !(extIor > 0.0 && std::isfinite(extIor)))
    fail("dielectric: int_ior and ext_ior must be positive and finite, got {} and {}", intIor,
         extIor);
}

std::optional<BsdfSample> Dielectric::sample(const Vec3& wi, const Vec2&, double uLobe) const {
  const DielectricFresnel fresnel = fresnelDielectric(wi.z(), eta_);
  BsdfSample s;
  s.delta = true;
  if (uLobe < fresnel.reflectance) {
    s.wo = reflectLocal(wi);
    s.pdf = fresnel.reflectance;
    s.weight = Color::Ones();
    return s;
  }
  s.wo = refractLocal(wi, fresnel);
  s.pdf = 1.0 - fresnel.reflectance;
  s.weight = Color::Constant(1.0 / (fresnel.etaTI * fresnel.etaTI));
  s.eta = fresnel.etaTI;
  return s;
}

std::string Dielectric::toString() const {
  return fmt::format(
      "<bsdf type=\"dielectric\"><float name=\"int_ior\" value=\"{}\"/>"
      "<float name=\"ext_ior\" value=\"{}\"/></bsdf>",
      intIor_, extIor_);
}

}  // namespace quadtri
