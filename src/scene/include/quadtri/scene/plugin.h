// The scene's plugins (docs/DESIGN.md §5.1): one registry per concept (BSDFs, emitters,
// shapes, integrators), each a table of {XML type name, property parser} in
// plugin_registry.cpp. A plugin's parser reads its own properties from the element and returns
// its parameters as a *Params object, which prints itself (for messages, logs and the render
// key) and builds the render object (the factory). Nothing outside the plugin's own files knows
// its fields.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "quadtri/math/color.h"
#include "quadtri/math/vec.h"
#include "quadtri/mesh/mesh_io_check.h"
#include "quadtri/mesh/normals.h"

namespace quadtri {

class Bsdf;
class Integrator;
class RenderScene;
class ObjectProperties;  // src/scene/properties.h: an element's typed properties
struct SceneParseState;  // src/scene/scene_parser.h: what a parse has built so far
struct ShapeDesc;

/// What a plugin writes into the render key (render_key.h): bytes of values, texts and files.
class KeyWriter {
 public:
  virtual ~KeyWriter() = default;
  virtual void bytes(const void* data, size_t n) = 0;
  /// The text's length, then its bytes.
  virtual void text(std::string_view text) = 0;
  /// The bytes of the file, then their count; throws Error naming a file it cannot read.
  virtual void file(const std::filesystem::path& path) = 0;

  template <typename T>
  void value(const T& v) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    bytes(&v, sizeof(v));
  }
  void color(const Color& c) {
    for (int i = 0; i < 3; ++i) value(double(c[i]));
  }
  void vector(const Vec3& v) {
    for (int i = 0; i < 3; ++i) value(double(v[i]));
  }
};

/// What every plugin's parameters can do besides building: print themselves and identify the
/// image they make.
class PluginParams {
 public:
  virtual ~PluginParams() = default;
  /// The parameters in Mitsuba-like syntax, " name=value name=value" (empty, or starting with
  /// a space), for messages and logs. Numbers print in full (round-trip) precision.
  virtual std::string toString() const = 0;
  /// Writes everything the image depends on into the render key. The default writes `type`
  /// (the registered name) and toString(), enough for a plugin whose every parameter prints;
  /// the plugins of quadtri 0.1.0 write the layout of its keys instead (legacy_key.h), so that
  /// render states and tiles saved before the registries still resume and merge.
  virtual void addToKey(KeyWriter& key, std::string_view type) const {
    key.text(type);
    key.text(toString());
  }
};

/// A BSDF's parameters. build() gets the BSDFs built before it (SceneDescription::bsdfs
/// order), so that a wrapper (twosided) can take the one it names by index.
class BsdfParams : public PluginParams {
 public:
  virtual std::shared_ptr<const Bsdf> build(
      const std::vector<std::shared_ptr<const Bsdf>>& earlier) const = 0;
  /// The index into SceneDescription::bsdfs of a BSDF this one wraps (twosided), if any.
  virtual std::optional<size_t> nested() const { return std::nullopt; }
};

/// An emitter's parameters: a light of its own (addTo) or the radiance of the shape it is
/// nested in (shapeRadiance, for area emitters).
class EmitterParams : public PluginParams {
 public:
  /// Adds the light to the scene (emitters outside shapes).
  virtual void addTo(RenderScene& scene) const = 0;
  /// The radiance it gives the shape it is nested in (area emitters); nullopt otherwise.
  virtual std::optional<Color> shapeRadiance() const { return std::nullopt; }
};

/// An integrator's parameters.
class IntegratorParams : public PluginParams {
 public:
  /// `samplesPerPixel` is the sampler's sample_count (after any --spp).
  virtual std::shared_ptr<const Integrator> build(int samplesPerPixel) const = 0;
  /// Called once the scene is parsed with the sampler's sample_count, for defaults taken from
  /// it; returns replacement parameters, or null to keep these. Throws Error.
  virtual std::shared_ptr<const IntegratorParams> withSamplerCount(int sampleCount,
                                                                   const std::string& location,
                                                                   const std::string& file) const {
    (void)sampleCount, (void)location, (void)file;
    return nullptr;
  }
  /// The parameters under `--spp N` (RenderSettings::samplesPerPixel), or null when --spp
  /// leaves them as they are. Throws Error for a count the integrator cannot take.
  virtual std::shared_ptr<const IntegratorParams> withSamplesPerPixel(
      int samplesPerPixel, const std::string& file) const {
    (void)samplesPerPixel, (void)file;
    return nullptr;
  }
};

/// The check of one mesh shape's model (conversionWarning, corner_stats.h): its warning, or
/// nullopt. It evaluates the model at every corner of the mesh (0.1 to 0.5 s on a million
/// triangles), which the image does not need, so a render may run it after the image.
using ModelCheck = std::function<std::optional<std::string>()>;

/// What a shape plugin's build() adds its geometry with.
struct ShapeBuildContext {
  RenderScene& scene;
  const ShapeDesc& desc;  ///< the shape's placement, flip, area radiance, location
  std::shared_ptr<const Bsdf> bsdf;
  std::string name;  ///< "FILE:LINE <shape ...>", the geometry's name in messages
  const std::optional<std::string>& modelOverride;  ///< --model
  MemoryBudget& budget;                             ///< --max-memory
  size_t& inputTriangles;              ///< BuiltScene::inputTriangles (mesh files add theirs)
  std::vector<std::string>& warnings;  ///< BuiltScene::warnings
  FileDigests& fileDigests;            ///< BuiltScene::fileDigests (mesh files add theirs)
  /// BuiltScene::modelChecks when the caller defers them (buildScene's deferModelChecks): a
  /// mesh shape whose model has patches (all but flat, shading and shading-offset) then adds
  /// the check of its model there instead of running it; null: run every check now.
  std::vector<ModelCheck>* modelChecks = nullptr;
};

/// A shape's parameters (besides the placement all shapes share, in ShapeDesc).
class SceneShapeParams : public PluginParams {
 public:
  virtual void build(ShapeBuildContext& context) const = 0;
  /// The files it reads (addToKey adds their bytes to the render key).
  virtual std::vector<std::filesystem::path> files() const { return {}; }
  /// PluginParams::addToKey's default, and the bytes of files().
  void addToKey(KeyWriter& key, std::string_view type) const override {
    PluginParams::addToKey(key, type);
    for (const std::filesystem::path& path : files()) key.file(path);
  }
  /// The parameters under --normals / --crease-angle, or null when they do not apply.
  virtual std::shared_ptr<const SceneShapeParams> withNormals(
      std::optional<NormalSource> source, std::optional<double> creaseDeg) const {
    (void)source, (void)creaseDeg;
    return nullptr;
  }
};

/// Where an emitter type may stand: at the scene's top level, or nested in a <shape>.
enum class EmitterPlace { Scene, Shape };

/// One line of a registry: the XML type name and the parser that reads the element's
/// properties (through ObjectProperties, which reports every unread or mistyped one with its
/// FILE:LINE) and returns the parameters. The parsers' extra arguments: the parse state (BSDFs
/// name other BSDFs, notes of ignored properties go to state.scene.notes) and, for shapes, the
/// ShapeDesc whose placement the parser fills by calling parseShapePlacement (scene_parser.h).
struct BsdfPlugin {
  std::string_view name;
  std::shared_ptr<const BsdfParams> (*parse)(ObjectProperties& props, SceneParseState& state);
};
struct EmitterPlugin {
  std::string_view name;
  EmitterPlace place;
  std::shared_ptr<const EmitterParams> (*parse)(ObjectProperties& props);
};
struct ShapePlugin {
  std::string_view name;
  std::shared_ptr<const SceneShapeParams> (*parse)(ObjectProperties& props, ShapeDesc& desc,
                                                   SceneParseState& state);
};
struct IntegratorPlugin {
  std::string_view name;
  std::shared_ptr<const IntegratorParams> (*parse)(ObjectProperties& props);
};

/// The registries (plugin_registry.cpp), in the order their names are listed in messages.
const std::vector<BsdfPlugin>& bsdfPlugins();
const std::vector<EmitterPlugin>& emitterPlugins();
const std::vector<ShapePlugin>& shapePlugins();
const std::vector<IntegratorPlugin>& integratorPlugins();

/// The registered type names of each concept, in table order.
std::vector<std::string> bsdfNames();
std::vector<std::string> emitterNames();
std::vector<std::string> shapeNames();
std::vector<std::string> integratorNames();

/// The plugin registered under `name`, or null.
const BsdfPlugin* findBsdfPlugin(std::string_view name);
const EmitterPlugin* findEmitterPlugin(std::string_view name);
const ShapePlugin* findShapePlugin(std::string_view name);
const IntegratorPlugin* findIntegratorPlugin(std::string_view name);

}  // namespace quadtri
