#include "quadtri/scene/integrator/direct_xml.h"

#include "../legacy_key.h"
#include "../properties.h"
#include "quadtri/render/integrator/direct_integrator.h"
#include "quadtri/scene/integrator/path_xml.h"

namespace quadtri {

std::string DirectIntegratorParams::toString() const {
  return fmt::format(" emitter_samples={} bsdf_samples={} hide_emitters={}", emitterSamples,
                     bsdfSamples, hideEmitters);
}

std::shared_ptr<const Integrator> DirectIntegratorParams::build(int /*samplesPerPixel*/) const {
  return std::make_shared<DirectIntegrator>(
      DirectIntegrator::Params{emitterSamples, bsdfSamples, hideEmitters});
}

std::shared_ptr<const IntegratorParams> parseDirectIntegrator(ObjectProperties& props) {
  auto params = std::make_shared<DirectIntegratorParams>();
  const int shading = boundedInteger(props, "shading_samples", 1, 1, kMaxSceneSamples);
  params->emitterSamples = boundedInteger(props, "emitter_samples", shading, 0, kMaxSceneSamples);
  params->bsdfSamples = boundedInteger(props, "bsdf_samples", shading, 0, kMaxSceneSamples);
  if (params->emitterSamples == 0 && params->bsdfSamples == 0)
    props.element().fail("integrator 'direct' needs emitter_samples or bsdf_samples > 0");
  params->hideEmitters = props.getBoolean("hide_emitters", false);
  return params;
}

void DirectIntegratorParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::IntegratorFields fields;
  fields.type = legacy_key::Integrator::Direct;
  fields.hideEmitters = hideEmitters;
  fields.emitterSamples = emitterSamples;
  fields.bsdfSamples = bsdfSamples;
  fields.write(key);
}

}  // namespace quadtri
