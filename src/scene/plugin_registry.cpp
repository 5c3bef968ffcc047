// The registries: one table per concept, keyed by the XML `type` string. Adding a plugin is
// one line here (and its files in the CMake list); docs/DESIGN.md §5.1 walks through one.
#include <algorithm>

#include "quadtri/scene/bsdf/blend_xml.h"
#include "quadtri/scene/bsdf/conductor_xml.h"
#include "quadtri/scene/bsdf/dielectric_xml.h"
#include "quadtri/scene/bsdf/diffuse_xml.h"
#include "quadtri/scene/bsdf/rough_conductor_xml.h"
#include "quadtri/scene/bsdf/twosided_xml.h"
#include "quadtri/scene/emitter/area_xml.h"
#include "quadtri/scene/emitter/constant_xml.h"
#include "quadtri/scene/emitter/point_xml.h"
#include "quadtri/scene/integrator/adaptive_xml.h"
#include "quadtri/scene/integrator/direct_xml.h"
#include "quadtri/scene/integrator/normals_xml.h"
#include "quadtri/scene/integrator/path_xml.h"
#include "quadtri/scene/plugin.h"
#include "quadtri/scene/shape/builtin_shapes_xml.h"
#include "quadtri/scene/shape/mesh_file_xml.h"

namespace quadtri {

const std::vector<BsdfPlugin>& bsdfPlugins() {
  static const std::vector<BsdfPlugin> table = {
      {"diffuse", parseDiffuseBsdf},     {"dielectric", parseDielectricBsdf},
      {"conductor", parseConductorBsdf}, {"roughconductor", parseRoughConductorBsdf},
      {"twosided", parseTwoSidedBsdf},   {"blendbsdf", parseBlendBsdf},
  };
  return table;
}

const std::vector<EmitterPlugin>& emitterPlugins() {
  static const std::vector<EmitterPlugin> table = {
      {"point", EmitterPlace::Scene, parsePointEmitter},
      {"constant", EmitterPlace::Scene, parseConstantEmitter},
      {"area", EmitterPlace::Shape, parseAreaEmitter},
  };
  return table;
}

const std::vector<ShapePlugin>& shapePlugins() {
  static const std::vector<ShapePlugin> table = {
      {"obj", parseMeshFileShape}, {"ply", parseMeshFileShape},  {"rectangle", parseRectangleShape},
      {"cube", parseCubeShape},    {"sphere", parseSphereShape},
  };
  return table;
}

const std::vector<IntegratorPlugin>& integratorPlugins() {
  static const std::vector<IntegratorPlugin> table = {
      {"path", parsePathIntegrator},
      {"direct", parseDirectIntegrator},
      {"normals", parseNormalsIntegrator},
      {"adaptive", parseAdaptiveIntegrator},
  };
  return table;
}

namespace {

template <typename Plugin>
std::vector<std::string> namesOf(const std::vector<Plugin>& table) {
  std::vector<std::string> names;
  for (const Plugin& plugin : table) names.emplace_back(plugin.name);
  return names;
}

template <typename Plugin>
const Plugin* find(const std::vector<Plugin>& table, std::string_view name) {
  const auto it = std::find_if(table.begin(), table.end(),
                               [&](const Plugin& plugin) { return plugin.name == name; });
  return it == table.end() ? nullptr : &*it;
}

}  // namespace

std::vector<std::string> bsdfNames() {
  return namesOf(bsdfPlugins());
}
std::vector<std::string> emitterNames() {
  return namesOf(emitterPlugins());
}
std::vector<std::string> shapeNames() {
  return namesOf(shapePlugins());
}
std::vector<std::string> integratorNames() {
  return namesOf(integratorPlugins());
}

const BsdfPlugin* findBsdfPlugin(std::string_view name) {
  return find(bsdfPlugins(), name);
}
const EmitterPlugin* findEmitterPlugin(std::string_view name) {
  return find(emitterPlugins(), name);
}
const ShapePlugin* findShapePlugin(std::string_view name) {
  return find(shapePlugins(), name);
}
const IntegratorPlugin* findIntegratorPlugin(std::string_view name) {
  return find(integratorPlugins(), name);
}

}  // namespace quadtri
