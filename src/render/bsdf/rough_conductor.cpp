#include "quadtri/render/bsdf/rough_conductor.h"

#include <fmt/format.h>

#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/conductor.h"
#include "quadtri/render/bsdf/fresnel.h"
#include "quadtri/render/sampling/frame.h"

namespace quadtri {

RoughConductor::RoughConductor(double alpha, const ConductorIor& ior) : ggx_(alpha), ior_(ior) {
  if (!(alpha >= 1e-4 && std::isfinite(alpha)))
    fail("roughconductor: alpha must be finite and at least 1e-4, got {}", alpha);
  validateConductorIor(ior, "roughconductor");
}

Color RoughConductor::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z() <= 0.0 || wo.z() <= 0.0) return Color::Zero();
  const Vec3 h = (wi + wo).normalized();
  // f·cos θo: the cos θo of the Cook–Torrance denominator cancels.
  const double scalar = ggx_.D(h) * ggx_.G2(wi, wo) / (4.0 * wi.z());
  return fresnelConductor(wi.dot(h), ior_.eta, ior_.k) * scalar;
}

double RoughConductor::pdf(const Vec3& wi, const Vec3& wo) const {
  if (wi.z() <= 0.0 || wo.z() <= 0.0) return 0.0;
  const Vec3 h = (wi + wo).normalized();
  // Jacobian of the reflection wo = reflect(wi, h): dωh/dωo = 1 / (4 wi·h).
  return ggx_.pdfVisible(wi, h) / (4.0 * wi.dot(h));
}

std::optional<BsdfSample> RoughConductor::sample(const Vec3& wi, const Vec2& u, double) const {
  if (wi.z() <= 0.0) return std::nullopt;
  const Vec3 m = ggx_.sampleVisible(wi, u);
  BsdfSample s;
  s.wo = reflect(wi, m);
  // Visible normals can still reflect below the horizon (multiple scattering is not modelled).
  if (s.wo.z() <= 0.0) return std::nullopt;
  s.pdf = pdf(wi, s.wo);
  if (!(s.pdf > 0.0)) return std::nullopt;
  // eval/pdf with D and the Jacobian cancelled: F · G2 / G1(wi).
  const double wiDotH = wi.dot((wi + s.wo).normalized());
  s.weight = fresnelConductor(wiDotH, ior_.eta, ior_.k) * (ggx_.G2(wi, s.wo) / ggx_.G1(wi));
  return s;
}

std::string RoughConductor::toString() const {
  return fmt::format(
      "<bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"ggx\"/>"
      "<float name=\"alpha\" value=\"{}\"/><rgb name=\"eta\" value=\"{}, {}, {}\"/>"
      "<rgb name=\"k\" value=\"{}, {}, {}\"/></bsdf>",
      ggx_.alpha(), ior_.eta[0], ior_.eta[1], ior_.eta[2], ior_.k[0], ior_.k[1], ior_.k[2]);
}

}  // namespace quadtri
