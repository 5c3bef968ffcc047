// <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// A constant environment: the same radiance from every direction
/// (render/emitter/constant_emitter.h).
struct ConstantEmitterParams final : EmitterParams {
  Color radiance = Color::Ones();

  std::string toString() const override;
  void addTo(RenderScene& scene) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const EmitterParams> parseConstantEmitter(ObjectProperties& props);

}  // namespace quadtri
