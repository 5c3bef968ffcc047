// Internal to src/scene: how descriptions and plugins print their values (toString, the render
// key): numbers in fmt's shortest round-trip form, so that equal text means equal values.
#pragma once

#include <fmt/format.h>

#include <string>

#include "quadtri/math/color.h"
#include "quadtri/math/vec.h"

namespace quadtri {

/// "r, g, b".
inline std::string colorText(const Color& c) {
  return fmt::format("{}, {}, {}", c[0], c[1], c[2]);
}

/// The 16 entries of a matrix, row by row, separated by spaces.
inline std::string matrixText(const Mat4& m) {
  std::string out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out += fmt::format("{}{}", r + c ? " " : "", m(r, c));
  return out;
}

}  // namespace quadtri
