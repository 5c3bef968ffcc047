#include "quadtri/scene/integrator/adaptive_xml.h"

#include <algorithm>

#include "../legacy_key.h"
#include "../properties.h"
#include "quadtri/render/integrator/adaptive_integrator.h"
#include "quadtri/render/integrator/path_integrator.h"

namespace quadtri {

std::string AdaptiveIntegratorParams::toString() const {
  return fmt::format(" threshold={} min_samples={} max_samples={} path({})", threshold, minSamples,
                     maxSamples, path.toString());
}

std::shared_ptr<const Integrator> AdaptiveIntegratorParams::build(int samplesPerPixel) const {
  AdaptiveSampling sampling;
  sampling.minSamples = minSamples;
  sampling.maxSamples = maxSamples > 0 ? maxSamples : samplesPerPixel;
  sampling.batch = minSamples;
  sampling.threshold = threshold;
  return std::make_shared<AdaptiveIntegrator>(
      std::make_shared<PathIntegrator>(
          PathIntegrator::Params{path.maxDepth, path.rrDepth, path.hideEmitters}),
      sampling);
}

std::shared_ptr<const IntegratorParams> AdaptiveIntegratorParams::withSamplerCount(
    int sampleCount, const std::string& location, const std::string& /*file*/) const {
  if (maxSamples != 0) return nullptr;
  auto params = std::make_shared<AdaptiveIntegratorParams>(*this);
  params->maxSamples = sampleCount;
  if (params->maxSamples < params->minSamples)
    fail(
        "{}: integrator 'adaptive': max_samples defaults to the sampler's sample_count "
        "({}), which is below min_samples ({})",
        location, params->maxSamples, params->minSamples);
  return params;
}

std::shared_ptr<const IntegratorParams> AdaptiveIntegratorParams::withSamplesPerPixel(
    int samplesPerPixel, const std::string& file) const {
  if (samplesPerPixel < 2)
    fail("--spp {}: the adaptive integrator of {} needs at least 2 samples per pixel",
         samplesPerPixel, file);
  auto params = std::make_shared<AdaptiveIntegratorParams>(*this);
  params->maxSamples = samplesPerPixel;
  params->minSamples = std::min(params->minSamples, samplesPerPixel);
  return params;
}

std::shared_ptr<const IntegratorParams> parseAdaptiveIntegrator(ObjectProperties& props) {
  auto params = std::make_shared<AdaptiveIntegratorParams>();
  params->threshold = props.getFloat("threshold", 0.05);
  if (!(params->threshold > 0.0)) props.fail("threshold", "must be > 0, got {}", params->threshold);
  // Two samples at least: the stopping test needs a sample variance.
  params->minSamples = boundedInteger(props, "min_samples", 16, 2, kMaxSceneSamples);
  if (const std::optional<long long> maxSamples = props.getOptionalInteger("max_samples")) {
    if (*maxSamples < params->minSamples || *maxSamples > kMaxSceneSamples)
      props.fail("max_samples", "must be in [min_samples = {}, {}], got {}", params->minSamples,
                 kMaxSceneSamples, *maxSamples);
    params->maxSamples = int(*maxSamples);
  }
  if (const std::optional<XmlElement> inner = props.takeOptional("integrator")) {
    ObjectProperties innerProps(*inner, {});
    if (innerProps.type() != "path")
      inner->fail("integrator 'adaptive' wraps a 'path' integrator, got '{}'", innerProps.type());
    params->path = parsePathSettings(innerProps);
    innerProps.finish();
  }
  return params;
}

void AdaptiveIntegratorParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::IntegratorFields fields;
  fields.type = legacy_key::Integrator::Adaptive;
  fields.maxDepth = path.maxDepth;
  fields.rrDepth = path.rrDepth;
  fields.hideEmitters = path.hideEmitters;
  fields.threshold = threshold;
  fields.minSamples = minSamples;
  fields.maxSamples = maxSamples;
  fields.write(key);
}

}  // namespace quadtri
