#include "quadtri/render/bsdf/ior_tables.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cctype>

#include "quadtri/math/error.h"

namespace quadtri {
namespace {

struct NamedIor {
  std::string_view name;
  double ior;
};

// Mitsuba 3's dielectric table (its values are taken from Hecht, Optics, 4th ed., measured at
// 0–20 °C and ~589 nm), plus "glass" as a name for the everyday crown glass BK7.
constexpr NamedIor kIors[] = {
    {"vacuum", 1.0},
    {"helium", 1.000036},
    {"hydrogen", 1.000132},
    {"air", 1.000277},
    {"carbon dioxide", 1.00045},
    {"water", 1.3330},
    {"acetone", 1.36},
    {"ethanol", 1.361},
    {"carbon tetrachloride", 1.461},
    {"glycerol", 1.4729},
    {"benzene", 1.501},
    {"silicone oil", 1.52045},
    {"bromine", 1.661},
    {"water ice", 1.31},
    {"fused quartz", 1.458},
    {"pyrex", 1.470},
    {"acrylic glass", 1.49},
    {"polypropylene", 1.49},
    {"bk7", 1.5046},
    {"glass", 1.5046},
    {"sodium chloride", 1.544},
    {"amber", 1.55},
    {"pet", 1.5750},
    {"diamond", 2.419},
};

struct NamedConductor {
  std::string_view name;
  std::array<double, 3> eta, k;
};

// RGB η and k of metals at room temperature: the spectral data Mitsuba ships (Palik, Handbook of
// Optical Constants of Solids, 1985) reduced to linear sRGB channels, as tabulated in Tungsten's
// ComplexIorData.hpp (B. Bitterli). "none" is Mitsuba's perfect mirror (η = 0, k = 1: F = 1).
constexpr NamedConductor kConductors[] = {
    {"Ag", {0.1552646489, 0.1167232965, 0.1383806959}, {4.8283433224, 3.1222459278, 2.1469504455}},
    {"Al", {1.6574599595, 0.8803689579, 0.5212287346}, {9.2238691996, 6.2695232477, 4.8370012281}},
    {"Au", {0.1431189557, 0.3749570432, 1.4424785571}, {3.9831604247, 2.3857207478, 1.6032152899}},
    {"Cr", {4.3696828663, 2.9167024892, 1.6547005413}, {5.2064337956, 4.2313645277, 3.7549467933}},
    {"Cu", {0.2004376970, 0.9240334304, 1.1022119527}, {3.9129485033, 2.4528477015, 2.1421879552}},
    {"none", {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}},
};

std::string lowerCase(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return out;
}

}  // namespace

double lookupIor(std::string_view name) {
  const std::string key = lowerCase(name);
  for (const NamedIor& entry : kIors)
    if (entry.name == key) return entry.ior;
  fail("unknown index of refraction name \"{}\"; valid names: {}", name,
       fmt::join(iorNames(), ", "));
}

std::vector<std::string> iorNames() {
  std::vector<std::string> names;
  for (const NamedIor& entry : kIors) names.emplace_back(entry.name);
  return names;
}

ConductorIor lookupConductor(std::string_view name) {
  for (const NamedConductor& entry : kConductors)
    if (entry.name == name)
      return {Color(entry.eta[0], entry.eta[1], entry.eta[2]),
              Color(entry.k[0], entry.k[1], entry.k[2])};
  fail("unknown conductor material \"{}\"; valid names: {}", name,
       fmt::join(conductorNames(), ", "));
}

std::vector<std::string> conductorNames() {
  std::vector<std::string> names;
  for (const NamedConductor& entry : kConductors) names.emplace_back(entry.name);
  return names;
}

}  // namespace quadtri
