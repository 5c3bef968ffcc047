#include "quadtri/scene/emitter/constant_xml.h"

#include "../legacy_key.h"
#include "../param_text.h"
#include "../plugin_checks.h"
#include "quadtri/render/render_scene.h"

namespace quadtri {

std::string ConstantEmitterParams::toString() const {
  return fmt::format(" radiance=[{}]", colorText(radiance));
}

void ConstantEmitterParams::addTo(RenderScene& scene) const {
  scene.setEnvironment(radiance);
}

std::shared_ptr<const EmitterParams> parseConstantEmitter(ObjectProperties& props) {
  auto params = std::make_shared<ConstantEmitterParams>();
  params->radiance = nonNegativeColor(props, "radiance", Color(Color::Ones()));
  return params;
}

void ConstantEmitterParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::EmitterFields fields;
  fields.type = legacy_key::Emitter::Constant;
  fields.radiance = radiance;
  fields.write(key);
}

}  // namespace quadtri
