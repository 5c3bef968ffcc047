// Named media and metals, so scenes can say int_ior="bk7" or material="Au" as in Mitsuba 3.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "quadtri/math/color.h"

namespace quadtri {

/// Index of refraction of a named dielectric (Mitsuba 3's table, ~589 nm); the name is matched
/// case-insensitively. Unknown names throw Error listing the valid ones.
double lookupIor(std::string_view name);
/// The names lookupIor accepts, in table order.
std::vector<std::string> iorNames();

/// Complex index of refraction η + i·k of a metal relative to vacuum, per RGB channel.
struct ConductorIor {
  Color eta;
  Color k;
};

/// RGB η and k of a named metal ("Au", "Ag", ...; "none" is a perfect mirror, η = 0, k = 1).
/// Unknown names throw Error listing the valid ones.
ConductorIor lookupConductor(std::string_view name);
/// The names lookupConductor accepts, in table order.
std::vector<std::string> conductorNames();

}  // namespace quadtri
