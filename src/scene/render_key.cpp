#include "quadtri/scene/render_key.h"

#include <fstream>
#include <type_traits>
#include <vector>

#include "quadtri/math/error.h"

#ifndef QUADTRI_VERSION
#error "QUADTRI_VERSION is set by src/scene/CMakeLists.txt"
#endif

namespace quadtri {
namespace {

class Fnv1a {
 public:
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ULL;
  }
  template <typename T>
  void add(const T& value) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    bytes(&value, sizeof(value));
  }
  void add(const std::string& text) {
    add(uint64_t(text.size()));
    bytes(text.data(), text.size());
  }
  template <typename Derived>
  void addMatrix(const Eigen::DenseBase<Derived>& m) {
    for (Eigen::Index i = 0; i < m.size(); ++i) add(double(m.derived().data()[i]));
  }
  void file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("{}: cannot read it to identify the render", path.string());
    std::vector<char> block(size_t(1) << 16);
    uint64_t total = 0;
    while (in) {
      in.read(block.data(), std::streamsize(block.size()));
      bytes(block.data(), size_t(in.gcount()));
      total += uint64_t(in.gcount());
    }
    add(total);
  }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ULL;
};

}  // namespace

uint64_t renderKey(const SceneDescription& d, const RenderOptions& options,
                   const std::optional<std::string>& modelOverride) {
  Fnv1a h;
  h.add(std::string("quadtri " QUADTRI_VERSION " render state"));
  h.file(d.file);
  const SensorDesc& s = d.sensor;
  h.addMatrix(s.toWorld);
  h.add(s.fov);
  h.add(s.fovAxis);
  h.add(s.nearClip);
  h.add(s.farClip);
  h.add(s.film.width);
  h.add(s.film.height);
  h.add(s.film.filter.type);
  h.add(s.film.filter.stddev);
  h.add(s.film.filter.radius);
  h.add(s.film.cropX);
  h.add(s.film.cropY);
  h.add(s.film.cropWidth);
  h.add(s.film.cropHeight);
  h.addMatrix(s.principalPointOffset);
  h.add(s.sampler.sampleCount);
  h.add(s.sampler.seed);
  const IntegratorDesc& i = d.integrator;
  h.add(i.type);
  h.add(i.maxDepth);
  h.add(i.rrDepth);
  h.add(i.hideEmitters);
  h.add(i.emitterSamples);
  h.add(i.bsdfSamples);
  h.add(i.threshold);
  h.add(i.minSamples);
  h.add(i.maxSamples);
  h.add(uint64_t(d.bsdfs.size()));
  for (const BsdfDesc& b : d.bsdfs) {
    h.add(b.type);
    h.addMatrix(b.reflectance);
    for (const IorValue* ior : {&b.intIor, &b.extIor}) {
      h.add(uint64_t(ior->index()));
      if (const double* v = std::get_if<double>(ior))
        h.add(*v);
      else
        h.add(std::get<std::string>(*ior));
    }
    h.add(b.material);
    h.addMatrix(b.eta);
    h.addMatrix(b.k);
    h.add(b.alpha);
    h.add(b.nested ? int64_t(*b.nested) : int64_t(-1));
  }
  h.add(uint64_t(d.emitters.size()));
  for (const EmitterDesc& e : d.emitters) {
    h.add(e.type);
    h.addMatrix(e.intensity);
    h.addMatrix(e.position);
    h.addMatrix(e.radiance);
  }
  h.add(uint64_t(d.shapes.size()));
  for (const ShapeDesc& shape : d.shapes) {
    h.add(shape.type);
    if (shape.type == ShapeDesc::Type::Obj || shape.type == ShapeDesc::Type::Ply)
      h.file(shape.filename);
    h.add(shape.model);
    h.add(shape.tessellation);
    h.add(shape.normals.source);
    h.add(shape.normals.creaseAngleDeg);
    h.add(shape.faceNormals);
    h.add(shape.flipNormals);
    h.addMatrix(shape.toWorld);
    h.add(uint64_t(shape.bsdf));
    h.add(shape.areaRadiance.has_value());
    if (shape.areaRadiance) h.addMatrix(*shape.areaRadiance);
  }
  h.add(modelOverride.value_or(std::string()));
  h.add(options.samplesPerPixel);
  h.add(options.seed);
  h.add(options.filter.kind);
  h.add(options.filter.stddev);
  h.add(options.filter.tentRadius);
  return h.value();
}

void checkResumable(const RenderState& state, uint64_t key, int width, int height,
                    const std::string& path) {
  if (state.width != width || state.height != height)
    fail("{}: the render state is of a {}x{} image, this render's is {}x{}", path, state.width,
         state.height, width, height);
  if (state.key != key)
    fail(
        "{}: the render state was saved by another render (key {:016x}, this render's "
        "{:016x}): the scene, a mesh file, -D, --model, --spp, --seed or quadtri's version "
        "differ; expected the state of this render",
        path, state.key, key);
}

uint64_t filmRenderKey(SceneDescription description, const RenderOptions& options,
                       const std::optional<std::string>& modelOverride) {
  FilmDesc& film = description.sensor.film;
  film.cropX = film.cropY = 0;
  film.cropWidth = film.width;
  film.cropHeight = film.height;
  return renderKey(description, options, modelOverride);
}

}  // namespace quadtri
