#include <gtest/gtest.h>

#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/dielectric.h"
#include "quadtri/render/bsdf/fresnel.h"
#include "quadtri/render/bsdf/ior_tables.h"
#include "quadtri/render/sampling/frame.h"
#include "quadtri/render/sampling/warp.h"
#include "render/bsdf_checks.h"

namespace quadtri {
namespace {

using namespace quadtri::testing;

TEST(Fresnel, DielectricAtNormalIncidence) {
  for (double eta : {1.5046, 1.333, 2.419, 1.0 / 1.5}) {
    const double expected = std::pow((1.0 - eta) / (1.0 + eta), 2.0);
    EXPECT_NEAR(fresnelDielectric(1.0, eta).reflectance, expected, 1e-15);
    EXPECT_NEAR(fresnelDielectric(-1.0, eta).reflectance, expected, 1e-15);  // from inside
    EXPECT_NEAR(fresnelDielectric(1.0, eta).cosThetaT, -1.0, 1e-15);
  }
  EXPECT_NEAR(fresnelDielectric(1e-9, 1.5).reflectance, 1.0, 1e-8);  // grazing: a mirror
  EXPECT_EQ(fresnelDielectric(0.5, 1.0).reflectance, 0.0);           // index-matched
}

TEST(Fresnel, DielectricIsSymmetricAcrossTheInterface) {
  // Light refracted from i to t sees the same F going back from t to i (Stokes relations).
  Pcg32 rng(21);
  for (int i = 0; i < 1000; ++i) {
    const double cosI = rng.nextDouble(), eta = 1.0 + 1.5 * rng.nextDouble();
    const DielectricFresnel in = fresnelDielectric(cosI, eta);
    ASSERT_LT(in.cosThetaT, 0.0);
    const DielectricFresnel out = fresnelDielectric(in.cosThetaT, eta);
    // Near the critical angle F is steep in cos θt, which amplifies rounding.
    EXPECT_NEAR(out.reflectance, in.reflectance, 1e-10);
    EXPECT_NEAR(out.cosThetaT, cosI, 1e-12);
    EXPECT_NEAR(out.etaTI * in.etaTI, 1.0, 1e-15);
  }
}

TEST(Fresnel, ConductorWithoutAbsorptionIsTheDielectricFormula) {
  // The complex formula with k = 0 must reproduce the real one, total internal reflection included.
  for (double eta : {1.5, 1.0 / 1.5}) {
    for (double cosI = 0.0; cosI <= 1.0; cosI += 1.0 / 64.0) {
      const double f = fresnelDielectric(cosI, eta).reflectance;
      const Color c = fresnelConductor(cosI, Color::Constant(eta), Color::Zero());
      EXPECT_NEAR(c[0], f, 1e-12) << "eta " << eta << " cos " << cosI;
    }
  }
}

TEST(Dielectric, SnellsLawAndTotalInternalReflection) {
  const double eta = lookupIor("bk7") / lookupIor("air");
  const Dielectric glass(lookupIor("bk7"), lookupIor("air"));
  const double criticalSin = 1.0 / eta;
  Pcg32 rng(22);
  int refracted = 0, internal = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 wi = squareToUniformSphere(rng.next2D());
    const auto s = glass.sample(wi, rng.next2D(), rng.nextDouble());
    ASSERT_TRUE(s);
    EXPECT_TRUE(s->delta);
    EXPECT_NEAR(s->wo.norm(), 1.0, 1e-12);
    const double sinI = std::hypot(wi.x(), wi.y()), sinO = std::hypot(s->wo.x(), s->wo.y());
    const bool inside = wi.z() < 0.0;
    if (inside && sinI > criticalSin) {
      ++internal;
      EXPECT_LT((s->wo - reflectLocal(wi)).norm(), 1e-15);
      EXPECT_EQ(s->pdf, 1.0);
      EXPECT_TRUE((s->weight == 1.0).all());
      continue;
    }
    if (s->wo.z() * wi.z() > 0.0) {
      EXPECT_LT((s->wo - reflectLocal(wi)).norm(), 1e-15);
      EXPECT_EQ(s->eta, 1.0);
      continue;
    }
    ++refracted;
    // η_i sin θi = η_t sin θt, in the plane of incidence on the far side of the normal.
    const double etaI = inside ? eta : 1.0, etaT = inside ? 1.0 : eta;
    EXPECT_NEAR(etaI * sinI, etaT * sinO, 1e-12);
    EXPECT_NEAR(wi.x() * s->wo.y() - wi.y() * s->wo.x(), 0.0, 1e-12);
    EXPECT_LE(wi.x() * s->wo.x() + wi.y() * s->wo.y(), 1e-15);
    EXPECT_NEAR(s->eta, etaT / etaI, 1e-15);
  }
  EXPECT_GT(refracted, 10000);
  EXPECT_GT(internal, 1000);
}

TEST(Dielectric, FresnelSplitConservesEnergy) {
  const double eta = 1.5046;
  const Dielectric glass(eta, 1.0);
  const int n = 100000;
  const int zTests = 6;
  for (double cosI : {0.95, 0.5, 0.1, -0.95, -0.8, -0.7}) {
    const Vec3 wi(std::sqrt(1.0 - cosI * cosI), 0.0, cosI);
    const double f = fresnelDielectric(cosI, eta).reflectance;
    Pcg32 rng(23);
    int reflected = 0;
    double energy = 0.0, radiance = 0.0, radianceSq = 0.0;
    for (int i = 0; i < n; ++i) {
      const auto s = glass.sample(wi, rng.next2D(), rng.nextDouble());
      ASSERT_TRUE(s);
      const bool reflection = s->wo.z() * wi.z() > 0.0;
      reflected += reflection;
      EXPECT_NEAR(s->pdf, reflection ? f : 1.0 - f, 1e-15);
      // Radiance weight times the solid-angle compression η_t²/η_i² is the energy throughput.
      energy += s->weight[0] * s->eta * s->eta;
      radiance += s->weight[0];
      radianceSq += s->weight[0] * s->weight[0];
    }
    // R + T = 1: every draw carries energy one, and reflection happens with probability F.
    EXPECT_NEAR(energy / n, 1.0, 1e-12);
    if (f < 1.0) {
      const double z = (reflected - n * f) / std::sqrt(n * f * (1.0 - f));
      EXPECT_GT(twoSidedNormalPValue(z), sidakLevel(0.01, zTests)) << "cos " << cosI;
    } else {
      EXPECT_EQ(reflected, n);
    }
    // Radiance entering the denser side is compressed by 1/η², so its albedo stays below one.
    if (cosI > 0.0) {
      const double mean = radiance / n;
      const double se = std::sqrt(std::max(0.0, radianceSq / n - mean * mean) / n);
      EXPECT_LE(mean, 1.0 + 3.0 * se);
      EXPECT_NEAR(mean, f + (1.0 - f) / (eta * eta), 4.0 * se + 1e-12);
    }
  }
}

TEST(Dielectric, HasNoNonDeltaLobes) {
  const Dielectric glass(1.5, 1.0);
  EXPECT_TRUE(glass.isDelta());
  EXPECT_TRUE(glass.transmits());
  EXPECT_TRUE(isBlack(glass.eval(Vec3(0, 0, 1), Vec3(0, 0, 1))));
  EXPECT_EQ(glass.pdf(Vec3(0, 0, 1), Vec3(0, 0, -1)), 0.0);
  EXPECT_THROW(Dielectric(-1.0, 1.0), Error);
  EXPECT_THROW(Dielectric(1.5, 0.0), Error);
}

}  // namespace
}  // namespace quadtri
