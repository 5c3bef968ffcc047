#include "quadtri/scene/integrator/path_xml.h"

#include "../legacy_key.h"
#include "../properties.h"
#include "quadtri/render/integrator/path_integrator.h"

namespace quadtri {

int boundedInteger(ObjectProperties& props, std::string_view name, long long fallback, long long lo,
                   long long hi) {
  const long long v = props.getInteger(name, fallback);
  if (v < lo || v > hi) props.fail(name, "must be in [{}, {}], got {}", lo, hi, v);
  return int(v);
}

std::string PathSettings::toString() const {
  return fmt::format("max_depth={} rr_depth={} hide_emitters={}", maxDepth, rrDepth, hideEmitters);
}

PathSettings parsePathSettings(ObjectProperties& props) {
  PathSettings path;
  path.maxDepth = boundedInteger(props, "max_depth", -1, -1, 1 << 20);
  path.rrDepth = boundedInteger(props, "rr_depth", 5, 1, 1 << 20);
  path.hideEmitters = props.getBoolean("hide_emitters", false);
  return path;
}

std::string PathIntegratorParams::toString() const {
  return fmt::format(" {}", path.toString());
}

std::shared_ptr<const Integrator> PathIntegratorParams::build(int /*samplesPerPixel*/) const {
  return std::make_shared<PathIntegrator>(
      PathIntegrator::Params{path.maxDepth, path.rrDepth, path.hideEmitters});
}

std::shared_ptr<const IntegratorParams> parsePathIntegrator(ObjectProperties& props) {
  auto params = std::make_shared<PathIntegratorParams>();
  params->path = parsePathSettings(props);
  return params;
}

void PathIntegratorParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::IntegratorFields fields;
  fields.type = legacy_key::Integrator::Path;
  fields.maxDepth = path.maxDepth;
  fields.rrDepth = path.rrDepth;
  fields.hideEmitters = path.hideEmitters;
  fields.write(key);
}

}  // namespace quadtri
