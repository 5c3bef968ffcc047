#include "quadtri/scene/scene_builder.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/render/bsdf/conductor.h"
#include "quadtri/render/bsdf/dielectric.h"
#include "quadtri/render/bsdf/diffuse.h"
#include "quadtri/render/bsdf/ior_tables.h"
#include "quadtri/render/bsdf/rough_conductor.h"
#include "quadtri/render/bsdf/twosided.h"
#include "quadtri/render/integrator/adaptive_integrator.h"
#include "quadtri/render/integrator/direct_integrator.h"
#include "quadtri/render/integrator/normals_integrator.h"
#include "quadtri/render/integrator/path_integrator.h"
#include "quadtri/surface/corner_stats.h"
#include "quadtri/surface/model_memory.h"

namespace quadtri {
namespace {

// Runs `build`, prefixing any Error with the element's location and description.
template <typename F>
auto at(const std::string& location, const std::string& what, F&& build) {
  try {
    return build();
  } catch (const Error& e) {
    fail("{}: {}: {}", location, what, e.what());
  }
}

double resolveIor(const IorValue& value) {
  if (const double* v = std::get_if<double>(&value)) return *v;
  return lookupIor(std::get<std::string>(value));
}

std::shared_ptr<const Bsdf> makeBsdf(const BsdfDesc& d,
                                     const std::vector<std::shared_ptr<const Bsdf>>& built) {
  switch (d.type) {
    case BsdfDesc::Type::Diffuse:
      return std::make_shared<Diffuse>(d.reflectance);
    case BsdfDesc::Type::Dielectric:
      return std::make_shared<Dielectric>(resolveIor(d.intIor), resolveIor(d.extIor));
    case BsdfDesc::Type::Conductor:
      return std::make_shared<Conductor>(d.material == "none" ? ConductorIor{d.eta, d.k}
                                                              : lookupConductor(d.material));
    case BsdfDesc::Type::RoughConductor:
      return std::make_shared<RoughConductor>(
          d.alpha, d.material == "none" ? ConductorIor{d.eta, d.k} : lookupConductor(d.material));
    case BsdfDesc::Type::TwoSided:
      if (!d.nested || *d.nested >= built.size()) fail("twosided needs a nested BSDF");
      return std::make_shared<TwoSided>(built[*d.nested]);
  }
  fail("unknown BSDF type");
}

std::shared_ptr<const Integrator> makeIntegrator(const IntegratorDesc& d, int samplesPerPixel) {
  const PathIntegrator::Params path{d.maxDepth, d.rrDepth, d.hideEmitters};
  switch (d.type) {
    case IntegratorDesc::Type::Path:
      return std::make_shared<PathIntegrator>(path);
    case IntegratorDesc::Type::Direct:
      return std::make_shared<DirectIntegrator>(
          DirectIntegrator::Params{d.emitterSamples, d.bsdfSamples, d.hideEmitters});
    case IntegratorDesc::Type::Normals:
      return std::make_shared<NormalsIntegrator>();
    case IntegratorDesc::Type::Adaptive: {
      AdaptiveSampling sampling;
      sampling.minSamples = d.minSamples;
      sampling.maxSamples = d.maxSamples > 0 ? d.maxSamples : samplesPerPixel;
      sampling.batch = d.minSamples;
      sampling.threshold = d.threshold;
      return std::make_shared<AdaptiveIntegrator>(std::make_shared<PathIntegrator>(path), sampling);
    }
  }
  fail("unknown integrator type");
}

// Places a mesh in the world: positions by M, normals by M⁻ᵀ. A mirroring M (det < 0) or
// flip_normals reverses the winding, so face and shading normals keep pointing the same way.
void transformMesh(TriangleMesh& mesh, const Mat4& toWorld, bool flipNormals) {
  const Mat3 linear = toWorld.topLeftCorner<3, 3>();
  const Vec3 translation = toWorld.topRightCorner<3, 1>();
  const Mat3 normalMatrix = linear.inverse().transpose();
  for (Vec3& p : mesh.positions) p = linear * p + translation;
  for (Vec3& n : mesh.normals)
    n = safeNormalized((flipNormals ? -1.0 : 1.0) * (normalMatrix * n), n);
  if ((linear.determinant() < 0.0) != flipNormals) {
    for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
    for (Tri& t : mesh.normalIndices) std::swap(t[1], t[2]);
  }
}

// Mitsuba's rectangle [-1,1]² in z = 0 facing +z, and cube [-1,1]³ facing outwards.
TriangleMesh rectangleMesh() {
  TriangleMesh m;
  m.positions = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TriangleMesh cubeMesh() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  // Each face as a quad wound counter-clockwise seen from outside.
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

}  // namespace

BuiltScene buildScene(const SceneDescription& description,
                      const std::optional<std::string>& modelOverride, uint64_t maxMemoryBytes) {
  MemoryBudget budget;
  budget.maxBytes = maxMemoryBytes;
  BuiltScene built;
  built.scene = std::make_unique<RenderScene>();
  RenderScene& scene = *built.scene;

  const SensorDesc& sensor = description.sensor;
  PerspectiveCamera::Params camera;
  camera.cameraToWorld = sensor.toWorld;
  camera.fovDegrees = sensor.fov;
  camera.fovAxis = sensor.fovAxis;
  camera.nearClip = sensor.nearClip;
  camera.farClip = sensor.farClip;
  camera.width = sensor.film.width;
  camera.height = sensor.film.height;
  camera.cropX = sensor.film.cropX;
  camera.cropY = sensor.film.cropY;
  camera.cropWidth = sensor.film.cropWidth;
  camera.cropHeight = sensor.film.cropHeight;
  camera.principalPointOffset = sensor.principalPointOffset;
  at(sensor.location, toString(sensor), [&] {
    const PerspectiveCamera film(camera);  // its width and height are the crop window's
    chargeMemory(budget, renderImageBytes(film.width(), film.height()), "the film",
                 fmt::format("a {}x{} image", film.width(), film.height()));
    scene.setCamera(film);
  });
  built.options.samplesPerPixel = sensor.sampler.sampleCount;
  built.options.seed = uint64_t(uint32_t(sensor.sampler.seed));
  built.options.filter.kind =
      sensor.film.filter.type == FilterDesc::Type::Box    ? ReconstructionFilter::Kind::Box
      : sensor.film.filter.type == FilterDesc::Type::Tent ? ReconstructionFilter::Kind::Tent
                                                          : ReconstructionFilter::Kind::Gaussian;
  built.options.filter.tentRadius = sensor.film.filter.radius;
  built.options.filter.stddev = sensor.film.filter.stddev;
  built.integrator = at(description.integrator.location, toString(description.integrator), [&] {
    return makeIntegrator(description.integrator, sensor.sampler.sampleCount);
  });

  std::vector<std::shared_ptr<const Bsdf>> bsdfs;
  for (const BsdfDesc& d : description.bsdfs)
    bsdfs.push_back(at(d.location, toString(d), [&] { return makeBsdf(d, bsdfs); }));

  for (const EmitterDesc& e : description.emitters)
    at(e.location, toString(e), [&] {
      if (e.type == EmitterDesc::Type::Point)
        scene.addPointLight(e.position, e.intensity);
      else
        scene.setEnvironment(e.radiance);
    });

  for (const ShapeDesc& s : description.shapes) {
    const std::string what = toString(s);
    at(s.location, what, [&] {
      if (s.bsdf >= bsdfs.size()) fail("BSDF index {} out of range", s.bsdf);
      const std::shared_ptr<const Bsdf>& bsdf = bsdfs[s.bsdf];
      const std::string name = s.location + " " + what;
      if (s.type == ShapeDesc::Type::Sphere) {
        scene.addSphere(Vec3::Zero(), 1.0, s.toWorld, s.flipNormals, bsdf, s.areaRadiance, name);
        return;
      }
      const bool isFile = s.type == ShapeDesc::Type::Obj || s.type == ShapeDesc::Type::Ply;
      const std::string model = !isFile ? "flat" : modelOverride ? *modelOverride : s.model;
      const Tessellation tessellation =
          s.tessellation.empty() ? Tessellation{} : Tessellation::parse(s.tessellation);
      budget.bytesPerTriangle = modelBytesPerTriangle(model, tessellation, ModelUse::Render);
      TriangleMesh mesh =
          isFile ? loadMesh(s.filename, s.normals, &budget)
                 : (s.type == ShapeDesc::Type::Rectangle ? rectangleMesh() : cubeMesh());
      if (s.faceNormals) {
        mesh.normals.clear();
        mesh.normalIndices.clear();
      }
      if (isFile) {
        built.inputTriangles += mesh.triangleCount();
        if (std::optional<std::string> repaired =
                repairWarning(mesh, fmt::format("{} {}", s.location, s.filename.string())))
          built.warnings.push_back(std::move(*repaired));
      }
      transformMesh(mesh, s.toWorld, s.flipNormals);
      std::shared_ptr<const SurfaceModel> converted =
          makeModel(model, std::make_shared<TriangleMesh>(std::move(mesh)));
      if (isFile)
        if (std::optional<std::string> warning = conversionWarning(
                *converted, fmt::format("{} {}", s.location, s.filename.string())))
          built.warnings.push_back(std::move(*warning));
      scene.addModel(std::move(converted), tessellation, bsdf, s.areaRadiance, name);
    });
  }
  scene.commit();
  return built;
}

}  // namespace quadtri
