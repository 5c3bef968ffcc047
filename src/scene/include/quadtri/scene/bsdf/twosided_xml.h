// <bsdf type="twosided"><bsdf type="diffuse"/></bsdf>  <!-- or a <ref id="..."/> -->
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// The same one-sided BSDF on both sides of a surface (render/bsdf/twosided.h).
struct TwoSidedBsdfParams final : BsdfParams {
  /// The wrapped BSDF's index in SceneDescription::bsdfs (always lower than this BSDF's own).
  size_t wrapped = 0;

  std::string toString() const override;
  std::shared_ptr<const Bsdf> build(
      const std::vector<std::shared_ptr<const Bsdf>>& earlier) const override;
  std::optional<size_t> nested() const override { return wrapped; }
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const BsdfParams> parseTwoSidedBsdf(ObjectProperties& props,
                                                    SceneParseState& state);

}  // namespace quadtri
