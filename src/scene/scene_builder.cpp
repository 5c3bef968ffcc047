#include "quadtri/scene/scene_builder.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"
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

// An element as an error names it: its tag, type and id. Its parameters are at its line of the
// scene file; spelled out (matrices, resolved paths, defaults) they buried the message.
std::string tagOf(std::string_view element, const std::string& type, const std::string& id = {}) {
  return id.empty() ? fmt::format("<{} type=\"{}\">", element, type)
                    : fmt::format("<{} type=\"{}\" id=\"{}\">", element, type, id);
}

}  // namespace

BuiltScene buildScene(const SceneDescription& description,
                      const std::optional<std::string>& modelOverride, uint64_t maxMemoryBytes,
                      bool deferModelChecks) {
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
  at(sensor.location, "<sensor type=\"perspective\">", [&] {
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
  const IntegratorDesc& integrator = description.integrator;
  built.integrator = at(integrator.location, tagOf("integrator", integrator.type), [&] {
    if (!integrator.params) fail("no integrator parameters");
    return integrator.params->build(sensor.sampler.sampleCount);
  });

  std::vector<std::shared_ptr<const Bsdf>> bsdfs;
  for (const BsdfDesc& d : description.bsdfs)
    bsdfs.push_back(at(d.location, tagOf("bsdf", d.type, d.id), [&] {
      if (!d.params) fail("no BSDF parameters");
      return d.params->build(bsdfs);
    }));

  for (const EmitterDesc& e : description.emitters)
    at(e.location, tagOf("emitter", e.type), [&] {
      if (!e.params) fail("no emitter parameters");
      e.params->addTo(scene);
    });

  for (const ShapeDesc& s : description.shapes) {
    const std::string what = tagOf("shape", s.type, s.id);
    at(s.location, what, [&] {
      if (s.bsdf >= bsdfs.size()) fail("BSDF index {} out of range", s.bsdf);
      if (!s.params) fail("no shape parameters");
      ShapeBuildContext context{scene,
                                s,
                                bsdfs[s.bsdf],
                                s.location + " " + what,
                                modelOverride,
                                budget,
                                built.inputTriangles,
                                built.warnings,
                                built.fileDigests,
                                deferModelChecks ? &built.modelChecks : nullptr};
      s.params->build(context);
    });
  }
  scene.commit();
  return built;
}

}  // namespace quadtri
