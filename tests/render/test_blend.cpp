// blendbsdf (render/bsdf/blend.h): the mixture's eval and pdf, its sampling against its pdf,
// its albedo, and a Dirac lobe inside the mixture.
#include <gtest/gtest.h>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/blend.h"
#include "quadtri/render/bsdf/conductor.h"
#include "quadtri/render/bsdf/diffuse.h"
#include "quadtri/render/bsdf/ior_tables.h"
#include "quadtri/render/bsdf/rough_conductor.h"
#include "quadtri/render/sampling/warp.h"
#include "render/bsdf_checks.h"

namespace quadtri {
namespace {

using namespace quadtri::testing;

TEST(Blend, EvalAndPdfAreTheMixture) {
  const auto diffuse = std::make_shared<Diffuse>(Color(0.8, 0.5, 0.2));
  const auto rough = std::make_shared<RoughConductor>(0.3, lookupConductor("Au"));
  const Blend blend(diffuse, rough, 0.3);
  Pcg32 rng(7);
  for (int i = 0; i < 500; ++i) {
    const Vec3 wi = squareToUniformSphere(rng.next2D()), wo = squareToUniformSphere(rng.next2D());
    const Color f = 0.7 * diffuse->eval(wi, wo) + 0.3 * rough->eval(wi, wo);
    EXPECT_LT((blend.eval(wi, wo) - f).abs().maxCoeff(), 1e-15);
    EXPECT_NEAR(blend.pdf(wi, wo), 0.7 * diffuse->pdf(wi, wo) + 0.3 * rough->pdf(wi, wo), 1e-15);
  }
  EXPECT_FALSE(blend.isDelta());
  EXPECT_FALSE(blend.transmits());
}

TEST(Blend, SamplingMatchesItsPdfAndItsAlbedoIsTheMixture) {
  const auto diffuse = std::make_shared<Diffuse>(Color(0.8, 0.5, 0.2));
  const auto rough = std::make_shared<RoughConductor>(0.2, lookupConductor("Cu"));
  const Blend blend(diffuse, rough, 0.4);
  for (const double theta : {10.0, 60.0}) {
    const Vec3 wi = directionAt(theta, 30.0);
    expectSamplingMatchesPdf(blend, wi, 11, 0.01);
    const Albedo a = sampledAlbedo(blend, wi, 200000, 12);
    const Albedo d = sampledAlbedo(*diffuse, wi, 200000, 13);
    const Albedo r = sampledAlbedo(*rough, wi, 200000, 14);
    for (int c = 0; c < 3; ++c) {
      const double expected = 0.6 * d.mean[c] + 0.4 * r.mean[c];
      const double sigma = std::sqrt(a.standardError[c] * a.standardError[c] +
                                     0.36 * d.standardError[c] * d.standardError[c] +
                                     0.16 * r.standardError[c] * r.standardError[c]);
      EXPECT_NEAR(a.mean[c], expected, 5 * sigma) << "theta " << theta << " channel " << c;
    }
  }
}

TEST(Blend, ADiracLobeKeepsItsWeightAndTheChanceOfItsBsdf) {
  const auto diffuse = std::make_shared<Diffuse>(Color::Constant(0.5));
  const auto mirror = std::make_shared<Conductor>(ConductorIor{Color::Zero(), Color::Ones()});
  const Blend blend(diffuse, mirror, 0.25);
  const Vec3 wi = directionAt(40.0, 10.0);
  // uLobe below the weight picks the mirror: a Dirac sample with the mirror's own weight.
  const auto m = blend.sample(wi, Vec2(0.3, 0.7), 0.1);
  const auto alone = mirror->sample(wi, Vec2(0.3, 0.7), 0.4);
  ASSERT_TRUE(m && alone);
  EXPECT_TRUE(m->delta);
  EXPECT_LT((m->wo - alone->wo).norm(), 1e-15);
  EXPECT_LT((m->weight - alone->weight).abs().maxCoeff(), 1e-15);
  EXPECT_NEAR(m->pdf, 0.25 * alone->pdf, 1e-15);
  // Above it, the diffuse lobe: its pdf is the mixture's, which the mirror adds nothing to.
  const auto d = blend.sample(wi, Vec2(0.3, 0.7), 0.9);
  ASSERT_TRUE(d);
  EXPECT_FALSE(d->delta);
  EXPECT_NEAR(d->pdf, 0.75 * diffuse->pdf(wi, d->wo), 1e-15);
  EXPECT_LT((d->weight - diffuse->eval(wi, d->wo) / diffuse->pdf(wi, d->wo)).abs().maxCoeff(),
            1e-12);
  EXPECT_FALSE(blend.isDelta());
  EXPECT_TRUE(Blend(mirror, mirror, 0.5).isDelta());
}

TEST(Blend, RefusesAMissingBsdfOrAWeightOutsideTheUnitInterval) {
  const auto diffuse = std::make_shared<Diffuse>(Color::Constant(0.5));
  EXPECT_THROW(Blend(diffuse, nullptr, 0.5), Error);
  EXPECT_THROW(Blend(diffuse, diffuse, 1.5), Error);
  EXPECT_THROW(Blend(diffuse, diffuse, -0.1), Error);
  EXPECT_NO_THROW(Blend(diffuse, diffuse, 0.0));
  EXPECT_NO_THROW(Blend(diffuse, diffuse, 1.0));
}

}  // namespace
}  // namespace quadtri
