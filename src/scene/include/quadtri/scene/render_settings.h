// The options every command that renders a scene file shares, parsed once and meaning the same
// everywhere: `quadtri render`, `quadtri figure` (and `reproduce`, which runs figures), and the
// Python module's render(). The CLI registers them on each command from one place
// (src/cli/render_flags.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadtri/render/renderer.h"
#include "quadtri/scene/scene_description.h"
#include "quadtri/scene/scene_loader.h"

namespace quadtri {

struct RenderSettings {
  /// -D name=value: the scene's $name, winning over the file's <default name="name">.
  SceneDefines defines;
  /// --model: the model of every obj/ply shape, replacing the scene's (figure: the column's).
  std::optional<std::string> model;
  /// --spp N: the sampler's sample_count, and for an adaptive integrator its cap per pixel
  /// (min_samples lowered to N where needed; overrideSamplesPerPixel). It does not set $spp:
  /// -D spp=N does.
  std::optional<int> samplesPerPixel;
  /// --seed: the sampler's seed.
  std::optional<uint64_t> seed;
  /// --threads: worker threads, 0 = all (the image does not depend on it).
  int threads = 0;
  /// --time: a budget in seconds, 0 = none; pixels not started in time stay black.
  double timeLimitSeconds = 0;

  /// Throws Error for spp below 1, negative threads, a negative or non-finite time, or a model
  /// not in modelNames(); each message names the option as `prefix` + its name ("spp 0: ..."
  /// for the library, "--spp 0: ..." for the CLI).
  void validate(std::string_view prefix = "") const;
  /// Applies --spp to a loaded description (overrideSamplesPerPixel).
  void applyTo(SceneDescription& description) const;
  /// Applies --spp, --seed, --threads and --time to the options a built scene asked for.
  void applyTo(RenderOptions& options) const;
};

/// Adds "name=value" (one -D) to `defines`; throws "-D TEXT: expected name=value".
void addDefine(SceneDefines& defines, std::string_view text);

/// The items of a comma-separated list, empty ones dropped ("a,,b" → a, b).
std::vector<std::string> splitList(std::string_view text);

/// Throws "OPTION NAME: unknown model; expected one of ..." unless `name` is in modelNames().
void checkModelName(std::string_view option, std::string_view name);

}  // namespace quadtri
