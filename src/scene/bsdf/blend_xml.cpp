#include "quadtri/scene/bsdf/blend_xml.h"

#include "../properties.h"
#include "../scene_parser.h"
#include "quadtri/render/bsdf/blend.h"

namespace quadtri {

std::string BlendBsdfParams::toString() const {
  return fmt::format(" weight={} bsdfs=[{}, {}]", weight, blended[0], blended[1]);
}

std::shared_ptr<const Bsdf> BlendBsdfParams::build(
    const std::vector<std::shared_ptr<const Bsdf>>& earlier) const {
  if (blended[0] >= earlier.size() || blended[1] >= earlier.size())
    fail("blendbsdf needs two nested BSDFs");
  return std::make_shared<Blend>(earlier[blended[0]], earlier[blended[1]], weight);
}

std::shared_ptr<const BsdfParams> parseBlendBsdf(ObjectProperties& props, SceneParseState& state) {
  auto params = std::make_shared<BlendBsdfParams>();
  params->weight = props.getFloat("weight");
  if (!(params->weight >= 0.0 && params->weight <= 1.0))
    props.fail("weight", "must be in [0, 1], got {}", params->weight);
  const std::vector<XmlElement> nested = props.takeNested({"bsdf", "ref"});
  if (nested.size() != 2)
    props.element().fail("bsdf 'blendbsdf' needs exactly two nested <bsdf> or <ref>, got {}",
                         nested.size());
  for (size_t i = 0; i < 2; ++i)
    params->blended[i] =
        nested[i].tag() == "ref" ? resolveBsdfRef(nested[i], state) : parseBsdf(nested[i], state);
  return params;
}

}  // namespace quadtri
