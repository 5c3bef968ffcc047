#include "quadtri/scene/bsdf/diffuse_xml.h"

#include "../legacy_key.h"
#include "../param_text.h"
#include "../properties.h"
#include "quadtri/render/bsdf/diffuse.h"

namespace quadtri {

std::string DiffuseBsdfParams::toString() const {
  return fmt::format(" reflectance=[{}]", colorText(reflectance));
}

std::shared_ptr<const Bsdf> DiffuseBsdfParams::build(
    const std::vector<std::shared_ptr<const Bsdf>>& /*earlier*/) const {
  return std::make_shared<Diffuse>(reflectance);
}

std::shared_ptr<const BsdfParams> parseDiffuseBsdf(ObjectProperties& props,
                                                   SceneParseState& /*state*/) {
  auto params = std::make_shared<DiffuseBsdfParams>();
  params->reflectance = props.getColor("reflectance", Color(Color::Constant(0.5)));
  if (!((params->reflectance >= 0.0).all() && (params->reflectance <= 1.0).all()))
    props.fail("reflectance", "must lie in [0, 1] (energy conservation)");
  return params;
}

void DiffuseBsdfParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::BsdfFields fields;
  fields.type = legacy_key::Bsdf::Diffuse;
  fields.reflectance = reflectance;
  fields.write(key);
}

}  // namespace quadtri
