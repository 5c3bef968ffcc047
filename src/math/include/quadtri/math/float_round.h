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

/// The nearest float not above x, without a branch on the rounding's side, which is a coin toss for
/// the rays Embree is handed (a mispredicted jump in every ray copy cost more than the copy): the
/// step is taken from f's bits as in floatBelow, a zero counted as −0, and chosen by a select.
inline float floatDown(double x) {
  const float f = float(x);
  const uint32_t bits = std::bit_cast<uint32_t>(f);
  const uint32_t zero = uint32_t((bits & 0x7fffffffu) == 0);
  const uint32_t from = bits | (zero << 31);
  const uint32_t below = from + ((from >> 31) << 1) - 1u;  // +1 below zero, −1 above
  // Masks, not a ternary, which the compiler turns back into a jump.
  const uint32_t take = 0u - uint32_t(double(f) > x);
  return std::bit_cast<float>(bits ^ ((below ^ bits) & take));
}

/// The nearest float not below x, without a branch as floatDown (a zero counted as +0).
inline float floatUp(double x) {
  const float f = float(x);
  const uint32_t bits = std::bit_cast<uint32_t>(f);
  const uint32_t zero = uint32_t((bits & 0x7fffffffu) == 0);
  const uint32_t from = bits & ~(zero << 31);
  const uint32_t above = from + 1u - ((from >> 31) << 1);  // +1 above zero, −1 below
  const uint32_t take = 0u - uint32_t(double(f) < x);
  return std::bit_cast<float>(bits ^ ((above ^ bits) & take));
}

}  // namespace quadtri
