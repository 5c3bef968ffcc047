#include "quadtri/scene/emitter/point_xml.h"

#include "../legacy_key.h"
#include "../param_text.h"
#include "../plugin_checks.h"
#include "quadtri/render/render_scene.h"

namespace quadtri {

std::string PointEmitterParams::toString() const {
  return fmt::format(" intensity=[{}] position=[{}, {}, {}]", colorText(intensity), position.x(),
                     position.y(), position.z());
}

void PointEmitterParams::addTo(RenderScene& scene) const {
  scene.addPointLight(position, intensity);
}

std::shared_ptr<const EmitterParams> parsePointEmitter(ObjectProperties& props) {
  auto params = std::make_shared<PointEmitterParams>();
  params->intensity = nonNegativeColor(props, "intensity", Color(Color::Ones()));
  const Vec3 position = props.getVector("position", Vec3(Vec3::Zero()));
  const std::optional<Mat4> toWorld = props.getTransform("to_world");
  if (toWorld && props.has("position"))
    props.fail("position", "and to_world both given; use one of them");
  params->position = toWorld ? Vec3(toWorld->block<3, 1>(0, 3)) : position;
  return params;
}

void PointEmitterParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::EmitterFields fields;
  fields.type = legacy_key::Emitter::Point;
  fields.intensity = intensity;
  fields.position = position;
  fields.write(key);
}

}  // namespace quadtri
