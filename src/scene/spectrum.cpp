#include "quadtri/scene/spectrum.h"

#include <cmath>

#include "quadtri/math/error.h"

namespace quadtri {
namespace {

// One lobe of the fit: a Gaussian with a different width on each side of its peak.
double lobe(double x, double mean, double sigmaBelow, double sigmaAbove) {
  const double t = (x - mean) / (x < mean ? sigmaBelow : sigmaAbove);
  return std::exp(-0.5 * t * t);
}

constexpr double kFirstNm = 360.0, kLastNm = 830.0, kStepNm = 1.0;

Color xyzToLinearSrgb(const Color& xyz) {
  return Color(3.2404542 * xyz[0] - 1.5371385 * xyz[1] - 0.4985314 * xyz[2],
               -0.9692660 * xyz[0] + 1.8760108 * xyz[1] + 0.0415560 * xyz[2],
               0.0556434 * xyz[0] - 0.2040259 * xyz[1] + 1.0572252 * xyz[2]);
}

// ∫ S·(x̄, ȳ, z̄) dλ / ∫ ȳ dλ by the midpoint rule on 1 nm steps.
template <typename F>
Color integrateXyz(F&& spectrum) {
  Color xyz = Color::Zero();
  double yNorm = 0.0;
  for (double nm = kFirstNm + 0.5 * kStepNm; nm < kLastNm; nm += kStepNm) {
    const Color cmf = cieXyzMatching(nm);
    xyz += spectrum(nm) * cmf;
    yNorm += cmf[1];
  }
  return xyz / yNorm;
}

}  // namespace

Color cieXyzMatching(double nm) {
  const double x = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
                   0.065 * lobe(nm, 501.1, 20.4, 26.2);
  const double y = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
  const double z = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
  return Color(x, y, z);
}

Color spectrumToRgb(const std::vector<double>& nm, const std::vector<double>& values) {
  if (nm.empty() || nm.size() != values.size())
    fail("a spectrum needs as many values as wavelengths, and at least one");
  for (size_t i = 1; i < nm.size(); ++i)
    if (!(nm[i] > nm[i - 1]))
      fail("spectrum wavelengths must increase: {} nm follows {} nm", nm[i], nm[i - 1]);
  const auto sample = [&](double at) {
    if (at <= nm.front()) return values.front();
    if (at >= nm.back()) return values.back();
    size_t i = 1;
    while (nm[i] < at) ++i;
    const double t = (at - nm[i - 1]) / (nm[i] - nm[i - 1]);
    return (1.0 - t) * values[i - 1] + t * values[i];
  };
  static const Color white = xyzToLinearSrgb(integrateXyz([](double) { return 1.0; }));
  return xyzToLinearSrgb(integrateXyz(sample)) / white;
}

}  // namespace quadtri
