// Statistical helpers for Monte Carlo tests: the chi-square goodness-of-fit test of a sampler
// against its claimed density (as in Nori's and Mitsuba's chi2 tests) and the normal tail used by
// Z-tests of means.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "quadtri/math/vec.h"

namespace quadtri::testing {

/// Q(a, x) = Γ(a, x) / Γ(a), the upper regularized incomplete gamma function.
double regularizedGammaQ(double a, double x);

/// P(X ≥ statistic) for X ~ χ² with `dof` degrees of freedom.
inline double chi2Survival(double statistic, int dof) {
  return regularizedGammaQ(0.5 * dof, 0.5 * statistic);
}

/// Šidák's per-test level so that `testCount` independent tests reject a true null hypothesis
/// with probability `familyLevel` overall: 1 − (1 − α)^(1/m).
double sidakLevel(double familyLevel, int testCount);

/// Outcome of a chi-square test; `report` lists the statistic and the worst cells on failure.
struct Chi2Result {
  double pValue = 0.0;
  int dof = 0;
  double statistic = 0.0;
  std::string report;
};

/// Chi-square test of `sampleCount` draws of `sample` (points of the parameter square [0,1]²,
/// nullopt for a draw the sampler rejects) against `density` (per unit parameter area). Expected
/// counts per cell of a resX × resY grid come from 8×8-point Gauss–Legendre quadrature on 4×4
/// sub-cells of the density (nodes strictly inside cells, so densities that jump on cell edges
/// integrate exactly); the rejected draws form one more cell whose expected count is N·(1 −
/// ∫density). Cells expecting fewer than 5 are pooled; a draw in a cell of zero density fails
/// outright.
Chi2Result chi2Test(int resX, int resY, int sampleCount,
                    const std::function<std::optional<Vec2>()>& sample,
                    const std::function<double(const Vec2&)>& density);

/// Chi-square test of a direction sampler against its solid-angle pdf over a (θ, φ) grid of
/// 18 × 36 cells (10° each: cones of 40° and the horizon fall on cell edges).
Chi2Result sphericalChi2Test(int sampleCount, const std::function<std::optional<Vec3>()>& sample,
                             const std::function<double(const Vec3&)>& pdf);

/// P(|Z| ≥ |z|) for a standard normal Z: the two-sided p-value of a Z-test.
double twoSidedNormalPValue(double z);

}  // namespace quadtri::testing
