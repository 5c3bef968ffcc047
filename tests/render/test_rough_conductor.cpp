#include <gtest/gtest.h>

#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/ggx.h"
#include "quadtri/render/bsdf/rough_conductor.h"
#include "quadtri/render/sampling/warp.h"
#include "render/bsdf_checks.h"

namespace quadtri {
namespace {

using namespace quadtri::testing;

constexpr double kAlphas[] = {0.1, 0.3, 0.7};
constexpr double kIncidences[] = {0.0, 45.0, 80.0};  // degrees from the normal
// Chi-square tests in this file (alphas × incidences) form one family at level 0.01.
const double kLevel = sidakLevel(0.01, 9);

TEST(Ggx, DistributionIsNormalized) {
  // ∫ D(m) cos θm dωm = 1: the projected microfacet area equals the macro-surface's. Midpoint
  // rule in θ (D is isotropic, the φ integral is 2π).
  for (double alpha : {0.05, 0.1, 0.3, 0.7, 1.0}) {
    const GgxDistribution ggx(alpha);
    const int n = 200000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double theta = (i + 0.5) * (0.5 * kPi / n);
      const Vec3 m(std::sin(theta), 0.0, std::cos(theta));
      sum += ggx.D(m) * m.z() * std::sin(theta);
    }
    EXPECT_NEAR(sum * 2.0 * kPi * (0.5 * kPi / n), 1.0, 1e-6) << "alpha " << alpha;
  }
}

TEST(Ggx, VisibleNormalsIntegrateToOne) {
  // ∫ G1(wi) max(0, wi·m) D(m) / cos θi dωm = 1 (the masking function's defining identity),
  // estimated with cosine-weighted m and checked by a Z-test.
  const int n = 200000;
  for (double alpha : kAlphas) {
    const GgxDistribution ggx(alpha);
    const Vec3 wi = directionAt(60.0, 0.0);
    Pcg32 rng(31);
    double sum = 0.0, sumSq = 0.0;
    for (int i = 0; i < n; ++i) {
      const Vec3 m = squareToCosineHemisphere(rng.next2D());
      const double pdf = squareToCosineHemispherePdf(m);
      if (!(pdf > 0.0)) continue;
      const double x = ggx.pdfVisible(wi, m) / pdf;
      sum += x;
      sumSq += x * x;
    }
    const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / n);
    EXPECT_GT(twoSidedNormalPValue((mean - 1.0) / se), sidakLevel(0.01, 3))
        << "alpha " << alpha << ": " << mean << " ± " << se;
  }
}

class RoughConductorSampling : public ::testing::TestWithParam<double> {};

TEST_P(RoughConductorSampling, MatchesPdf) {
  const double alpha = GetParam();
  const RoughConductor bsdf(alpha, lookupConductor("Au"));
  uint64_t seed = 40 + uint64_t(100 * alpha);
  for (double theta : kIncidences)
    expectSamplingMatchesPdf(bsdf, directionAt(theta, 25.0), ++seed, kLevel);
}

INSTANTIATE_TEST_SUITE_P(Alphas, RoughConductorSampling, ::testing::ValuesIn(kAlphas));

TEST(RoughConductor, ConservesEnergy) {
  // With a perfect-mirror Fresnel term the albedo is the single-scattering fraction ≤ 1; the
  // sampled estimate must agree with an independent uniform-hemisphere estimate of ∫ eval.
  const ConductorIor mirror = lookupConductor("none");
  const int n = 100000;
  const int zTests = 9;
  uint64_t seed = 60;
  for (double alpha : kAlphas)
    for (double theta : kIncidences) {
      const RoughConductor bsdf(alpha, mirror);
      const Vec3 wi = directionAt(theta, 0.0);
      const Albedo sampled = sampledAlbedo(bsdf, wi, n, ++seed);
      EXPECT_LE(sampled.mean[0], 1.0 + 3.0 * sampled.standardError[0]);
      Pcg32 rng(++seed);
      double sum = 0.0, sumSq = 0.0;
      for (int i = 0; i < n; ++i) {
        const Vec3 wo = squareToUniformHemisphere(rng.next2D());
        const double x = bsdf.eval(wi, wo)[0] / squareToUniformHemispherePdf(wo);
        sum += x;
        sumSq += x * x;
      }
      const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / n);
      const double z = (sampled.mean[0] - mean) / std::hypot(sampled.standardError[0], se);
      EXPECT_GT(twoSidedNormalPValue(z), sidakLevel(0.01, zTests))
          << "alpha " << alpha << " theta " << theta << ": sampled " << sampled.mean[0] << " ± "
          << sampled.standardError[0] << ", uniform " << mean << " ± " << se;
    }
  // Nearly smooth at normal incidence almost nothing is masked.
  const Albedo smooth = sampledAlbedo(RoughConductor(0.01, mirror), Vec3(0, 0, 1), 10000, 70);
  EXPECT_GT(smooth.mean[0], 0.999);
}

TEST(RoughConductor, IsReciprocal) {
  Pcg32 rng(80);
  for (double alpha : kAlphas) {
    const RoughConductor bsdf(alpha, lookupConductor("Cu"));
    for (int i = 0; i < 2000; ++i) {
      const Vec3 a = squareToUniformHemisphere(rng.next2D());
      const Vec3 b = squareToUniformHemisphere(rng.next2D());
      const Color fab = bsdf.eval(a, b) / b.z(), fba = bsdf.eval(b, a) / a.z();
      EXPECT_TRUE(((fab - fba).abs() <= 1e-9 * fab.abs().max(fba.abs())).all())
          << fab.transpose() << " vs " << fba.transpose();
    }
    EXPECT_TRUE(isBlack(bsdf.eval(Vec3(0, 0.6, 0.8), Vec3(0, 0.6, -0.8))));  // one-sided
    EXPECT_TRUE(isBlack(bsdf.eval(Vec3(0, 0.6, -0.8), Vec3(0, 0.6, 0.8))));
    EXPECT_FALSE(bsdf.sample(Vec3(0, 0.6, -0.8), Vec2(0.5, 0.5), 0.5));
  }
}

TEST(RoughConductor, RejectsInvalidRoughness) {
  EXPECT_THROW(RoughConductor(0.0, lookupConductor("Al")), Error);
  EXPECT_THROW(RoughConductor(std::nan(""), lookupConductor("Al")), Error);
}

}  // namespace
}  // namespace quadtri
