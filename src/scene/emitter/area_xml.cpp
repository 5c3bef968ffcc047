#include "quadtri/scene/emitter/area_xml.h"

#include "../param_text.h"
#include "../plugin_checks.h"

namespace quadtri {

std::string AreaEmitterParams::toString() const {
  return fmt::format(" radiance=[{}]", colorText(radiance));
}

void AreaEmitterParams::addTo(RenderScene& /*scene*/) const {
  fail("emitter 'area' must be nested inside a <shape>");
}

std::shared_ptr<const EmitterParams> parseAreaEmitter(ObjectProperties& props) {
  auto params = std::make_shared<AreaEmitterParams>();
  params->radiance = nonNegativeColor(props, "radiance", Color(Color::Ones()));
  return params;
}

}  // namespace quadtri
