// Emitter sampling: pdfs consistent between sampleLi and pdfLi, and normalised (E[1/pdf] is
// the solid angle the light subtends); light selection in proportion to power.
#include <gtest/gtest.h>

#include "quadtri/geometry/rng.h"
#include "quadtri/math/error.h"
#include "quadtri/render/emitter/constant_emitter.h"
#include "quadtri/render/emitter/light_sampler.h"
#include "quadtri/render/emitter/mesh_area_emitter.h"
#include "quadtri/render/emitter/point_emitter.h"
#include "quadtri/render/emitter/sphere_area_emitter.h"
#include "render/chi2.h"

namespace quadtri::testing {
namespace {

// Mean of 1/pdf over the light's samples with its standard error.
struct SolidAngleEstimate {
  double mean = 0.0, standardError = 0.0;
};

SolidAngleEstimate estimateSolidAngle(const Emitter& light, const Vec3& ref, int count,
                                      const std::function<Vec3(const Vec3&)>& normalAt) {
  Pcg32 rng(17);
  double sum = 0.0, sumSq = 0.0;
  for (int i = 0; i < count; ++i) {
    const std::optional<LightSample> s = light.sampleLi(ref, rng.next2D());
    if (!s) continue;
    EXPECT_NEAR(s->pdf, light.pdfLi(ref, s->direction, s->point, normalAt(s->point)),
                1e-9 * s->pdf);
    EXPECT_NEAR((ref + s->distance * s->direction - s->point).norm(), 0.0, 1e-9);
    sum += 1.0 / s->pdf;
    sumSq += 1.0 / (s->pdf * s->pdf);
  }
  SolidAngleEstimate e;
  e.mean = sum / count;
  e.standardError = std::sqrt(std::max(0.0, sumSq / count - e.mean * e.mean) / count);
  return e;
}

TEST(MeshAreaEmitter, PdfIntegratesToTheRectangleSolidAngle) {
  // A 2×1 rectangle in the plane z = 0 facing +z, split unevenly into three triangles, seen
  // from (0, 0, d) on its axis: Ω = 4 arcsin(ab / √((a² + 4d²)(b² + 4d²))).
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {Vec3(-1, -0.5, 0), Vec3(1, -0.5, 0), Vec3(1, 0.5, 0), Vec3(-1, 0.5, 0),
                     Vec3(0.6, 0.5, 0)};
  mesh->triangles = {{0, 1, 4}, {1, 2, 4}, {0, 4, 3}};
  const MeshAreaEmitter light(mesh, Color::Constant(3.0));
  const double a = 2, b = 1, d = 0.8;
  const double omega =
      4.0 * std::asin(a * b / std::sqrt((a * a + 4 * d * d) * (b * b + 4 * d * d)));
  const SolidAngleEstimate e =
      estimateSolidAngle(light, Vec3(0, 0, d), 100000, [](const Vec3&) { return Vec3(0, 0, 1); });
  EXPECT_GT(twoSidedNormalPValue((e.mean - omega) / e.standardError), 1e-4)
      << e.mean << " vs " << omega;
  // One-sided: from behind there is nothing to sample, and eval is zero on the back.
  Pcg32 rng;
  EXPECT_FALSE(light.sampleLi(Vec3(0, 0, -1), rng.next2D()));
  EXPECT_TRUE(isBlack(light.eval(Vec3(0, 0, 1), Vec3(0, 0, -1))));
  EXPECT_NEAR(light.power(Bounds3{}), kPi * 3.0 * 2.0, 1e-12);
}

TEST(SphereAreaEmitter, PdfIntegratesToTheCapSolidAngle) {
  const Vec3 c(0.5, -1, 2);
  const double r = 0.7;
  const SphereAreaEmitter light(c, r, false, Color::Constant(1.0));
  const Vec3 ref = c + Vec3(0, 2.0, 0);
  const double omega = 2.0 * kPi * (1.0 - std::sqrt(1.0 - r * r / 4.0));
  const SolidAngleEstimate e =
      estimateSolidAngle(light, ref, 20000, [&](const Vec3& p) { return Vec3((p - c) / r); });
  EXPECT_NEAR(e.mean, omega, 1e-9);  // uniform cone sampling: 1/pdf is the solid angle itself
  // Every sample lands on the near, lit side of the sphere.
  Pcg32 rng(2);
  for (int i = 0; i < 1000; ++i) {
    const auto s = light.sampleLi(ref, rng.next2D());
    ASSERT_TRUE(s);
    EXPECT_NEAR((s->point - c).norm(), r, 1e-9);
    EXPECT_LT((s->point - c).dot(s->direction), 0.0);
  }
}

TEST(PointEmitter, InverseSquareFalloff) {
  const PointEmitter light(Vec3(1, 2, 3), Color(4, 8, 12));
  Pcg32 rng;
  const auto s = light.sampleLi(Vec3(1, 2, 1), rng.next2D());
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->delta);
  EXPECT_NEAR(s->distance, 2.0, 1e-15);
  EXPECT_TRUE(s->radiance.isApprox(Color(1, 2, 3)));
  EXPECT_TRUE(s->direction.isApprox(Vec3(0, 0, 1)));
  EXPECT_THROW(PointEmitter(Vec3::Zero(), Color(-1, 0, 0)), Error);
}

TEST(ConstantEmitter, UniformSphereSampling) {
  const ConstantEmitter env(Color::Constant(2.0));
  Pcg32 rng(9);
  const Chi2Result r = sphericalChi2Test(
      100000,
      [&]() -> std::optional<Vec3> { return env.sampleLi(Vec3::Zero(), rng.next2D())->direction; },
      [&](const Vec3& w) { return env.pdfLi(Vec3::Zero(), w, Vec3::Zero(), Vec3::Zero()); });
  EXPECT_GT(r.pValue, 1e-3) << r.report;
}

TEST(LightSampler, ChoosesInProportionToPower) {
  const PointEmitter a(Vec3::Zero(), Color::Constant(1.0));
  const PointEmitter b(Vec3::Zero(), Color::Constant(3.0));
  const PointEmitter dark(Vec3::Zero(), Color::Zero());
  const LightSampler sampler({&a, &dark, &b}, Bounds3{});
  EXPECT_NEAR(sampler.probability(&a), 0.25, 1e-15);
  EXPECT_NEAR(sampler.probability(&b), 0.75, 1e-15);
  EXPECT_EQ(sampler.probability(&dark), 0.0);
  Pcg32 rng(4);
  const int n = 40000;
  int countA = 0;
  for (int i = 0; i < n; ++i) {
    const LightSampler::Choice c = sampler.choose(rng.nextDouble());
    ASSERT_NE(c.light, &dark);
    EXPECT_EQ(c.probability, sampler.probability(c.light));
    countA += c.light == &a;
  }
  const double z = (countA - 0.25 * n) / std::sqrt(n * 0.25 * 0.75);
  EXPECT_GT(twoSidedNormalPValue(z), 1e-4);
  // All dark: uniform.
  const PointEmitter alsoDark(Vec3::Zero(), Color::Zero());
  const LightSampler allDark({&dark, &alsoDark}, Bounds3{});
  EXPECT_NEAR(allDark.probability(&dark), 0.5, 1e-15);
  EXPECT_NEAR(allDark.probability(&alsoDark), 0.5, 1e-15);
}

}  // namespace
}  // namespace quadtri::testing
