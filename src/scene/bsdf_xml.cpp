// <bsdf type="..."> and <ref id="..."/>: the type picks a plugin of bsdfPlugins()
// (plugin_registry.cpp), which reads its own properties (src/scene/bsdf/).
#include "properties.h"
#include "scene_parser.h"

namespace quadtri {

size_t parseBsdf(const XmlElement& element, SceneParseState& state) {
  ObjectProperties props(element, {"bsdf", "ref"});
  const BsdfPlugin& plugin = lookupPlugin(bsdfPlugins(), props, "bsdf");
  BsdfDesc desc;
  desc.type = std::string(plugin.name);
  desc.id = props.id();
  desc.location = props.location();
  desc.params = plugin.parse(props, state);
  props.finish();
  state.declareId(desc.id, element);
  state.scene.bsdfs.push_back(std::move(desc));
  const size_t index = state.scene.bsdfs.size() - 1;
  if (!state.scene.bsdfs[index].id.empty()) state.bsdfIds[state.scene.bsdfs[index].id] = index;
  return index;
}

size_t resolveBsdfRef(const XmlElement& ref, const SceneParseState& state) {
  ref.checkAttributes({"id", "name"});
  const std::string_view id = ref.required("id");
  const auto it = state.bsdfIds.find(id);
  if (it != state.bsdfIds.end()) return it->second;
  const auto other = state.idLocations.find(id);
  if (other != state.idLocations.end())
    ref.fail("<ref id=\"{}\"> names the object at {}, which is not a bsdf", id, other->second);
  ref.fail("<ref id=\"{}\"> names no bsdf declared before it", id);
}

}  // namespace quadtri
