#include "quadtri/render/bsdf/fresnel.h"

#include <cmath>
#include <complex>

namespace quadtri {

DielectricFresnel fresnelDielectric(double cosThetaI, double eta) {
  DielectricFresnel out;
  const bool outside = cosThetaI >= 0.0;
  out.etaTI = outside ? eta : 1.0 / eta;
  const double cosI = std::abs(cosThetaI);
  const double sin2T = (1.0 - cosI * cosI) / (out.etaTI * out.etaTI);
  if (sin2T >= 1.0) return out;  // total internal reflection: F = 1, no refracted ray
  const double cosT = std::sqrt(1.0 - sin2T);
  // Divided through by η_i, so only the ratio η = η_t/η_i appears.
  const double n = out.etaTI;
  const double rs = (cosI - n * cosT) / (cosI + n * cosT);
  const double rp = (n * cosI - cosT) / (n * cosI + cosT);
  out.reflectance = 0.5 * (rs * rs + rp * rp);
  out.cosThetaT = outside ? -cosT : cosT;
  return out;
}

Color fresnelConductor(double cosThetaI, const Color& eta, const Color& k) {
  const double cosI = std::clamp(std::abs(cosThetaI), 0.0, 1.0);
  const double sin2I = 1.0 - cosI * cosI;
  Color f;
  for (int c = 0; c < 3; ++c) {
    const std::complex<double> n(eta[c], k[c]);
    // Principal root: Re ≥ 0 picks the wave that decays into the absorbing medium.
    const std::complex<double> cosT = std::sqrt(1.0 - sin2I / (n * n));
    const std::complex<double> rs = (cosI - n * cosT) / (cosI + n * cosT);
    const std::complex<double> rp = (n * cosI - cosT) / (n * cosI + cosT);
    f[c] = 0.5 * (std::norm(rs) + std::norm(rp));
  }
  return f;
}

}  // namespace quadtri
