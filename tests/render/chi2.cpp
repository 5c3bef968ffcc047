#include "render/chi2.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace quadtri::testing {
namespace {

/// Nodes and weights of n-point Gauss–Legendre quadrature on [0, 1], by Newton's method on the
/// Legendre polynomial P_n (recurrence (k+1)P_{k+1} = (2k+1)xP_k − kP_{k−1}).
struct GaussLegendre {
  static constexpr int kPoints = 8;
  std::array<double, kPoints> nodes{}, weights{};

  GaussLegendre() {
    const int n = kPoints;
    for (int i = 0; i < n; ++i) {
      double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
      double derivative = 0.0;
      for (int iter = 0; iter < 100; ++iter) {
        double p0 = 1.0, p1 = x;
        for (int k = 1; k < n; ++k) {
          const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
          p0 = p1;
          p1 = p2;
        }
        derivative = n * (x * p1 - p0) / (x * x - 1.0);
        const double step = p1 / derivative;
        x -= step;
        if (std::abs(step) < 1e-15) break;
      }
      // Map [−1, 1] to [0, 1]: the weights halve.
      nodes[i] = 0.5 * (x + 1.0);
      weights[i] = 1.0 / ((1.0 - x * x) * derivative * derivative);
    }
  }
};

}  // namespace

double regularizedGammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double logPrefactor = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    // Series P(a, x) = e^{−x} x^a / Γ(a) · Σ x^n / (a (a+1) ··· (a+n)).
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-16) break;
    }
    return 1.0 - sum * std::exp(logPrefactor);
  }
  // Continued fraction for Q(a, x) evaluated with the modified Lentz method.
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int n = 1; n < 10000; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(logPrefactor) * h;
}

double sidakLevel(double familyLevel, int testCount) {
  return 1.0 - std::pow(1.0 - familyLevel, 1.0 / testCount);
}

double twoSidedNormalPValue(double z) {
  return std::erfc(std::abs(z) / std::sqrt(2.0));
}

Chi2Result chi2Test(int resX, int resY, int sampleCount,
                    const std::function<std::optional<Vec2>()>& sample,
                    const std::function<double(const Vec2&)>& density) {
  static const GaussLegendre quad;
  constexpr int kSubcells = 4;
  const int cells = resX * resY;
  std::vector<double> observed(cells + 1, 0.0), expected(cells + 1, 0.0);
  for (int i = 0; i < sampleCount; ++i) {
    const std::optional<Vec2> p = sample();
    if (!p) {
      observed[cells] += 1.0;
      continue;
    }
    const int ix = std::clamp(int(p->x() * resX), 0, resX - 1);
    const int iy = std::clamp(int(p->y() * resY), 0, resY - 1);
    observed[iy * resX + ix] += 1.0;
  }
  const double cellArea = 1.0 / (double(resX) * resY);
  double total = 0.0;
  for (int iy = 0; iy < resY; ++iy)
    for (int ix = 0; ix < resX; ++ix) {
      // Composite rule: narrow lobes (GGX at α = 0.1) need sub-cells a few degrees wide.
      double integral = 0.0;
      for (int sx = 0; sx < kSubcells; ++sx)
        for (int sy = 0; sy < kSubcells; ++sy)
          for (int a = 0; a < GaussLegendre::kPoints; ++a)
            for (int b = 0; b < GaussLegendre::kPoints; ++b) {
              const double x = (sx + quad.nodes[a]) / kSubcells;
              const double y = (sy + quad.nodes[b]) / kSubcells;
              integral += quad.weights[a] * quad.weights[b] *
                          density(Vec2((ix + x) / resX, (iy + y) / resY));
            }
      integral /= kSubcells * kSubcells;
      expected[iy * resX + ix] = integral * cellArea * sampleCount;
      total += integral * cellArea;
    }
  // Quadrature error can push the rejected mass a hair below zero for lossless samplers.
  expected[cells] = std::max(0.0, 1.0 - total) * sampleCount;

  Chi2Result result;
  std::vector<int> order(cells + 1);
  for (int i = 0; i <= cells; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
  constexpr double kMinExpected = 5.0;
  double pooledObserved = 0.0, pooledExpected = 0.0;
  for (int i : order) {
    if (expected[i] == 0.0 && observed[i] > 0.0) {
      result.pValue = 0.0;
      result.report =
          fmt::format("{} samples in cell {} where the density integrates to zero", observed[i], i);
      return result;
    }
    if (expected[i] < kMinExpected || (pooledExpected > 0.0 && pooledExpected < kMinExpected)) {
      pooledObserved += observed[i];
      pooledExpected += expected[i];
      continue;
    }
    const double diff = observed[i] - expected[i];
    result.statistic += diff * diff / expected[i];
    ++result.dof;
  }
  if (pooledExpected > 0.0) {
    const double diff = pooledObserved - pooledExpected;
    result.statistic += diff * diff / pooledExpected;
    ++result.dof;
  }
  result.dof -= 1;
  result.pValue = result.dof > 0 ? chi2Survival(result.statistic, result.dof) : 1.0;
  result.report = fmt::format("chi2 = {:.2f}, dof = {}, p = {:.3g}, integral of density = {:.6f}",
                              result.statistic, result.dof, result.pValue, total);
  // The cells that contribute most, to tell a wrong lobe from a wrong normalization.
  std::vector<int> worst;
  for (int i = 0; i <= cells; ++i)
    if (expected[i] >= kMinExpected) worst.push_back(i);
  const auto contribution = [&](int i) {
    return (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
  };
  std::sort(worst.begin(), worst.end(),
            [&](int a, int b) { return contribution(a) > contribution(b); });
  for (size_t j = 0; j < std::min<size_t>(5, worst.size()); ++j) {
    const int i = worst[j];
    result.report += i == cells ? fmt::format("\n  rejected draws: observed {}, expected {:.1f}",
                                              observed[i], expected[i])
                                : fmt::format("\n  cell ({}, {}): observed {}, expected {:.1f}",
                                              i % resX, i / resX, observed[i], expected[i]);
  }
  return result;
}

Chi2Result sphericalChi2Test(int sampleCount, const std::function<std::optional<Vec3>()>& sample,
                             const std::function<double(const Vec3&)>& pdf) {
  // Parameters (θ/π, φ/2π); the density per unit parameter area is pdf · sin θ · 2π².
  const auto toParam = [&]() -> std::optional<Vec2> {
    const std::optional<Vec3> w = sample();
    if (!w) return std::nullopt;
    const double theta = std::acos(std::clamp(w->z(), -1.0, 1.0));
    double phi = std::atan2(w->y(), w->x());
    if (phi < 0.0) phi += 2.0 * kPi;
    return Vec2(theta / kPi, phi / (2.0 * kPi));
  };
  const auto paramDensity = [&](const Vec2& p) {
    const double theta = p.x() * kPi, phi = p.y() * 2.0 * kPi;
    const double sinTheta = std::sin(theta);
    const Vec3 w(sinTheta * std::cos(phi), sinTheta * std::sin(phi), std::cos(theta));
    return pdf(w) * sinTheta * 2.0 * kPi * kPi;
  };
  return chi2Test(18, 36, sampleCount, toParam, paramDensity);
}

}  // namespace quadtri::testing
