// The GGX (Trowbridge–Reitz) microfacet distribution with Smith masking, for rough BSDFs.
#pragma once

#include "quadtri/math/vec.h"

namespace quadtri {

/// Isotropic GGX normal distribution of roughness α (Walter et al. 2007) in the local frame.
class GgxDistribution {
 public:
  explicit GgxDistribution(double alpha) : alpha_(alpha) {}

  double alpha() const { return alpha_; }
  /// D(m) = α² / (π (cos²θm (α² − 1) + 1)²), normalized so ∫ D(m) cos θm dωm = 1.
  double D(const Vec3& m) const;
  /// Smith Λ(w) = (√(1 + α² tan²θ) − 1) / 2.
  double lambda(const Vec3& w) const;
  /// Smith masking G1(w) = 1 / (1 + Λ(w)).
  double G1(const Vec3& w) const { return 1.0 / (1.0 + lambda(w)); }
  /// Height-correlated masking-shadowing G2 = 1 / (1 + Λ(wi) + Λ(wo)) (Heitz 2014, eq. 99);
  /// symmetric in wi and wo, which keeps the BSDF reciprocal.
  double G2(const Vec3& wi, const Vec3& wo) const { return 1.0 / (1.0 + lambda(wi) + lambda(wo)); }
  /// Samples a normal m from the visible-normal distribution D_wi(m) = G1(wi) max(0, wi·m) D(m) /
  /// cos θi (Heitz 2018: stretch to α = 1, sample the projected hemisphere, unstretch).
  Vec3 sampleVisible(const Vec3& wi, const Vec2& u) const;
  /// D_wi(m), the density of sampleVisible w.r.t. solid angle of m; needs wi.z > 0.
  double pdfVisible(const Vec3& wi, const Vec3& m) const;

 private:
  double alpha_;
};

}  // namespace quadtri
