// Pixel reconstruction filters, applied by filter importance sampling: each sample's film
// position is drawn from the filter and weighted 1, so a pixel's value is the filter-weighted
// average of radiance with no splatting into neighbours. Pixels stay independent, which keeps
// the image identical for any thread count and lets adaptive sampling judge one pixel alone.
#pragma once

#include <cmath>
#include <string>

#include "quadtri/math/vec.h"

namespace quadtri {

/// Mitsuba 3's `box` (radius 0.5: uniform over the pixel), `tent` (per-axis triangle
/// 1 − |x|/r of radius r, default 1) or `gaussian` (per-axis normal of standard deviation
/// `stddev`, truncated at radius 4·stddev) reconstruction filter.
struct ReconstructionFilter {
  enum class Kind { Box, Gaussian, Tent } kind = Kind::Gaussian;
  double stddev = 0.5;      ///< gaussian only
  double tentRadius = 1.0;  ///< tent only

  /// The filter's support half-width in pixels.
  double radius() const {
    return kind == Kind::Box ? 0.5 : kind == Kind::Tent ? tentRadius : 4.0 * stddev;
  }
  /// Offset from the pixel centre distributed as the normalised filter, from two uniforms and
  /// (for the gaussian's rejection of the truncated tails) a generator of more.
  template <typename Rng>
  Vec2 sampleOffset(Rng& rng) const;
  std::string toString() const {
    if (kind == Kind::Box) return "box";
    if (kind == Kind::Tent) return "tent(radius=" + std::to_string(tentRadius) + ")";
    return "gaussian(stddev=" + std::to_string(stddev) + ")";
  }
};

template <typename Rng>
Vec2 ReconstructionFilter::sampleOffset(Rng& rng) const {
  if (kind == Kind::Box) return rng.next2D() - Vec2(0.5, 0.5);
  if (kind == Kind::Tent) {
    // Inverse CDF of the triangle density on [−r, r]: F⁻¹(u) = r(√(2u) − 1) below the
    // median, r(1 − √(2 − 2u)) above it.
    const Vec2 u = rng.next2D();
    const auto tent = [&](double v) {
      return tentRadius * (v < 0.5 ? std::sqrt(2.0 * v) - 1.0 : 1.0 - std::sqrt(2.0 - 2.0 * v));
    };
    return Vec2(tent(u.x()), tent(u.y()));
  }
  // Marsaglia's polar form of Box–Muller gives two independent normals from a uniform point
  // (a, b) of the unit disc (drawn by rejection from the square, accepted with probability
  // π/4) without a sine or cosine: (a, b) √(−2 ln s / s), s = a² + b². A component beyond the
  // radius is redrawn (probability 6e-5 at 4σ), which samples the truncated normal exactly.
  const double r = radius();
  Vec2 offset;
  for (int axis = 0; axis < 2;) {
    const Vec2 u = rng.next2D();
    const double a = 2.0 * u.x() - 1.0, b = 2.0 * u.y() - 1.0;
    const double s = a * a + b * b;
    if (!(s < 1.0 && s > 0.0)) continue;
    const double scale = stddev * std::sqrt(-2.0 * std::log(s) / s);
    if (std::abs(a * scale) <= r) offset[axis++] = a * scale;
    if (axis < 2 && std::abs(b * scale) <= r) offset[axis++] = b * scale;
  }
  return offset;
}

}  // namespace quadtri
