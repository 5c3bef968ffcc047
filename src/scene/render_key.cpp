#include "quadtri/scene/render_key.h"

#include <fstream>
#include <type_traits>
#include <vector>

#include "quadtri/math/error.h"
#include "quadtri/math/fnv1a.h"

#ifndef QUADTRI_VERSION
#error "QUADTRI_VERSION is set by src/scene/CMakeLists.txt"
#endif

namespace quadtri {
namespace {

/// The key of the render (its crop window) and of the whole film at once: the same bytes go
/// into both hashes but the crop window's, so the scene file and every mesh file are read
/// once for both.
class KeyPair final : public KeyWriter {
 public:
  explicit KeyPair(const FileDigests* known) : known_(known) {}
  void bytes(const void* data, size_t n) override {
    render_.bytes(data, n);
    film_.bytes(data, n);
  }
  template <typename T>
  void add(const T& v) {
    value(v);
  }
  void add(const std::string& s) { text(s); }
  void text(std::string_view s) override {
    value(uint64_t(s.size()));
    bytes(s.data(), s.size());
  }
  template <typename Derived>
  void addMatrix(const Eigen::DenseBase<Derived>& m) {
    for (Eigen::Index i = 0; i < m.size(); ++i) add(double(m.derived().data()[i]));
  }
  /// The file's digest (FileDigest: the FNV-1a of its bytes and their count): the one its
  /// loader recorded while reading it, or read here.
  void file(const std::filesystem::path& path) override {
    FileDigest digest;
    if (const auto it = known_ ? known_->find(path) : FileDigests::const_iterator();
        known_ && it != known_->end()) {
      digest = it->second;
    } else {
      std::ifstream in(path, std::ios::binary);
      if (!in) fail("{}: cannot read it to identify the render", path.string());
      std::vector<char> block(size_t(1) << 16);
      Fnv1a h;
      while (in) {
        in.read(block.data(), std::streamsize(block.size()));
        h.bytes(block.data(), size_t(in.gcount()));
        digest.bytes += uint64_t(in.gcount());
      }
      digest.hash = h.hash;
    }
    add(digest.hash);
    add(digest.bytes);
  }
  /// A value that differs between the two: the render's crop field and the whole film's.
  void addEach(int renderValue, int filmValue) {
    render_.bytes(&renderValue, sizeof(renderValue));
    film_.bytes(&filmValue, sizeof(filmValue));
  }
  RenderKeys keys() const { return {render_.hash, film_.hash}; }

 private:
  const FileDigests* known_;
  Fnv1a render_, film_;
};

}  // namespace

RenderKeys renderKeys(const SceneDescription& d, const RenderOptions& options,
                      const std::optional<std::string>& modelOverride, const FileDigests* files) {
  KeyPair h(files);
  h.add(std::string("quadtri " QUADTRI_VERSION " render state"));
  h.add(kSamplingScheme);
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
  // filmRenderKey: the crop window reset to the whole film.
  h.addEach(s.film.cropX, 0);
  h.addEach(s.film.cropY, 0);
  h.addEach(s.film.cropWidth, s.film.width);
  h.addEach(s.film.cropHeight, s.film.height);
  h.addMatrix(s.principalPointOffset);
  h.add(s.sampler.sampleCount);
  h.add(s.sampler.seed);
  // Each plugin writes its own parameters (PluginParams::addToKey).
  auto params = [&](const std::string& type, const PluginParams* p) {
    if (p)
      p->addToKey(h, type);
    else
      h.text(type);
  };
  params(d.integrator.type, d.integrator.params.get());
  h.add(uint64_t(d.bsdfs.size()));
  for (const BsdfDesc& b : d.bsdfs) params(b.type, b.params.get());
  h.add(uint64_t(d.emitters.size()));
  for (const EmitterDesc& e : d.emitters) params(e.type, e.params.get());
  h.add(uint64_t(d.shapes.size()));
  for (const ShapeDesc& shape : d.shapes) {
    params(shape.type, shape.params.get());
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
  return h.keys();
}

uint64_t renderKey(const SceneDescription& description, const RenderOptions& options,
                   const std::optional<std::string>& modelOverride) {
  return renderKeys(description, options, modelOverride).render;
}

void checkResumable(const RenderState& state, uint64_t key, int width, int height,
                    const std::string& path) {
  if (state.width != width || state.height != height)
    fail("{}: the render state is of a {}x{} image, this render's is {}x{}", path, state.width,
         state.height, width, height);
  if (state.key != key)
    fail(
        "{}: the render state was saved by another render (key {:016x}, this render's "
        "{:016x}): the scene, a mesh file, -D, --model, --spp, --seed, the window (--tile, "
        "--crop) or quadtri's version differ; expected the state of this render",
        path, state.key, key);
}

uint64_t filmRenderKey(const SceneDescription& description, const RenderOptions& options,
                       const std::optional<std::string>& modelOverride) {
  return renderKeys(description, options, modelOverride).film;
}

}  // namespace quadtri
