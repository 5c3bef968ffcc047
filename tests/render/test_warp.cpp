#include <gtest/gtest.h>

#include <cmath>

#include "quadtri/geometry/rng.h"
#include "quadtri/render/sampling/frame.h"
#include "quadtri/render/sampling/warp.h"
#include "render/chi2.h"

namespace quadtri {
namespace {

using testing::chi2Test;
using testing::sidakLevel;
using testing::sphericalChi2Test;

// The chi-square tests below form one family at level 0.01 (Šidák-corrected per test).
constexpr int kChi2TestsInFile = 9;
const double kLevel = sidakLevel(0.01, kChi2TestsInFile);
constexpr int kSamples = 200000;

TEST(Warp, DiskConcentricMatchesPdf) {
  Pcg32 rng(1);
  // Polar parameters (r, φ/2π): the disk's rim is the parameter edge, dA = r dr dφ.
  const auto sample = [&]() -> std::optional<Vec2> {
    const Vec2 p = squareToUniformDiskConcentric(rng.next2D());
    double phi = std::atan2(p.y(), p.x());
    if (phi < 0.0) phi += 2.0 * kPi;
    return Vec2(p.norm(), phi / (2.0 * kPi));
  };
  const auto density = [](const Vec2& q) {
    const double phi = 2.0 * kPi * q.y();
    const Vec2 p(q.x() * std::cos(phi), q.x() * std::sin(phi));
    return squareToUniformDiskConcentricPdf(p) * q.x() * 2.0 * kPi;
  };
  const auto r = chi2Test(20, 40, kSamples, sample, density);
  EXPECT_GT(r.pValue, kLevel) << r.report;
  EXPECT_EQ(squareToUniformDiskConcentricPdf(Vec2(0.8, 0.7)), 0.0);
  EXPECT_EQ(squareToUniformDiskConcentric(Vec2(0.5, 0.5)), Vec2::Zero());
}

// sinCosQuarter against the library's sine and cosine over [−π/4, π/4], endpoints and signed
// zero included: within 2 ulps (each is within an ulp of the true value), and exact at 0.
TEST(Warp, SinCosQuarterIsWithinUlpsOfStd) {
  const auto ulps = [](double got, double want) {
    return std::abs(got - want) / (std::nextafter(std::abs(want), kInfinity) - std::abs(want));
  };
  Pcg32 rng(7);
  double worstSin = 0.0, worstCos = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double x = i == 0   ? kPi / 4.0
                     : i == 1 ? -kPi / 4.0
                     : i == 2 ? 1e-300
                              : (kPi / 4.0) * (2.0 * rng.nextDouble() - 1.0);
    double s, c;
    sinCosQuarter(x, s, c);
    worstSin = std::max(worstSin, ulps(s, std::sin(x)));
    worstCos = std::max(worstCos, ulps(c, std::cos(x)));
  }
  EXPECT_LE(worstSin, 2.0);
  EXPECT_LE(worstCos, 2.0);
  double s, c;
  sinCosQuarter(-0.0, s, c);
  EXPECT_TRUE(s == 0.0 && std::signbit(s));
  EXPECT_EQ(c, 1.0);
}

// The concentric map's points are the polar form r (cos φ, sin φ) of Shirley and Chiu's
// construction, wedge by wedge, to rounding.
TEST(Warp, DiskConcentricIsShirleyChiusMap) {
  Pcg32 rng(3);
  for (int i = 0; i < 10000; ++i) {
    const Vec2 u = rng.next2D();
    const double a = 2.0 * u.x() - 1.0, b = 2.0 * u.y() - 1.0;
    const bool xWedge = std::abs(a) > std::abs(b);
    const double r = xWedge ? a : b;
    const double phi = xWedge ? (kPi / 4.0) * (b / a) : kPi / 2.0 - (kPi / 4.0) * (a / b);
    const Vec2 p = squareToUniformDiskConcentric(u);
    EXPECT_NEAR(p.x(), r * std::cos(phi), 1e-15) << u.transpose();
    EXPECT_NEAR(p.y(), r * std::sin(phi), 1e-15) << u.transpose();
  }
}

TEST(Warp, TriangleMatchesPdf) {
  Pcg32 rng(2);
  // Parameters (b0, b1 / (1 − b0)) cover the triangle with its hypotenuse on the square's edge;
  // db1 = (1 − b0) dt.
  const auto sample = [&]() -> std::optional<Vec2> {
    const Vec2 b = squareToUniformTriangle(rng.next2D());
    EXPECT_GE(b.x(), 0.0);
    EXPECT_GE(b.y(), 0.0);
    EXPECT_LE(b.x() + b.y(), 1.0 + 1e-15);
    const double rest = 1.0 - b.x();
    return Vec2(b.x(), rest > 0.0 ? b.y() / rest : 0.0);
  };
  const auto density = [](const Vec2& q) {
    const double rest = 1.0 - q.x();
    return squareToUniformTrianglePdf(Vec2(q.x(), q.y() * rest)) * rest;
  };
  const auto r = chi2Test(20, 20, kSamples, sample, density);
  EXPECT_GT(r.pValue, kLevel) << r.report;
  EXPECT_EQ(squareToUniformTrianglePdf(Vec2(0.6, 0.6)), 0.0);
}

/// Chi-square test of a direction warp of the unit square against its pdf.
void expectWarpMatches(uint64_t seed, const std::function<Vec3(const Vec2&)>& warp,
                       const std::function<double(const Vec3&)>& pdf) {
  Pcg32 rng(seed);
  const auto sample = [&]() -> std::optional<Vec3> {
    const Vec3 w = warp(rng.next2D());
    EXPECT_NEAR(w.norm(), 1.0, 1e-12);
    return w;
  };
  const auto r = sphericalChi2Test(kSamples, sample, pdf);
  EXPECT_GT(r.pValue, kLevel) << r.report;
}

TEST(Warp, UniformSphereMatchesPdf) {
  expectWarpMatches(3, squareToUniformSphere, squareToUniformSpherePdf);
}

TEST(Warp, UniformHemisphereMatchesPdf) {
  expectWarpMatches(4, squareToUniformHemisphere, squareToUniformHemispherePdf);
}

TEST(Warp, CosineHemisphereMatchesPdf) {
  expectWarpMatches(5, squareToCosineHemisphere, squareToCosineHemispherePdf);
}

TEST(Warp, UniformConeMatchesPdf) {
  // Half-angles on the test's 10° cell edges, a narrow and a wide cone.
  for (double degrees : {40.0, 120.0}) {
    const double cosMax = std::cos(degrees * kPi / 180.0);
    expectWarpMatches(
        6, [&](const Vec2& u) { return squareToUniformCone(u, cosMax); },
        [&](const Vec3& w) { return squareToUniformConePdf(w, cosMax); });
  }
}

TEST(Warp, SphereCapMatchesPdf) {
  // Outside: sin θmax = r/d = 1/2, a 30° cone, tested in the frame around the sphere's axis.
  const Vec3 origin(0.3, -0.2, 0.5), center(1.3, 1.8, -1.5);
  const Vec3 axis = (center - origin).normalized();
  const double radius = 0.5 * (center - origin).norm();
  const Frame frame(axis);
  Pcg32 rng(7);
  const auto sampleLocal = [&]() -> std::optional<Vec3> {
    const SphereDirectionSample s = sampleSphereCap(origin, center, radius, rng.next2D());
    EXPECT_NEAR(s.pdf, sphereCapPdf(origin, center, radius, s.direction), 1e-9 * s.pdf);
    return frame.toLocal(s.direction);
  };
  const auto pdfLocal = [&](const Vec3& w) {
    return sphereCapPdf(origin, center, radius, frame.toWorld(w));
  };
  const auto outside = sphericalChi2Test(kSamples, sampleLocal, pdfLocal);
  EXPECT_GT(outside.pValue, kLevel) << outside.report;

  // Inside: all directions, uniformly.
  const Vec3 inner = center + Vec3(0.1, 0.2, -0.1);
  const auto sampleInside = [&]() -> std::optional<Vec3> {
    return sampleSphereCap(inner, center, radius, rng.next2D()).direction;
  };
  const auto pdfInside = [&](const Vec3& w) { return sphereCapPdf(inner, center, radius, w); };
  const auto inside = sphericalChi2Test(kSamples, sampleInside, pdfInside);
  EXPECT_GT(inside.pValue, kLevel) << inside.report;
}

TEST(Warp, SphereCapDistanceReachesTheSphere) {
  const Vec3 center(2.0, -1.0, 3.0);
  const double radius = 0.75;
  Pcg32 rng(8);
  for (const Vec3& origin : {Vec3(0, 0, 0), Vec3(2.2, -1.1, 3.3)}) {
    const bool inside = (origin - center).norm() < radius;
    for (int i = 0; i < 1000; ++i) {
      const SphereDirectionSample s = sampleSphereCap(origin, center, radius, rng.next2D());
      const Vec3 hit = origin + s.distance * s.direction;
      EXPECT_NEAR((hit - center).norm(), radius, 1e-9);
      EXPECT_GT(s.distance, 0.0);
      // From outside the near side is seen: the surface normal there faces the origin.
      if (!inside) {
        EXPECT_LE((hit - center).dot(s.direction), 1e-9);
      }
    }
  }
}

TEST(Warp, SphereCapPdfIsAccurateForDistantSpheres) {
  // sin θmax = 1e-6: 1 − cos θmax = sin²/(1 + cos) must not cancel to zero.
  const Vec3 origin(0, 0, 0), center(0, 0, 1e6);
  const double radius = 1.0;
  const SphereDirectionSample s = sampleSphereCap(origin, center, radius, Vec2(0.3, 0.6));
  const double sin2 = 1e-12;
  const double expected = 1.0 / (2.0 * kPi * (sin2 / (1.0 + std::sqrt(1.0 - sin2))));
  EXPECT_NEAR(s.pdf, expected, 1e-9 * expected);
  EXPECT_TRUE(std::isfinite(s.pdf));
  EXPECT_NEAR((origin + s.distance * s.direction - center).norm(), radius, 1e-6);
  EXPECT_GE(s.distance, 1e6 - radius);
  EXPECT_EQ(sphereCapPdf(origin, center, radius, Vec3(0, 1, 0)), 0.0);
}

TEST(Warp, PowerHeuristicWeightsSumToOne) {
  EXPECT_DOUBLE_EQ(powerHeuristic(1, 2.0, 1, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(powerHeuristic(1, 3.0, 1, 1.0), 0.9);
  EXPECT_DOUBLE_EQ(powerHeuristic(1, kInfinity, 1, 5.0), 1.0);
  EXPECT_DOUBLE_EQ(powerHeuristic(1, 5.0, 1, kInfinity), 0.0);
  EXPECT_DOUBLE_EQ(powerHeuristic(1, 0.0, 1, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(powerHeuristic(1, 1e300, 1, 1e300), 0.5);
  Pcg32 rng(9);
  for (int i = 0; i < 100; ++i) {
    const double f = rng.nextDouble() * 10.0, g = rng.nextDouble() * 10.0;
    EXPECT_NEAR(powerHeuristic(2, f, 3, g) + powerHeuristic(3, g, 2, f), 1.0, 1e-14);
  }
}

TEST(Frame, RoundTripsAndIsOrthonormal) {
  Pcg32 rng(10);
  std::vector<Vec3> normals = {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1e-12, 0, -1).normalized(),
                               Vec3(1, 0, 0)};
  for (int i = 0; i < 100; ++i) normals.push_back(squareToUniformSphere(rng.next2D()));
  for (const Vec3& n : normals) {
    const Frame f(n);
    EXPECT_NEAR(f.s.dot(f.t), 0.0, 1e-12);
    EXPECT_NEAR(f.s.dot(f.n), 0.0, 1e-12);
    EXPECT_NEAR(f.t.dot(f.n), 0.0, 1e-12);
    EXPECT_NEAR(f.s.cross(f.t).dot(f.n), 1.0, 1e-12);  // right-handed
    EXPECT_LT((f.toLocal(n) - Vec3(0, 0, 1)).norm(), 1e-12);
    const Vec3 v = squareToUniformSphere(rng.next2D());
    EXPECT_LT((f.toWorld(f.toLocal(v)) - v).norm(), 1e-12);
  }
  const Vec3 w(0.3, -0.4, 0.866);
  EXPECT_LT((reflect(w, Vec3(0, 0, 1)) - reflectLocal(w)).norm(), 1e-15);
}

}  // namespace
}  // namespace quadtri
