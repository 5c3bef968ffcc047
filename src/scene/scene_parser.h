// Internal to src/scene: the state of one scene parse and the per-plugin parsers that fill it.
#pragma once

#include <fmt/ranges.h>

#include <map>
#include <string>
#include <vector>

#include "properties.h"
#include "quadtri/scene/scene_description.h"
#include "xml_file.h"

namespace quadtri {

/// What a parse has built so far, and the named objects a <ref> may point to.
struct SceneParseState {
  SceneDescription scene;
  /// id -> index into scene.bsdfs, for <ref id="..."/>.
  std::map<std::string, size_t, std::less<>> bsdfIds;
  /// id -> location of every named object, so that ids stay unique.
  std::map<std::string, std::string, std::less<>> idLocations;
  /// The shared "diffuse 0.5" given to shapes without a BSDF, created on first use.
  std::optional<size_t> defaultBsdf;

  /// Records `id` (if non-empty) as declared at `at`; throws when it is already taken.
  void declareId(const std::string& id, const XmlElement& at);
};

/// The plugin of `table` registered under the element's type; throws "FILE:LINE: unknown
/// <kind> type 'NAME'; expected one of <every registered name>" otherwise.
template <typename Plugin>
const Plugin& lookupPlugin(const std::vector<Plugin>& table, const ObjectProperties& props,
                           std::string_view kind) {
  std::vector<std::string_view> names;
  for (const Plugin& plugin : table) {
    if (plugin.name == props.type()) return plugin;
    names.push_back(plugin.name);
  }
  props.element().fail("unknown {} type '{}'; expected one of {}", kind, props.type(),
                       fmt::join(names, ", "));
}

/// <sensor type="perspective"> with its nested <film> (and <rfilter>) and <sampler>. Mitsuba
/// properties that do not change quadtri's image are accepted with a line in `notes`.
SensorDesc parseSensor(const XmlElement& element, std::vector<std::string>& notes);
/// <integrator>; adaptive's maxSamples is left 0 when not given (the caller fills it in).
IntegratorDesc parseIntegrator(const XmlElement& element, std::vector<std::string>& notes);
/// <bsdf>, appended to state.scene.bsdfs (a twosided's nested BSDF first); returns its index.
size_t parseBsdf(const XmlElement& element, SceneParseState& state);
/// <ref id="..."/> naming a BSDF declared earlier; returns its index.
size_t resolveBsdfRef(const XmlElement& ref, const SceneParseState& state);
/// A top-level <emitter> (a plugin placed at the scene's level).
EmitterDesc parseEmitter(const XmlElement& element, std::vector<std::string>& notes);
/// An <emitter> nested in a shape (a plugin placed on shapes: area); returns its radiance.
Color parseShapeEmitter(const XmlElement& element, std::vector<std::string>& notes);
/// <shape>, with its nested or referenced BSDF and optional area emitter.
ShapeDesc parseShape(const XmlElement& element, SceneParseState& state);
/// The placement every shape plugin reads (flip_normals, to_world) into `desc`; a shape
/// plugin's parser calls it where the properties should be listed in messages.
void parseShapePlacement(ObjectProperties& props, ShapeDesc& desc);
/// The default BSDF of shapes that name none: diffuse, reflectance 0.5.
BsdfDesc defaultBsdf();

}  // namespace quadtri
