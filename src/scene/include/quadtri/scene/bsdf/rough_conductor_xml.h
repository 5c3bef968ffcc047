// <bsdf type="roughconductor">
//   <string name="distribution" value="ggx"/> <float name="alpha" value="0.1"/>
//   <string name="material" value="Cu"/>  <!-- or rgb eta, k, as for conductor -->
// </bsdf>
#pragma once

#include "quadtri/scene/bsdf/conductor_xml.h"

namespace quadtri {

/// A rough conductor with an isotropic GGX distribution (render/bsdf/rough_conductor.h).
struct RoughConductorBsdfParams final : BsdfParams {
  ConductorSpec conductor;
  double alpha = 0.1;  ///< GGX roughness, in (0, 1]

  std::string toString() const override;
  std::shared_ptr<const Bsdf> build(
      const std::vector<std::shared_ptr<const Bsdf>>& earlier) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const BsdfParams> parseRoughConductorBsdf(ObjectProperties& props,
                                                          SceneParseState& state);

}  // namespace quadtri
