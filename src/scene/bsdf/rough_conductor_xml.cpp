#include "quadtri/scene/bsdf/rough_conductor_xml.h"

#include "../legacy_key.h"
#include "../properties.h"
#include "../scene_parser.h"
#include "quadtri/render/bsdf/conductor.h"
#include "quadtri/render/bsdf/rough_conductor.h"

namespace quadtri {

std::string RoughConductorBsdfParams::toString() const {
  return conductor.toString() + fmt::format(" distribution=ggx alpha={}", alpha);
}

std::shared_ptr<const Bsdf> RoughConductorBsdfParams::build(
    const std::vector<std::shared_ptr<const Bsdf>>& /*earlier*/) const {
  return std::make_shared<RoughConductor>(alpha, conductor.resolve());
}

std::shared_ptr<const BsdfParams> parseRoughConductorBsdf(ObjectProperties& props,
                                                          SceneParseState& state) {
  auto params = std::make_shared<RoughConductorBsdfParams>();
  params->conductor = parseConductorSpec(props);
  // Mitsuba's default distribution is Beckmann, which quadtri does not implement: asking
  // for GGX explicitly keeps a Mitsuba scene from silently rendering differently.
  const std::string distribution = props.getString("distribution", "beckmann");
  if (distribution != "ggx")
    props.fail("distribution",
               "'{}' is not supported; quadtri implements only <string name=\"distribution\" "
               "value=\"ggx\"/>",
               distribution);
  // alpha, or alpha_u = alpha_v (quadtri's GGX is isotropic).
  if (props.has("alpha_u") || props.has("alpha_v")) {
    if (props.has("alpha")) props.fail("alpha_u", "and alpha both given; use one of them");
    const double u = props.getFloat("alpha_u", 0.1), v = props.getFloat("alpha_v", 0.1);
    if (u != v)
      props.fail("alpha_u", "{} differs from alpha_v {}; quadtri's GGX is isotropic", u, v);
    params->alpha = u;
  } else {
    params->alpha = props.getFloat("alpha", 0.1);
  }
  // Visible-normal sampling changes how directions are drawn, not the BSDF: quadtri samples
  // the distribution of normals, which has the same expected image.
  props.ignore("sample_visible", "quadtri samples the GGX normals, same expected image",
               state.scene.notes);
  if (!(params->alpha > 0.0 && params->alpha <= 1.0))
    props.fail("alpha", "must be in (0, 1], got {}", params->alpha);
  return params;
}

void RoughConductorBsdfParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::BsdfFields fields;
  fields.type = legacy_key::Bsdf::RoughConductor;
  fields.material = conductor.material;
  fields.eta = conductor.eta;
  fields.k = conductor.k;
  fields.alpha = alpha;
  fields.write(key);
}

}  // namespace quadtri
