// <bsdf type="blendbsdf">  <!-- Mitsuba 3's: (1 - weight) first + weight second -->
//   <float name="weight" value="0.3"/>
//   <bsdf type="diffuse"/> <ref id="gold"/>  <!-- two nested <bsdf> or <ref>, in order -->
// </bsdf>
#pragma once

#include <array>

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// A linear blend of two BSDFs (render/bsdf/blend.h).
struct BlendBsdfParams final : BsdfParams {
  double weight = 0.5;            ///< of the second BSDF, in [0, 1]
  std::array<size_t, 2> blended;  ///< the two BSDFs' indices in SceneDescription::bsdfs

  std::string toString() const override;
  std::shared_ptr<const Bsdf> build(
      const std::vector<std::shared_ptr<const Bsdf>>& earlier) const override;
};

std::shared_ptr<const BsdfParams> parseBlendBsdf(ObjectProperties& props, SceneParseState& state);

}  // namespace quadtri
