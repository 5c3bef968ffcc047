#include <gtest/gtest.h>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/diffuse.h"
#include "quadtri/render/sampling/warp.h"
#include "render/bsdf_checks.h"

namespace quadtri {
namespace {

using namespace quadtri::testing;

// Chi-square tests in this file form one family at level 0.01.
const double kLevel = sidakLevel(0.01, 3);

TEST(Diffuse, SamplingMatchesPdf) {
  const Diffuse bsdf(Color(0.8, 0.5, 0.2));
  expectSamplingMatchesPdf(bsdf, directionAt(0.0, 0.0), 11, kLevel);
  expectSamplingMatchesPdf(bsdf, directionAt(45.0, 30.0), 12, kLevel);
  expectSamplingMatchesPdf(bsdf, directionAt(89.0, 200.0), 13, kLevel);
}

TEST(Diffuse, WhiteAlbedoIsOne) {
  const Diffuse bsdf(Color::Ones());
  const Vec3 wi = directionAt(60.0, 10.0);
  // The sampled weights are R exactly; the integral of eval itself, estimated with uniform
  // hemisphere sampling (2π · eval), must be R too: a Z-test against 1.
  const Albedo sampled = sampledAlbedo(bsdf, wi, 100000, 14);
  EXPECT_NEAR(sampled.mean[1], 1.0, 1e-12);
  Pcg32 rng(15);
  const int n = 200000;
  double sum = 0.0, sumSq = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec3 wo = squareToUniformHemisphere(rng.next2D());
    const double x = bsdf.eval(wi, wo)[1] / squareToUniformHemispherePdf(wo);
    sum += x;
    sumSq += x * x;
  }
  const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / n);
  EXPECT_GT(twoSidedNormalPValue((mean - 1.0) / se), 0.001) << mean << " ± " << se;
}

TEST(Diffuse, IsReciprocalAndOneSided) {
  const Diffuse bsdf(Color(0.3, 0.6, 0.9));
  Pcg32 rng(16);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = squareToUniformSphere(rng.next2D()), b = squareToUniformSphere(rng.next2D());
    const Color fab = bsdf.eval(a, b) / std::abs(b.z()), fba = bsdf.eval(b, a) / std::abs(a.z());
    EXPECT_TRUE(((fab - fba).abs() <= 1e-9 * fab.abs().max(fba.abs())).all());
    if (a.z() <= 0.0 || b.z() <= 0.0) {
      EXPECT_TRUE(isBlack(bsdf.eval(a, b)));
      EXPECT_EQ(bsdf.pdf(a, b), 0.0);
    }
  }
  EXPECT_FALSE(bsdf.sample(Vec3(0, 0, -1), Vec2(0.3, 0.3), 0.5));
}

TEST(Diffuse, RejectsReflectanceAboveOne) {
  EXPECT_THROW(Diffuse(Color(0.5, 1.2, 0.5)), Error);
  EXPECT_THROW(Diffuse(Color(0.5, std::nan(""), 0.5)), Error);
}

}  // namespace
}  // namespace quadtri
