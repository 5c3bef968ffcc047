// <bsdf type="dielectric">  <!-- float or named medium; Mitsuba's defaults bk7 / air -->
//   <string name="int_ior" value="bk7"/> <float name="ext_ior" value="1.0"/>
// </bsdf>
#pragma once

#include <variant>

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// An index of refraction: a number or a named medium ("bk7", "air", ...) to be looked up.
using IorValue = std::variant<double, std::string>;

/// A smooth dielectric interface (render/bsdf/dielectric.h).
struct DielectricBsdfParams final : BsdfParams {
  IorValue intIor = std::string("bk7");  ///< interior
  IorValue extIor = std::string("air");  ///< exterior

  std::string toString() const override;
  /// Named media are looked up here (lookupIor; an unknown name throws Error).
  std::shared_ptr<const Bsdf> build(
      const std::vector<std::shared_ptr<const Bsdf>>& earlier) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const BsdfParams> parseDielectricBsdf(ObjectProperties& props,
                                                      SceneParseState& state);

}  // namespace quadtri
