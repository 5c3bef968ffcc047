// <shape type="rectangle"> <emitter type="area"><rgb name="radiance" value="5"/></emitter>
// </shape>
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// Makes the shape it is nested in a light of uniform radiance
/// (render/emitter/mesh_area_emitter.h, sphere_area_emitter.h).
struct AreaEmitterParams final : EmitterParams {
  Color radiance = Color::Ones();

  std::string toString() const override;
  /// Throws Error: an area light is part of a shape.
  void addTo(RenderScene& scene) const override;
  std::optional<Color> shapeRadiance() const override { return radiance; }
};

std::shared_ptr<const EmitterParams> parseAreaEmitter(ObjectProperties& props);

}  // namespace quadtri
