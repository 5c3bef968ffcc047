// Shared checks of the Bsdf contract, used by the per-material tests: sampling against pdf() by
// chi-square, the sample weight against eval/pdf, and the Monte Carlo albedo.
#pragma once

#include <gtest/gtest.h>

#include "quadtri/geometry/rng.h"
#include "quadtri/render/bsdf/bsdf.h"
#include "render/chi2.h"

namespace quadtri::testing {

/// Mean and standard error of the per-channel sample weights (lost samples count as zero).
struct Albedo {
  Color mean = Color::Zero();
  Color standardError = Color::Zero();
};

/// ∫ f(wi, wo)|cos θo| dωo estimated as the mean weight of `count` draws of bsdf.sample.
inline Albedo sampledAlbedo(const Bsdf& bsdf, const Vec3& wi, int count, uint64_t seed) {
  Pcg32 rng(seed);
  Color sum = Color::Zero(), sumSq = Color::Zero();
  for (int i = 0; i < count; ++i) {
    const auto s = bsdf.sample(wi, rng.next2D(), rng.nextDouble());
    if (!s) continue;
    sum += s->weight;
    sumSq += s->weight * s->weight;
  }
  Albedo a;
  a.mean = sum / count;
  const Color variance = (sumSq / count - a.mean * a.mean).max(0.0);
  a.standardError = (variance / count).sqrt();
  return a;
}

/// Chi-square test of bsdf.sample against bsdf.pdf for incident `wi`, and on every sample:
/// finite values, pdf equal to pdf(wi, wo), weight equal to eval/pdf (both to 1e-9 relative).
inline void expectSamplingMatchesPdf(const Bsdf& bsdf, const Vec3& wi, uint64_t seed, double level,
                                     int sampleCount = 200000) {
  Pcg32 rng(seed);
  int badPdf = 0, badWeight = 0, notFinite = 0;
  const auto sample = [&]() -> std::optional<Vec3> {
    const auto s = bsdf.sample(wi, rng.next2D(), rng.nextDouble());
    if (!s) return std::nullopt;
    if (!allFinite(s->wo) || !s->weight.isFinite().all() || !std::isfinite(s->pdf)) {
      ++notFinite;
      return std::nullopt;
    }
    const double pdf = bsdf.pdf(wi, s->wo);
    if (std::abs(pdf - s->pdf) > 1e-9 * pdf) ++badPdf;
    if (pdf > 0.0) {
      const Color expected = bsdf.eval(wi, s->wo) / pdf;
      if (((s->weight - expected).abs() > 1e-9 * (1.0 + expected.abs())).any()) ++badWeight;
    }
    return s->wo;
  };
  const auto r =
      sphericalChi2Test(sampleCount, sample, [&](const Vec3& wo) { return bsdf.pdf(wi, wo); });
  EXPECT_GT(r.pValue, level) << bsdf.toString() << " wi = " << wi.transpose() << ": " << r.report;
  EXPECT_EQ(notFinite, 0) << bsdf.toString();
  EXPECT_EQ(badPdf, 0) << bsdf.toString();
  EXPECT_EQ(badWeight, 0) << bsdf.toString();
}

/// The unit direction at polar angle θ (degrees) and azimuth φ (degrees) in the local frame.
inline Vec3 directionAt(double thetaDegrees, double phiDegrees) {
  const double t = thetaDegrees * kPi / 180.0, p = phiDegrees * kPi / 180.0;
  return Vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

}  // namespace quadtri::testing
