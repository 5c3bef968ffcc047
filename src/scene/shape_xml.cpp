// <shape type="...">: the type picks a plugin of shapePlugins() (plugin_registry.cpp), which
// reads its own properties (src/scene/shape/) and the placement every shape has
// (parseShapePlacement); the BSDF and an area emitter are read here for every shape.
//
//   <shape type="obj"> ... <ref id="glass"/> </shape>   <!-- or a nested <bsdf> -->
//   <shape type="sphere"> <emitter type="area"><rgb name="radiance" value="10"/></emitter>
//   </shape>
#include "properties.h"
#include "quadtri/scene/bsdf/diffuse_xml.h"
#include "scene_parser.h"

namespace quadtri {

namespace {

/// The BSDF a shape names by <ref> or nests, or the shared default diffuse 0.5.
size_t shapeBsdf(ObjectProperties& props, SceneParseState& state) {
  const std::optional<XmlElement> nested = props.takeOptional("bsdf");
  const std::optional<XmlElement> ref = props.takeOptional("ref");
  if (nested && ref) ref->fail("{} has both a nested <bsdf> and a <ref>", props.describe());
  if (nested) return parseBsdf(*nested, state);
  if (ref) return resolveBsdfRef(*ref, state);
  if (!state.defaultBsdf) {
    state.scene.bsdfs.push_back(defaultBsdf());
    state.defaultBsdf = state.scene.bsdfs.size() - 1;
  }
  return *state.defaultBsdf;
}

}  // namespace

BsdfDesc defaultBsdf() {
  BsdfDesc diffuse;
  diffuse.type = "diffuse";
  diffuse.params = std::make_shared<DiffuseBsdfParams>();
  diffuse.location = "(default bsdf)";
  return diffuse;
}

void parseShapePlacement(ObjectProperties& props, ShapeDesc& desc) {
  desc.flipNormals = props.getBoolean("flip_normals", false);
  desc.toWorld = props.getTransform("to_world").value_or(Mat4::Identity());
}

ShapeDesc parseShape(const XmlElement& element, SceneParseState& state) {
  ObjectProperties props(element, {"bsdf", "ref", "emitter"});
  const ShapePlugin& plugin = lookupPlugin(shapePlugins(), props, "shape");
  ShapeDesc desc;
  desc.type = std::string(plugin.name);
  desc.id = props.id();
  desc.location = props.location();
  desc.params = plugin.parse(props, desc, state);
  desc.bsdf = shapeBsdf(props, state);
  if (const std::optional<XmlElement> emitter = props.takeOptional("emitter"))
    desc.areaRadiance = parseShapeEmitter(*emitter, state.scene.notes);
  props.finish();
  state.declareId(desc.id, element);
  return desc;
}

}  // namespace quadtri
