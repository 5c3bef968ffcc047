#include "quadtri/scene/bsdf/conductor_xml.h"

#include "../legacy_key.h"
#include "../param_text.h"
#include "../plugin_checks.h"
#include "quadtri/render/bsdf/conductor.h"
#include "quadtri/render/bsdf/ior_tables.h"

namespace quadtri {

std::string ConductorSpec::toString() const {
  return material != "none" ? fmt::format(" material={}", material)
                            : fmt::format(" eta=[{}] k=[{}]", colorText(eta), colorText(k));
}

ConductorIor ConductorSpec::resolve() const {
  return material == "none" ? ConductorIor{eta, k} : lookupConductor(material);
}

ConductorSpec parseConductorSpec(ObjectProperties& props) {
  requireWhite(props, "specular_reflectance");
  ConductorSpec spec;
  spec.material = props.getString("material", "none");
  spec.eta = props.getColor("eta", Color(Color::Zero()));
  spec.k = props.getColor("k", Color(Color::Ones()));
  if (spec.material != "none" && (props.has("eta") || props.has("k")))
    props.fail("material", "'{}' and eta/k both given; use one of them", spec.material);
  checkNonNegative(props, "eta", spec.eta);
  checkNonNegative(props, "k", spec.k);
  return spec;
}

std::string ConductorBsdfParams::toString() const {
  return conductor.toString();
}

std::shared_ptr<const Bsdf> ConductorBsdfParams::build(
    const std::vector<std::shared_ptr<const Bsdf>>& /*earlier*/) const {
  return std::make_shared<Conductor>(conductor.resolve());
}

std::shared_ptr<const BsdfParams> parseConductorBsdf(ObjectProperties& props,
                                                     SceneParseState& /*state*/) {
  auto params = std::make_shared<ConductorBsdfParams>();
  params->conductor = parseConductorSpec(props);
  return params;
}

void ConductorBsdfParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::BsdfFields fields;
  fields.type = legacy_key::Bsdf::Conductor;
  fields.material = conductor.material;
  fields.eta = conductor.eta;
  fields.k = conductor.k;
  fields.write(key);
}

}  // namespace quadtri
