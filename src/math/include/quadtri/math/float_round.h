// Doubles rounded to the float that lies on a chosen side: Embree traverses in float, and a
// float box or interval must hold the double one so that no hit is culled by rounding.
#pragma once

#include <cmath>
#include <limits>

namespace quadtri {

/// The nearest float not above x.
inline float floatDown(double x) {
  float f = float(x);
  if (double(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

/// The nearest float not below x.
inline float floatUp(double x) {
  float f = float(x);
  if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace quadtri
