// <emitter type="...">: the type picks a plugin of emitterPlugins() (plugin_registry.cpp),
// which reads its own properties (src/scene/emitter/). Scene-level emitters are lights of their
// own; shape-level ones (area) make the shape they are nested in a light.
#include <fmt/ranges.h>

#include "properties.h"
#include "scene_parser.h"

namespace quadtri {

namespace {

std::vector<std::string_view> namesAt(EmitterPlace place) {
  std::vector<std::string_view> names;
  for (const EmitterPlugin& plugin : emitterPlugins())
    if (plugin.place == place) names.push_back(plugin.name);
  return names;
}

}  // namespace

EmitterDesc parseEmitter(const XmlElement& element, std::vector<std::string>& notes) {
  ObjectProperties props(element, {});
  // Mitsuba's relative chance of picking this light: it changes the noise, not the image.
  props.ignore("sampling_weight", "quadtri picks lights by their power", notes);
  const EmitterPlugin* found = findEmitterPlugin(props.type());
  if (!found) {
    std::vector<std::string> names;
    for (const EmitterPlugin& p : emitterPlugins())
      names.push_back(std::string(p.name) +
                      (p.place == EmitterPlace::Shape ? " (inside a <shape>)" : ""));
    element.fail("unknown emitter type '{}'; expected one of {}", props.type(),
                 fmt::join(names, ", "));
  }
  const EmitterPlugin& plugin = *found;
  if (plugin.place == EmitterPlace::Shape)
    element.fail("emitter '{}' must be nested inside a <shape>", plugin.name);
  EmitterDesc desc;
  desc.type = std::string(plugin.name);
  desc.location = props.location();
  desc.params = plugin.parse(props);
  props.finish();
  return desc;
}

Color parseShapeEmitter(const XmlElement& element, std::vector<std::string>& notes) {
  ObjectProperties props(element, {});
  props.ignore("sampling_weight", "quadtri picks lights by their power", notes);
  const EmitterPlugin* plugin = findEmitterPlugin(props.type());
  if (!plugin || plugin->place != EmitterPlace::Shape)
    element.fail("a <shape> may only contain an emitter of type '{}', got '{}'",
                 fmt::join(namesAt(EmitterPlace::Shape), "' or '"), props.type());
  const std::shared_ptr<const EmitterParams> params = plugin->parse(props);
  props.finish();
  const std::optional<Color> radiance = params->shapeRadiance();
  if (!radiance) element.fail("emitter '{}' gives a shape no radiance", plugin->name);
  return *radiance;
}

}  // namespace quadtri
