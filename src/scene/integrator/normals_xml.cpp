#include "quadtri/scene/integrator/normals_xml.h"

#include "../legacy_key.h"
#include "quadtri/render/integrator/normals_integrator.h"

namespace quadtri {

std::shared_ptr<const Integrator> NormalsIntegratorParams::build(int /*samplesPerPixel*/) const {
  return std::make_shared<NormalsIntegrator>();
}

std::shared_ptr<const IntegratorParams> parseNormalsIntegrator(ObjectProperties& /*props*/) {
  return std::make_shared<NormalsIntegratorParams>();
}

void NormalsIntegratorParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::IntegratorFields fields;
  fields.type = legacy_key::Integrator::Normals;
  fields.write(key);
}

}  // namespace quadtri
