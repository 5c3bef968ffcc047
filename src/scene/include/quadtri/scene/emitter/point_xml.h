// <emitter type="point">
//   <rgb name="intensity" value="10"/>  <!-- W/sr -->
//   <point name="position" x="0" y="1.9" z="0"/>  <!-- or a to_world transform -->
// </emitter>
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// An isotropic point light (render/emitter/point_emitter.h).
struct PointEmitterParams final : EmitterParams {
  Color intensity = Color::Ones();  ///< W/sr
  Vec3 position = Vec3::Zero();

  std::string toString() const override;
  void addTo(RenderScene& scene) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const EmitterParams> parsePointEmitter(ObjectProperties& props);

}  // namespace quadtri
