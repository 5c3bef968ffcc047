// Rendering a scene file as `quadtri render` does: the file's <default>s overridden by defines,
// the model, samples per pixel and seed overridden when given. Shared by the CLI and the Python
// module, so both render the same image from the same arguments.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "quadtri/render/renderer.h"
#include "quadtri/render/tiles.h"
#include "quadtri/scene/render_settings.h"
#include "quadtri/scene/scene_builder.h"
#include "quadtri/scene/scene_loader.h"

namespace quadtri {

/// What a render takes besides the scene file (`quadtri render`'s options).
struct SceneRenderRequest {
  /// -D, --model, --spp, --seed, --threads, --time, as every rendering command takes them.
  RenderSettings settings;
  /// --crop X,Y,W,H / --tile I/N (at most one): the window of the film rendered, replacing the
  /// scene's crop window; the pixels are those of the whole film's render inside it.
  std::optional<PixelWindow> crop;
  std::optional<TileIndex> tile;
  /// --normals / --crease-angle: replace every obj/ply shape's normal settings when given.
  std::optional<NormalSource> normals;
  std::optional<double> creaseAngleDegrees;
  /// --max-memory: the scene's image and meshes with their models must fit (0: no limit).
  uint64_t maxMemoryBytes = 0;
  /// Called with each warning (a define the file has no <default> for, a model that folds or
  /// falls back on a mesh) as it is found; the warnings are ignored when unset.
  std::function<void(const std::string&)> warn;
  /// Leave the model checks (the fold and fallback warnings) of the mesh shapes whose models
  /// have patches in PreparedRender::built.modelChecks for the caller to run, after the image,
  /// instead of running them before it: they are not needed for the first pixel.
  bool deferModelChecks = false;
  /// Called with each "FILE:LINE: note: ..." of a Mitsuba property accepted without effect.
  std::function<void(const std::string&)> note;
};

/// A scene built for rendering, with the request applied to its render options.
struct PreparedRender {
  SceneDescription description;  ///< as loaded, with the request's overrides applied
  BuiltScene built;
  RenderOptions options;  ///< cancel and progress are left for the caller to set
};

/// Loads `file` with the settings' defines, applies --spp to the description, builds the scene
/// with the model override and fills the render options (RenderSettings::applyTo). Throws
/// Error for a bad scene or a bad request (RenderSettings::validate, a crop window off the
/// film, both a crop and a tile), naming the file and line or the argument.
PreparedRender prepareSceneRender(const std::filesystem::path& file,
                                  const SceneRenderRequest& request);

}  // namespace quadtri
