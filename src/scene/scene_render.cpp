#include "quadtri/scene/scene_render.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/scene/scene_description.h"

namespace quadtri {

PreparedRender prepareSceneRender(const std::filesystem::path& file,
                                  const SceneRenderRequest& request) {
  const RenderSettings& settings = request.settings;
  settings.validate();

  PreparedRender prepared;
  SceneDescription& description = prepared.description;
  description = loadSceneDescription(file, settings.defines);
  if (request.note)
    for (const std::string& note : description.notes) request.note(note);
  if (request.warn)
    for (const auto& [name, value] : settings.defines)
      if (std::find(description.defaultNames.begin(), description.defaultNames.end(), name) ==
          description.defaultNames.end())
        request.warn(fmt::format(
            "-D {}={}: {} has no <default name=\"{}\">; the value reaches only a ${} in the file",
            name, value, file.string(), name, name));
  if (request.crop && request.tile) fail("--crop and --tile: give one or the other");
  if (request.crop || request.tile) {
    FilmDesc& film = description.sensor.film;
    const PixelWindow window =
        request.crop ? *request.crop : tileWindow(*request.tile, film.width, film.height);
    if (window.x + window.width > film.width || window.y + window.height > film.height)
      fail("--crop {}: the window does not lie on the {}x{} film", window.toString(), film.width,
           film.height);
    film.cropX = window.x;
    film.cropY = window.y;
    film.cropWidth = window.width;
    film.cropHeight = window.height;
  }
  settings.applyTo(description);
  overrideNormals(description, request.normals, request.creaseAngleDegrees);
  prepared.built =
      buildScene(description, settings.model, request.maxMemoryBytes, request.deferModelChecks);
  if (request.warn)
    for (const std::string& warning : prepared.built.warnings) request.warn(warning);
  RenderOptions& options = prepared.options;
  options = prepared.built.options;
  settings.applyTo(options);
  return prepared;
}

}  // namespace quadtri
