#include <gtest/gtest.h>

#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/conductor.h"
#include "quadtri/render/bsdf/fresnel.h"
#include "quadtri/render/sampling/frame.h"
#include "render/bsdf_checks.h"

namespace quadtri {
namespace {

using namespace quadtri::testing;

TEST(Fresnel, ConductorAtNormalIncidence) {
  for (const std::string& name : conductorNames()) {
    const ConductorIor ior = lookupConductor(name);
    const Color n = ior.eta, k = ior.k;
    const Color expected = ((n - 1.0).square() + k.square()) / ((n + 1.0).square() + k.square());
    const Color f = fresnelConductor(1.0, n, k);
    EXPECT_TRUE(((f - expected).abs() < 1e-12).all()) << name << ": " << f.transpose();
    EXPECT_TRUE(((fresnelConductor(1e-9, n, k) - 1.0).abs() < 1e-7).all()) << name;  // grazing
  }
}

TEST(Conductor, AlbedoIsTheFresnelReflectance) {
  // A smooth conductor reflects everything into the mirror direction, so its albedo is exactly
  // F(cos θi): one draw is the whole integral.
  const Conductor gold(lookupConductor("Au"));
  for (double cosI : {1.0, 0.7, 0.3, 0.05}) {
    const Vec3 wi(std::sqrt(1.0 - cosI * cosI), 0.0, cosI);
    const auto s = gold.sample(wi, Vec2(0.3, 0.7), 0.2);
    ASSERT_TRUE(s);
    EXPECT_TRUE(s->delta);
    EXPECT_LT((s->wo - reflectLocal(wi)).norm(), 1e-15);
    const Color f = fresnelConductor(cosI, lookupConductor("Au").eta, lookupConductor("Au").k);
    EXPECT_TRUE(((s->weight - f).abs() < 1e-15).all());
    EXPECT_TRUE((s->weight <= 1.0).all() && (s->weight > 0.0).all());
  }
  EXPECT_FALSE(gold.sample(Vec3(0, 0.6, -0.8), Vec2(0.3, 0.7), 0.2));  // one-sided
  EXPECT_TRUE(isBlack(gold.eval(Vec3(0, 0, 1), Vec3(0, 0, 1))));
  EXPECT_EQ(gold.pdf(Vec3(0, 0, 1), Vec3(0, 0, 1)), 0.0);
}

TEST(Conductor, NoneIsAPerfectMirrorAndMetalsHaveTheirColour) {
  const ConductorIor none = lookupConductor("none");
  for (double cosI = 0.0; cosI <= 1.0; cosI += 0.125)
    EXPECT_TRUE(((fresnelConductor(cosI, none.eta, none.k) - 1.0).abs() < 1e-12).all());
  const ConductorIor au = lookupConductor("Au"), ag = lookupConductor("Ag");
  const Color gold = fresnelConductor(1.0, au.eta, au.k);
  const Color silver = fresnelConductor(1.0, ag.eta, ag.k);
  EXPECT_GT(gold[0], gold[1]);  // gold is yellow: red > green > blue
  EXPECT_GT(gold[1], gold[2]);
  EXPECT_TRUE((silver > 0.9).all()) << silver.transpose();
}

TEST(Conductor, RejectsInvalidIndices) {
  EXPECT_THROW(Conductor({Color::Zero(), Color::Zero()}), Error);
  EXPECT_THROW(Conductor({Color(1.0, -0.5, 1.0), Color::Ones()}), Error);
}

}  // namespace
}  // namespace quadtri
