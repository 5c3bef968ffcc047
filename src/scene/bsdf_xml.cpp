// <bsdf type="diffuse|dielectric|conductor|roughconductor|twosided"> and <ref id="..."/>.
//
//   <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.25, 0.7"/></bsdf>
//   <bsdf type="dielectric">  <!-- float or named medium; Mitsuba's defaults bk7 / air -->
//     <string name="int_ior" value="bk7"/> <float name="ext_ior" value="1.0"/>
//   </bsdf>
//   <bsdf type="conductor"><string name="material" value="Au"/></bsdf>  <!-- or rgb eta, k -->
//   <bsdf type="roughconductor">
//     <string name="distribution" value="ggx"/> <float name="alpha" value="0.1"/>
//     <string name="material" value="Cu"/>
//   </bsdf>
//   <bsdf type="twosided"><bsdf type="diffuse"/></bsdf>
#include "properties.h"
#include "scene_parser.h"

namespace quadtri {

namespace {

void checkNonNegative(ObjectProperties& props, std::string_view name, const Color& c) {
  if (!(c >= 0.0).all()) props.fail(name, "must be >= 0, got {}, {}, {}", c[0], c[1], c[2]);
}

IorValue parseIor(ObjectProperties& props, std::string_view name, const char* fallback) {
  IorValue ior = props.getFloatOrString(name, std::string(fallback));
  if (const double* value = std::get_if<double>(&ior); value && !(*value > 0.0))
    props.fail(name, "must be > 0, got {}", *value);
  if (const std::string* medium = std::get_if<std::string>(&ior); medium && medium->empty())
    props.fail(name, "needs a number or a medium name");
  return ior;
}

/// Mitsuba's specular_reflectance / specular_transmittance tints: quadtri's BSDFs have none, so
/// only the default (white) is accepted, and anything else is an error rather than a silently
/// different image.
void requireWhite(ObjectProperties& props, std::string_view name) {
  const Color c = props.getColor(name, Color(Color::Ones()));
  if (!(c == Color::Ones()).all())
    props.fail(name, "{}, {}, {} is not supported; quadtri implements only the default 1", c[0],
               c[1], c[2]);
}

/// conductor/roughconductor: a named material or explicit eta and k, as in Mitsuba.
void parseConductor(ObjectProperties& props, BsdfDesc& desc) {
  requireWhite(props, "specular_reflectance");
  desc.material = props.getString("material", "none");
  desc.eta = props.getColor("eta", Color(Color::Zero()));
  desc.k = props.getColor("k", Color(Color::Ones()));
  if (desc.material != "none" && (props.has("eta") || props.has("k")))
    props.fail("material", "'{}' and eta/k both given; use one of them", desc.material);
  checkNonNegative(props, "eta", desc.eta);
  checkNonNegative(props, "k", desc.k);
}

}  // namespace

size_t parseBsdf(const XmlElement& element, SceneParseState& state) {
  ObjectProperties props(element, {"bsdf", "ref"});
  BsdfDesc desc;
  desc.id = props.id();
  desc.location = props.location();
  const std::string& type = props.type();
  if (type == "diffuse") {
    desc.type = BsdfDesc::Type::Diffuse;
    desc.reflectance = props.getColor("reflectance", Color(Color::Constant(0.5)));
    if (!((desc.reflectance >= 0.0).all() && (desc.reflectance <= 1.0).all()))
      props.fail("reflectance", "must lie in [0, 1] (energy conservation)");
  } else if (type == "dielectric") {
    desc.type = BsdfDesc::Type::Dielectric;
    desc.intIor = parseIor(props, "int_ior", "bk7");
    desc.extIor = parseIor(props, "ext_ior", "air");
    requireWhite(props, "specular_reflectance");
    requireWhite(props, "specular_transmittance");
  } else if (type == "conductor") {
    desc.type = BsdfDesc::Type::Conductor;
    parseConductor(props, desc);
  } else if (type == "roughconductor") {
    desc.type = BsdfDesc::Type::RoughConductor;
    parseConductor(props, desc);
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
      desc.alpha = u;
    } else {
      desc.alpha = props.getFloat("alpha", 0.1);
    }
    // Visible-normal sampling changes how directions are drawn, not the BSDF: quadtri samples
    // the distribution of normals, which has the same expected image.
    props.ignore("sample_visible", "quadtri samples the GGX normals, same expected image",
                 state.scene.notes);
    if (!(desc.alpha > 0.0 && desc.alpha <= 1.0))
      props.fail("alpha", "must be in (0, 1], got {}", desc.alpha);
  } else if (type == "twosided") {
    desc.type = BsdfDesc::Type::TwoSided;
    const std::vector<XmlElement> inner = props.takeNested("bsdf");
    const std::vector<XmlElement> refs = props.takeNested("ref");
    if (inner.size() + refs.size() != 1)
      element.fail("bsdf 'twosided' needs exactly one nested <bsdf> or <ref>, got {}",
                   inner.size() + refs.size());
    desc.nested =
        inner.empty() ? resolveBsdfRef(refs.front(), state) : parseBsdf(inner.front(), state);
    if (state.scene.bsdfs[*desc.nested].type == BsdfDesc::Type::TwoSided)
      element.fail("bsdf 'twosided' cannot wrap another twosided BSDF");
  } else {
    element.fail(
        "unknown bsdf type '{}'; expected diffuse, dielectric, conductor, roughconductor or "
        "twosided",
        type);
  }
  props.finish();
  state.declareId(desc.id, element);
  state.scene.bsdfs.push_back(std::move(desc));
  const size_t index = state.scene.bsdfs.size() - 1;
  if (!state.scene.bsdfs[index].id.empty()) state.bsdfIds[state.scene.bsdfs[index].id] = index;
  return index;
}

size_t resolveBsdfRef(const XmlElement& ref, const SceneParseState& state) {
  ref.checkAttributes({"id", "name"});
  const std::string_view id = ref.required("id");
  const auto it = state.bsdfIds.find(id);
  if (it != state.bsdfIds.end()) return it->second;
  const auto other = state.idLocations.find(id);
  if (other != state.idLocations.end())
    ref.fail("<ref id=\"{}\"> names the object at {}, which is not a bsdf", id, other->second);
  ref.fail("<ref id=\"{}\"> names no bsdf declared before it", id);
}

}  // namespace quadtri
