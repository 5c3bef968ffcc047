#include "quadtri/scene/scene_description.h"

#include <fmt/format.h>

#include <algorithm>

#include "param_text.h"
#include "quadtri/math/error.h"

namespace quadtri {

namespace {

std::string idText(const std::string& id) {
  return id.empty() ? std::string() : fmt::format(" id=\"{}\"", id);
}

std::string paramsText(const PluginParams* params) {
  return params ? params->toString() : std::string();
}

}  // namespace

std::string_view fovAxisName(FovAxis axis) {
  switch (axis) {
    case FovAxis::X:
      return "x";
    case FovAxis::Y:
      return "y";
    case FovAxis::Diagonal:
      return "diagonal";
    case FovAxis::Smaller:
      return "smaller";
    case FovAxis::Larger:
      return "larger";
  }
  return "?";
}

std::string toString(const SensorDesc& s) {
  std::string extras;
  if (s.principalPointOffset != Vec2::Zero())
    extras += fmt::format(" principal_point_offset=({}, {})", s.principalPointOffset.x(),
                          s.principalPointOffset.y());
  if (s.film.cropX != 0 || s.film.cropY != 0 || s.film.cropWidth != 0 || s.film.cropHeight != 0)
    extras += fmt::format(" crop={}x{}+{}+{}", s.film.cropWidth, s.film.cropHeight, s.film.cropX,
                          s.film.cropY);
  return fmt::format(
      "<sensor type=\"perspective\"> ({}) fov={} fov_axis={} near_clip={} far_clip={} "
      "to_world=[{}] film={}x{} rfilter={}{} sample_count={} seed={}{}",
      s.location, s.fov, fovAxisName(s.fovAxis), s.nearClip, s.farClip, matrixText(s.toWorld),
      s.film.width, s.film.height,
      s.film.filter.type == FilterDesc::Type::Box    ? "box"
      : s.film.filter.type == FilterDesc::Type::Tent ? "tent"
                                                     : "gaussian",
      s.film.filter.type == FilterDesc::Type::Box ? std::string()
      : s.film.filter.type == FilterDesc::Type::Tent
          ? fmt::format("(radius={})", s.film.filter.radius)
          : fmt::format("(stddev={})", s.film.filter.stddev),
      s.sampler.sampleCount, s.sampler.seed, extras);
}

std::string toString(const IntegratorDesc& i) {
  return fmt::format("<integrator type=\"{}\"> ({}){}", i.type, i.location,
                     paramsText(i.params.get()));
}

std::string toString(const BsdfDesc& b) {
  return fmt::format("<bsdf type=\"{}\"{}> ({}){}", b.type, idText(b.id), b.location,
                     paramsText(b.params.get()));
}

std::string toString(const EmitterDesc& e) {
  return fmt::format("<emitter type=\"{}\"> ({}){}", e.type, e.location,
                     paramsText(e.params.get()));
}

std::string toString(const ShapeDesc& s) {
  std::string params = paramsText(s.params.get());
  params += fmt::format(" flip_normals={} to_world=[{}] bsdf=bsdfs[{}]", s.flipNormals,
                        matrixText(s.toWorld), s.bsdf);
  if (s.areaRadiance) params += fmt::format(" area_radiance=[{}]", colorText(*s.areaRadiance));
  return fmt::format("<shape type=\"{}\"{}> ({}){}", s.type, idText(s.id), s.location, params);
}

void overrideSamplesPerPixel(SceneDescription& scene, int samplesPerPixel) {
  if (samplesPerPixel < 1) fail("--spp {}: expected a positive count", samplesPerPixel);
  scene.sensor.sampler.sampleCount = samplesPerPixel;
  IntegratorDesc& integrator = scene.integrator;
  if (!integrator.params) return;
  if (std::shared_ptr<const IntegratorParams> changed =
          integrator.params->withSamplesPerPixel(samplesPerPixel, scene.file.string()))
    integrator.params = std::move(changed);
}

void overrideNormals(SceneDescription& scene, std::optional<NormalSource> source,
                     std::optional<double> creaseAngleDeg) {
  if (creaseAngleDeg) checkCreaseAngle(*creaseAngleDeg);
  for (ShapeDesc& shape : scene.shapes) {
    if (!shape.params) continue;
    if (std::shared_ptr<const SceneShapeParams> changed =
            shape.params->withNormals(source, creaseAngleDeg))
      shape.params = std::move(changed);
  }
}

}  // namespace quadtri
