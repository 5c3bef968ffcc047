#include "quadtri/scene/scene_description.h"

#include <fmt/format.h>

#include <algorithm>

#include "quadtri/math/error.h"

namespace quadtri {

namespace {

std::string colorText(const Color& c) {
  return fmt::format("{}, {}, {}", c[0], c[1], c[2]);
}

std::string iorText(const IorValue& ior) {
  if (const double* value = std::get_if<double>(&ior)) return fmt::format("{}", *value);
  return std::get<std::string>(ior);
}

std::string matrixText(const Mat4& m) {
  std::string out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out += fmt::format("{}{}", r + c ? " " : "", m(r, c));
  return out;
}

std::string idText(const std::string& id) {
  return id.empty() ? std::string() : fmt::format(" id=\"{}\"", id);
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

std::string_view integratorTypeName(IntegratorDesc::Type type) {
  switch (type) {
    case IntegratorDesc::Type::Path:
      return "path";
    case IntegratorDesc::Type::Direct:
      return "direct";
    case IntegratorDesc::Type::Normals:
      return "normals";
    case IntegratorDesc::Type::Adaptive:
      return "adaptive";
  }
  return "?";
}

std::string_view bsdfTypeName(BsdfDesc::Type type) {
  switch (type) {
    case BsdfDesc::Type::Diffuse:
      return "diffuse";
    case BsdfDesc::Type::Dielectric:
      return "dielectric";
    case BsdfDesc::Type::Conductor:
      return "conductor";
    case BsdfDesc::Type::RoughConductor:
      return "roughconductor";
    case BsdfDesc::Type::TwoSided:
      return "twosided";
  }
  return "?";
}

std::string_view emitterTypeName(EmitterDesc::Type type) {
  switch (type) {
    case EmitterDesc::Type::Point:
      return "point";
    case EmitterDesc::Type::Constant:
      return "constant";
  }
  return "?";
}

std::string_view shapeTypeName(ShapeDesc::Type type) {
  switch (type) {
    case ShapeDesc::Type::Obj:
      return "obj";
    case ShapeDesc::Type::Ply:
      return "ply";
    case ShapeDesc::Type::Rectangle:
      return "rectangle";
    case ShapeDesc::Type::Cube:
      return "cube";
    case ShapeDesc::Type::Sphere:
      return "sphere";
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
  std::string params;
  switch (i.type) {
    case IntegratorDesc::Type::Path:
      params = fmt::format(" max_depth={} rr_depth={} hide_emitters={}", i.maxDepth, i.rrDepth,
                           i.hideEmitters);
      break;
    case IntegratorDesc::Type::Direct:
      params = fmt::format(" emitter_samples={} bsdf_samples={} hide_emitters={}", i.emitterSamples,
                           i.bsdfSamples, i.hideEmitters);
      break;
    case IntegratorDesc::Type::Normals:
      break;
    case IntegratorDesc::Type::Adaptive:
      params = fmt::format(
          " threshold={} min_samples={} max_samples={} path(max_depth={} rr_depth={} "
          "hide_emitters={})",
          i.threshold, i.minSamples, i.maxSamples, i.maxDepth, i.rrDepth, i.hideEmitters);
      break;
  }
  return fmt::format("<integrator type=\"{}\"> ({}){}", integratorTypeName(i.type), i.location,
                     params);
}

std::string toString(const BsdfDesc& b) {
  std::string params;
  switch (b.type) {
    case BsdfDesc::Type::Diffuse:
      params = fmt::format(" reflectance=[{}]", colorText(b.reflectance));
      break;
    case BsdfDesc::Type::Dielectric:
      params = fmt::format(" int_ior={} ext_ior={}", iorText(b.intIor), iorText(b.extIor));
      break;
    case BsdfDesc::Type::Conductor:
    case BsdfDesc::Type::RoughConductor:
      params = b.material != "none"
                   ? fmt::format(" material={}", b.material)
                   : fmt::format(" eta=[{}] k=[{}]", colorText(b.eta), colorText(b.k));
      if (b.type == BsdfDesc::Type::RoughConductor)
        params += fmt::format(" distribution=ggx alpha={}", b.alpha);
      break;
    case BsdfDesc::Type::TwoSided:
      params = fmt::format(" nested=bsdfs[{}]", b.nested.value_or(0));
      break;
  }
  return fmt::format("<bsdf type=\"{}\"{}> ({}){}", bsdfTypeName(b.type), idText(b.id), b.location,
                     params);
}

std::string toString(const EmitterDesc& e) {
  const std::string params =
      e.type == EmitterDesc::Type::Point
          ? fmt::format(" intensity=[{}] position=[{}, {}, {}]", colorText(e.intensity),
                        e.position.x(), e.position.y(), e.position.z())
          : fmt::format(" radiance=[{}]", colorText(e.radiance));
  return fmt::format("<emitter type=\"{}\"> ({}){}", emitterTypeName(e.type), e.location, params);
}

std::string toString(const ShapeDesc& s) {
  std::string params;
  if (s.type == ShapeDesc::Type::Obj || s.type == ShapeDesc::Type::Ply)
    params =
        fmt::format(" filename={} model={} tessellation={} face_normals={}", s.filename.string(),
                    s.model, s.tessellation.empty() ? "default" : s.tessellation, s.faceNormals);
  params += fmt::format(" flip_normals={} to_world=[{}] bsdf=bsdfs[{}]", s.flipNormals,
                        matrixText(s.toWorld), s.bsdf);
  if (s.areaRadiance) params += fmt::format(" area_radiance=[{}]", colorText(*s.areaRadiance));
  return fmt::format("<shape type=\"{}\"{}> ({}){}", shapeTypeName(s.type), idText(s.id),
                     s.location, params);
}

void overrideSamplesPerPixel(SceneDescription& scene, int samplesPerPixel) {
  if (samplesPerPixel < 1) fail("--spp {}: expected a positive count", samplesPerPixel);
  scene.sensor.sampler.sampleCount = samplesPerPixel;
  IntegratorDesc& integrator = scene.integrator;
  if (integrator.type != IntegratorDesc::Type::Adaptive) return;
  if (samplesPerPixel < 2)
    fail("--spp {}: the adaptive integrator of {} needs at least 2 samples per pixel",
         samplesPerPixel, scene.file.string());
  integrator.maxSamples = samplesPerPixel;
  integrator.minSamples = std::min(integrator.minSamples, samplesPerPixel);
}

void overrideNormals(SceneDescription& scene, std::optional<NormalSource> source,
                     std::optional<double> creaseAngleDeg) {
  if (creaseAngleDeg) checkCreaseAngle(*creaseAngleDeg);
  for (ShapeDesc& shape : scene.shapes) {
    if (shape.type != ShapeDesc::Type::Obj && shape.type != ShapeDesc::Type::Ply) continue;
    if (source) shape.normals.source = *source;
    if (creaseAngleDeg) shape.normals.creaseAngleDeg = *creaseAngleDeg;
  }
}

}  // namespace quadtri
