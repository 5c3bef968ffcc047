// <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.25, 0.7"/></bsdf>
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// Lambertian reflection (render/bsdf/diffuse.h).
struct DiffuseBsdfParams final : BsdfParams {
  Color reflectance = Color::Constant(0.5);  ///< albedo, each channel in [0, 1]

  std::string toString() const override;
  std::shared_ptr<const Bsdf> build(
      const std::vector<std::shared_ptr<const Bsdf>>& earlier) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const BsdfParams> parseDiffuseBsdf(ObjectProperties& props, SceneParseState& state);

}  // namespace quadtri
