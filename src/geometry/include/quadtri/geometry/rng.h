// PCG32 (O'Neill 2014): small state, good statistics, and independent streams, so every pixel
// gets its own deterministic sequence whatever thread renders it.
#pragma once

#include <cstdint>

#include "quadtri/math/vec.h"

namespace quadtri {

class Pcg32 {
 public:
  Pcg32(uint64_t seed = 0x853c49e6748fea9bULL, uint64_t stream = 0xda3e39cb94b95bdbULL) {
    seedWith(seed, stream);
  }

  void seedWith(uint64_t seed, uint64_t stream) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    nextUint();
    state_ += seed;
    nextUint();
  }
  uint32_t nextUint() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  /// Uniform in [0, 1) with 53 random bits.
  double nextDouble() {
    const uint64_t hi = nextUint(), lo = nextUint();
    return double(((hi << 32) | lo) >> 11) * 0x1.0p-53;
  }
  Vec2 next2D() { return Vec2(nextDouble(), nextDouble()); }

 private:
  uint64_t state_ = 0, inc_ = 0;
};

/// A direction uniform on the unit sphere from two of rng's doubles (z, then the azimuth): the
/// crack-rate lines' directions (analysis/crack_rate.cpp), so tools that redraw those lines
/// must use it.
inline Vec3 uniformDirection(Pcg32& rng) {
  const double z = 1.0 - 2.0 * rng.nextDouble(), phi = 2.0 * kPi * rng.nextDouble();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

}  // namespace quadtri
