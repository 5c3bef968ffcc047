// Rough metal: Cook–Torrance reflection from a GGX microfacet surface.
#pragma once

#include "quadtri/render/bsdf/bsdf.h"
#include "quadtri/render/bsdf/ggx.h"
#include "quadtri/render/bsdf/ior_tables.h"

namespace quadtri {

/// Rough conductor: f = F(wi·h) D(h) G2(wi, wo) / (4 cos θi cos θo), h = (wi + wo)/|wi + wo|, with
/// isotropic GGX D, height-correlated Smith G2 and the exact complex Fresnel F. Samples visible
/// normals (Heitz 2018), so pdf(wo) = D_wi(h) / (4 wi·h) and the weight is F·G2/G1(wi).
/// One-sided: zero unless wi.z > 0 and wo.z > 0.
class RoughConductor final : public Bsdf {
 public:
  /// GGX roughness α ≥ 1e-4 (smaller lobes are Dirac-like in double precision: use Conductor);
  /// η, k as for Conductor. Anything else throws Error.
  RoughConductor(double alpha, const ConductorIor& ior);

  Color eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  std::optional<BsdfSample> sample(const Vec3& wi, const Vec2& u, double uLobe) const override;
  bool isDelta() const override { return false; }
  std::string toString() const override;

 private:
  GgxDistribution ggx_;
  ConductorIor ior_;
};

}  // namespace quadtri
