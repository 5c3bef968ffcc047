// Internal to src/scene: value checks several plugins share.
#pragma once

#include <string_view>

#include "properties.h"

namespace quadtri {

/// Throws at `name` unless every channel of `c` is >= 0.
inline void checkNonNegative(ObjectProperties& props, std::string_view name, const Color& c) {
  if (!(c >= 0.0).all()) props.fail(name, "must be >= 0, got {}, {}, {}", c[0], c[1], c[2]);
}

/// The colour `name` (fallback when absent), checked >= 0.
inline Color nonNegativeColor(ObjectProperties& props, std::string_view name,
                              std::optional<Color> fallback) {
  const Color c = props.getColor(name, fallback);
  checkNonNegative(props, name, c);
  return c;
}

/// Mitsuba's specular_reflectance / specular_transmittance tints: quadtri's BSDFs have none, so
/// only the default (white) is accepted, and anything else is an error rather than a silently
/// different image.
inline void requireWhite(ObjectProperties& props, std::string_view name) {
  const Color c = props.getColor(name, Color(Color::Ones()));
  if (!(c == Color::Ones()).all())
    props.fail(name, "{}, {}, {} is not supported; quadtri implements only the default 1", c[0],
               c[1], c[2]);
}

}  // namespace quadtri
