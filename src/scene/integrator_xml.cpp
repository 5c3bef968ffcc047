// <integrator type="path|direct|normals|adaptive">.
//
//   <integrator type="path">
//     <integer name="max_depth" value="-1"/>  <!-- -1: unbounded -->
//     <integer name="rr_depth" value="5"/>  <boolean name="hide_emitters" value="false"/>
//   </integrator>
//   <integrator type="direct">  <!-- shading_samples sets both of the next two -->
//     <integer name="emitter_samples" value="1"/> <integer name="bsdf_samples" value="1"/>
//   </integrator>
//   <integrator type="normals"/>
//   <integrator type="adaptive">  <!-- quadtri's version of the thesis' adaptive integration -->
//     <float name="threshold" value="0.05"/>  <!-- relative standard error that stops a pixel -->
//     <integer name="min_samples" value="16"/> <integer name="max_samples" value="256"/>
//     <integrator type="path"> ... </integrator>
//   </integrator>
#include "properties.h"
#include "scene_parser.h"

namespace quadtri {

namespace {

constexpr int kMaxSamples = 1 << 24;

int boundedInteger(ObjectProperties& props, std::string_view name, long long fallback, long long lo,
                   long long hi) {
  const long long v = props.getInteger(name, fallback);
  if (v < lo || v > hi) props.fail(name, "must be in [{}, {}], got {}", lo, hi, v);
  return int(v);
}

void parsePathParameters(ObjectProperties& props, IntegratorDesc& desc) {
  desc.maxDepth = boundedInteger(props, "max_depth", -1, -1, 1 << 20);
  desc.rrDepth = boundedInteger(props, "rr_depth", 5, 1, 1 << 20);
  desc.hideEmitters = props.getBoolean("hide_emitters", false);
}

}  // namespace

IntegratorDesc parseIntegrator(const XmlElement& element, std::vector<std::string>& /*notes*/) {
  ObjectProperties props(element, {"integrator"});
  IntegratorDesc desc;
  desc.location = props.location();
  const std::string& type = props.type();
  if (type == "path") {
    desc.type = IntegratorDesc::Type::Path;
    parsePathParameters(props, desc);
  } else if (type == "direct") {
    desc.type = IntegratorDesc::Type::Direct;
    const int shading = boundedInteger(props, "shading_samples", 1, 1, kMaxSamples);
    desc.emitterSamples = boundedInteger(props, "emitter_samples", shading, 0, kMaxSamples);
    desc.bsdfSamples = boundedInteger(props, "bsdf_samples", shading, 0, kMaxSamples);
    if (desc.emitterSamples == 0 && desc.bsdfSamples == 0)
      element.fail("integrator 'direct' needs emitter_samples or bsdf_samples > 0");
    desc.hideEmitters = props.getBoolean("hide_emitters", false);
  } else if (type == "normals") {
    desc.type = IntegratorDesc::Type::Normals;
  } else if (type == "adaptive") {
    desc.type = IntegratorDesc::Type::Adaptive;
    desc.threshold = props.getFloat("threshold", 0.05);
    if (!(desc.threshold > 0.0)) props.fail("threshold", "must be > 0, got {}", desc.threshold);
    // Two samples at least: the stopping test needs a sample variance.
    desc.minSamples = boundedInteger(props, "min_samples", 16, 2, kMaxSamples);
    if (const std::optional<long long> maxSamples = props.getOptionalInteger("max_samples")) {
      if (*maxSamples < desc.minSamples || *maxSamples > kMaxSamples)
        props.fail("max_samples", "must be in [min_samples = {}, {}], got {}", desc.minSamples,
                   kMaxSamples, *maxSamples);
      desc.maxSamples = int(*maxSamples);
    }
    if (const std::optional<XmlElement> inner = props.takeOptional("integrator")) {
      ObjectProperties innerProps(*inner, {});
      if (innerProps.type() != "path")
        inner->fail("integrator 'adaptive' wraps a 'path' integrator, got '{}'", innerProps.type());
      parsePathParameters(innerProps, desc);
      innerProps.finish();
    }
  } else {
    element.fail("unknown integrator type '{}'; expected path, direct, normals or adaptive", type);
  }
  props.finish();
  return desc;
}

}  // namespace quadtri
