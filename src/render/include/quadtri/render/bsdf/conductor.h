// Smooth metal: a perfect mirror tinted by the conductor's Fresnel reflectance.
#pragma once

#include "quadtri/render/bsdf/bsdf.h"
#include "quadtri/render/bsdf/ior_tables.h"

namespace quadtri {

/// Smooth conductor (Dirac lobe): wo = (−x, −y, z) with weight F(cos θi; η + i·k), the exact
/// complex Fresnel reflectance. One-sided: no sample when wi.z ≤ 0.
class Conductor final : public Bsdf {
 public:
  /// η ≥ 0 and k ≥ 0 per channel, not both zero (else Error); see lookupConductor.
  explicit Conductor(const ConductorIor& ior);

  Color eval(const Vec3&, const Vec3&) const override { return Color::Zero(); }
  double pdf(const Vec3&, const Vec3&) const override { return 0.0; }
  std::optional<BsdfSample> sample(const Vec3& wi, const Vec2& u, double uLobe) const override;
  bool isDelta() const override { return true; }
  std::string toString() const override;

 private:
  ConductorIor ior_;
};

/// Throws Error unless η ≥ 0 and k ≥ 0 are finite and not both zero in every channel.
void validateConductorIor(const ConductorIor& ior, std::string_view bsdfName);

}  // namespace quadtri
