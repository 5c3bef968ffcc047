// <integrator type="...">: the type picks a plugin of integratorPlugins()
// (plugin_registry.cpp), which reads its own properties (src/scene/integrator/).
#include "properties.h"
#include "scene_parser.h"

namespace quadtri {

IntegratorDesc parseIntegrator(const XmlElement& element, std::vector<std::string>& /*notes*/) {
  ObjectProperties props(element, {"integrator"});
  const IntegratorPlugin& plugin = lookupPlugin(integratorPlugins(), props, "integrator");
  IntegratorDesc desc;
  desc.type = std::string(plugin.name);
  desc.location = props.location();
  desc.params = plugin.parse(props);
  props.finish();
  return desc;
}

}  // namespace quadtri
