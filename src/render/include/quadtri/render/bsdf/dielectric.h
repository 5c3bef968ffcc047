// Smooth glass-like interface between two dielectrics.
#pragma once

#include "quadtri/render/bsdf/bsdf.h"

namespace quadtri {

/// Smooth dielectric interface (Dirac lobes only): reflects wo = (−x, −y, z) with probability
/// F and refracts by Snell's law with probability 1 − F, F the exact Fresnel reflectance, so the
/// weights are 1 and (η_i/η_t)² (radiance is compressed into the smaller solid angle of the
/// denser side; BsdfSample::eta = η_t/η_i lets the integrator undo it for Russian roulette).
/// Two-sided by nature: wi.z < 0 means the path arrives from inside (the int_ior side).
class Dielectric final : public Bsdf {
 public:
  /// Interior and exterior indices of refraction, each positive and finite (else Error).
  Dielectric(double intIor, double extIor);

  Color eval(const Vec3&, const Vec3&) const override { return Color::Zero(); }
  double pdf(const Vec3&, const Vec3&) const override { return 0.0; }
  std::optional<BsdfSample> sample(const Vec3& wi, const Vec2& u, double uLobe) const override;
  bool isDelta() const override { return true; }
  bool transmits() const override { return true; }
  std::string toString() const override;

  /// η = int_ior / ext_ior.
  double eta() const { return eta_; }

 private:
  double intIor_, extIor_, eta_;
};

}  // namespace quadtri
