#include <gtest/gtest.h>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/dielectric.h"
#include "quadtri/render/bsdf/diffuse.h"
#include "quadtri/render/bsdf/rough_conductor.h"
#include "quadtri/render/bsdf/twosided.h"
#include "quadtri/render/sampling/warp.h"
#include "render/bsdf_checks.h"

namespace quadtri {
namespace {

using namespace quadtri::testing;

Vec3 mirrored(const Vec3& w) {
  return Vec3(w.x(), w.y(), -w.z());
}

TEST(TwoSided, BackSideMirrorsTheFront) {
  const auto rough = std::make_shared<RoughConductor>(0.3, lookupConductor("Au"));
  const TwoSided bsdf(rough);
  Pcg32 rng(90);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = squareToUniformSphere(rng.next2D()), b = squareToUniformSphere(rng.next2D());
    const bool sameSide = a.z() * b.z() > 0.0;
    const Vec3 fa = a.z() < 0.0 ? mirrored(a) : a, fb = a.z() < 0.0 ? mirrored(b) : b;
    EXPECT_TRUE((bsdf.eval(a, b) == rough->eval(fa, fb)).all());
    EXPECT_EQ(bsdf.pdf(a, b), rough->pdf(fa, fb));
    if (!sameSide) {
      EXPECT_TRUE(isBlack(bsdf.eval(a, b)));  // no light passes between the sides
    }
  }
  // Sampling from the back stays on the back and matches pdf() there.
  const Vec3 wiBack = directionAt(130.0, 40.0);
  const auto s = bsdf.sample(wiBack, Vec2(0.4, 0.6), 0.5);
  ASSERT_TRUE(s);
  EXPECT_LT(s->wo.z(), 0.0);
  expectSamplingMatchesPdf(bsdf, wiBack, 91, 0.01);
}

TEST(TwoSided, FrontAndBackCanDiffer) {
  const auto white = std::make_shared<Diffuse>(Color::Ones());
  const auto black = std::make_shared<Diffuse>(Color::Zero());
  const TwoSided bsdf(white, black);
  EXPECT_GT(bsdf.eval(Vec3(0, 0, 1), Vec3(0, 0.6, 0.8))[0], 0.0);
  EXPECT_TRUE(isBlack(bsdf.eval(Vec3(0, 0, -1), Vec3(0, 0.6, -0.8))));
}

TEST(TwoSided, RejectsTransmittingOrMissingBsdfs) {
  EXPECT_THROW(TwoSided(std::make_shared<Dielectric>(1.5, 1.0)), Error);
  EXPECT_THROW(TwoSided(nullptr), Error);
}

}  // namespace
}  // namespace quadtri
