#include "quadtri/scene/render_settings.h"

#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/surface/model.h"

namespace quadtri {

void RenderSettings::validate(std::string_view prefix) const {
  if (samplesPerPixel && *samplesPerPixel <= 0)
    fail("{}spp {}: expected a positive count", prefix, *samplesPerPixel);
  if (threads < 0) fail("{}threads {}: expected 0 (all) or a positive count", prefix, threads);
  if (timeLimitSeconds < 0.0 || !std::isfinite(timeLimitSeconds))
    fail("{}time {}: expected a positive number of seconds", prefix, timeLimitSeconds);
  if (model) checkModelName(fmt::format("{}model", prefix), *model);
}

void RenderSettings::applyTo(SceneDescription& description) const {
  if (samplesPerPixel) overrideSamplesPerPixel(description, *samplesPerPixel);
}

void RenderSettings::applyTo(RenderOptions& options) const {
  if (samplesPerPixel) options.samplesPerPixel = *samplesPerPixel;
  if (seed) options.seed = *seed;
  options.threads = threads;
  options.timeLimitSeconds = timeLimitSeconds;
}

void addDefine(SceneDefines& defines, std::string_view text) {
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0) fail("-D {}: expected name=value", text);
  defines[std::string(text.substr(0, eq))] = std::string(text.substr(eq + 1));
}

std::vector<std::string> splitList(std::string_view text) {
  std::vector<std::string> items;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string_view::npos) end = text.size();
    if (end > start) items.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
  return items;
}

void checkModelName(std::string_view option, std::string_view name) {
  const std::vector<std::string>& models = modelNames();
  if (std::find(models.begin(), models.end(), name) == models.end())
    fail("{} {}: unknown model; expected one of {}", option, name, fmt::join(models, ", "));
}

}  // namespace quadtri
