#include "quadtri/render/bsdf/conductor.h"

#include <fmt/format.h>

#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/fresnel.h"
#include "quadtri/render/sampling/frame.h"

namespace quadtri {

void validateConductorIor(const ConductorIor& ior, std::string_view bsdfName) {
  for (int c = 0; c < 3; ++c) {
    const double eta = ior.eta[c], k = ior.k[c];
    if (!(eta >= 0.0 && k >= 0.0 && std::isfinite(eta) && std::isfinite(k) && eta + k > 0.0))
      fail(
          "{}: eta and k must be finite, non-negative and not both zero, got eta = ({}, {}, {}), "
          "k = ({}, {}, {})",
          bsdfName, ior.eta[0], ior.eta[1], ior.eta[2], ior.k[0], ior.k[1], ior.k[2]);
  }
}

Conductor::Conductor(const ConductorIor& ior) : ior_(ior) {
  validateConductorIor(ior, "conductor");
}

std::optional<BsdfSample> Conductor::sample(const Vec3& wi, const Vec2&, double) const {
  if (wi.z() <= 0.0) return std::nullopt;
  BsdfSample s;
  s.wo = reflectLocal(wi);
  s.pdf = 1.0;
  s.delta = true;
  s.weight = fresnelConductor(wi.z(), ior_.eta, ior_.k);
  return s;
}

std::string Conductor::toString() const {
  return fmt::format(
      "<bsdf type=\"conductor\"><rgb name=\"eta\" value=\"{}, {}, {}\"/>"
      "<rgb name=\"k\" value=\"{}, {}, {}\"/></bsdf>",
      ior_.eta[0], ior_.eta[1], ior_.eta[2], ior_.k[0], ior_.k[1], ior_.k[2]);
}

}  // namespace quadtri
