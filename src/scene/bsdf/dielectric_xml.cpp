#include "quadtri/scene/bsdf/dielectric_xml.h"

#include <fmt/format.h>

#include "../legacy_key.h"
#include "../plugin_checks.h"
#include "quadtri/render/bsdf/dielectric.h"
#include "quadtri/render/bsdf/ior_tables.h"

namespace quadtri {

namespace {

std::string iorText(const IorValue& ior) {
  if (const double* value = std::get_if<double>(&ior)) return fmt::format("{}", *value);
  return std::get<std::string>(ior);
}

double resolveIor(const IorValue& value) {
  if (const double* v = std::get_if<double>(&value)) return *v;
  return lookupIor(std::get<std::string>(value));
}

IorValue parseIor(ObjectProperties& props, std::string_view name, const char* fallback) {
  IorValue ior = props.getFloatOrString(name, std::string(fallback));
  if (const double* value = std::get_if<double>(&ior); value && !(*value > 0.0))
    props.fail(name, "must be > 0, got {}", *value);
  if (const std::string* medium = std::get_if<std::string>(&ior); medium && medium->empty())
    props.fail(name, "needs a number or a medium name");
  return ior;
}

}  // namespace

std::string DielectricBsdfParams::toString() const {
  return fmt::format(" int_ior={} ext_ior={}", iorText(intIor), iorText(extIor));
}

std::shared_ptr<const Bsdf> DielectricBsdfParams::build(
    const std::vector<std::shared_ptr<const Bsdf>>& /*earlier*/) const {
  return std::make_shared<Dielectric>(resolveIor(intIor), resolveIor(extIor));
}

std::shared_ptr<const BsdfParams> parseDielectricBsdf(ObjectProperties& props,
                                                      SceneParseState& /*state*/) {
  auto params = std::make_shared<DielectricBsdfParams>();
  params->intIor = parseIor(props, "int_ior", "bk7");
  params->extIor = parseIor(props, "ext_ior", "air");
  requireWhite(props, "specular_reflectance");
  requireWhite(props, "specular_transmittance");
  return params;
}

void DielectricBsdfParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::BsdfFields fields;
  fields.type = legacy_key::Bsdf::Dielectric;
  fields.intIor = intIor;
  fields.extIor = extIor;
  fields.write(key);
}

}  // namespace quadtri
