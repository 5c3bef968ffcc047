#include "quadtri/scene/bsdf/twosided_xml.h"

#include "../legacy_key.h"
#include "../properties.h"
#include "../scene_parser.h"
#include "quadtri/render/bsdf/twosided.h"

namespace quadtri {

std::string TwoSidedBsdfParams::toString() const {
  return fmt::format(" nested=bsdfs[{}]", wrapped);
}

std::shared_ptr<const Bsdf> TwoSidedBsdfParams::build(
    const std::vector<std::shared_ptr<const Bsdf>>& earlier) const {
  if (wrapped >= earlier.size()) fail("twosided needs a nested BSDF");
  return std::make_shared<TwoSided>(earlier[wrapped]);
}

std::shared_ptr<const BsdfParams> parseTwoSidedBsdf(ObjectProperties& props,
                                                    SceneParseState& state) {
  const std::vector<XmlElement> inner = props.takeNested("bsdf");
  const std::vector<XmlElement> refs = props.takeNested("ref");
  const XmlElement& element = props.element();
  if (inner.size() + refs.size() != 1)
    element.fail("bsdf 'twosided' needs exactly one nested <bsdf> or <ref>, got {}",
                 inner.size() + refs.size());
  auto params = std::make_shared<TwoSidedBsdfParams>();
  params->wrapped =
      inner.empty() ? resolveBsdfRef(refs.front(), state) : parseBsdf(inner.front(), state);
  if (state.scene.bsdfs[params->wrapped].type == "twosided")
    element.fail("bsdf 'twosided' cannot wrap another twosided BSDF");
  return params;
}

void TwoSidedBsdfParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::BsdfFields fields;
  fields.type = legacy_key::Bsdf::TwoSided;
  fields.nested = int64_t(wrapped);
  fields.write(key);
}

}  // namespace quadtri
