// Doubles rounded to the float that lies on a chosen side: Embree traverses in float, and a
// float box or interval must hold the double one so that no hit is culled by rounding.
#pragma once

#include <bit>
#include <cstdint>

namespace quadtri {

/// The float after f towards −∞ (std::nextafter(f, −∞)) for f not NaN, from its bits: floats of
/// one sign are ordered as their bit patterns, so a step is ±1 on those bits; both zeros step to
/// −denorm_min and −∞ stays. Inline bit arithmetic: every ray Embree traces rounds its interval
/// this way.
inline float floatBelow(float f) {
  const uint32_t bits = std::bit_cast<uint32_t>(f);
  if ((bits & 0x7fffffffu) == 0) return -std::bit_cast<float>(uint32_t(1));
  if (bits == 0xff800000u) return f;
  return std::bit_cast<float>(bits >> 31 ? bits + 1 : bits - 1);
}

/// The float after f towards +∞ (std::nextafter(f, +∞)) for f not NaN; both zeros step to
/// denorm_min and +∞ stays.
inline float floatAbove(float f) {
  const uint32_t bits = std::bit_cast<uint32_t>(f);
  if ((bits & 0x7fffffffu) == 0) return std::bit_cast<float>(uint32_t(1));
  if (bits == 0x7f800000u) return f;
  return std::bit_cast<float>(bits >> 31 ? bits - 1 : bits + 1);
}

/// The nearest float not above x.
inline float floatDown(double x) {
  const float f = float(x);
  return double(f) > x ? floatBelow(f) : f;
}

/// The nearest float not below x.
inline float floatUp(double x) {
  const float f = float(x);
  return double(f) < x ? floatAbove(f) : f;
}

}  // namespace quadtri
