#include "quadtri/report/figure_cells.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <system_error>

#include "quadtri/math/error.h"
#include "quadtri/render/image_io.h"
#include "quadtri/report/shard.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

std::string joinTimes(const std::vector<double>& times) {
  std::string text;
  for (double t : times) text += fmt::format("{}{:.17g}", text.empty() ? "" : ";", t);
  return text;
}

double parseNumber(const fs::path& file, const char* name, const std::string& text) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value) || value < 0)
    fail("{}: {} is '{}', expected a non-negative number", file.string(), name, text);
  return value;
}

// The first ';'-separated item where two settings texts differ, for the error message.
std::string firstDifference(const std::string& a, const std::string& b) {
  size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  const size_t start = a.rfind(';', i) == std::string::npos ? 0 : a.rfind(';', i) + 1;
  const size_t endA = std::min(a.find(';', i), a.size()), endB = std::min(b.find(';', i), b.size());
  return fmt::format("{} against {}", a.substr(start, endA - start),
                     b.substr(std::min(start, b.size()), endB - std::min(start, b.size())));
}

}  // namespace

std::string figureSettingsText(const FigureRequest& request, const std::string& setup) {
  const RenderSettings& s = request.settings;
  std::string defines;
  for (const auto& [name, value] : s.defines)  // a std::map: sorted by name
    defines += fmt::format("{}{}={}", defines.empty() ? "" : ",", name, value);
  return fmt::format(
      "setup={};shapes={};models={};defines={};spp={};seed={};time={:.17g};normals={};crease={};"
      "repeats={}",
      setup, fmt::join(request.shapes, ","), fmt::join(request.models, ","), defines,
      s.samplesPerPixel ? std::to_string(*s.samplesPerPixel) : "scene",
      s.seed ? std::to_string(*s.seed) : "scene", s.timeLimitSeconds,
      request.normals ? std::to_string(int(*request.normals)) : "scene",
      request.creaseAngleDeg ? fmt::format("{:.17g}", *request.creaseAngleDeg) : "scene",
      request.repeats);
}

void saveFigureCell(const FigureCell& cell, const std::string& settingsText, const fs::path& dir,
                    const Shard& shard) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) fail("{}: cannot create the folder: {}", dir.string(), ec.message());
  ImageFrame frame;
  frame.attributes = {
      {figure_attribute::kSettings, settingsText},
      {figure_attribute::kShape, cell.shape},
      {figure_attribute::kModel, cell.model},
      {figure_attribute::kBuildSeconds, fmt::format("{:.17g}", cell.buildSeconds)},
      {figure_attribute::kRenderTimes, joinTimes(cell.renderTimes)},
      {figure_attribute::kSamples, fmt::format("{:.17g}", cell.meanSamplesPerPixel)},
      {figure_attribute::kPrimitives, std::to_string(cell.primitives)},
      {figure_attribute::kGeometryBytes, std::to_string(cell.geometryBytes)},
      {figure_attribute::kShard, shard.toString()}};
  writeImage(cell.image, dir / fmt::format("{}__{}.exr", cell.shape, cell.model), frame);
}

std::vector<FigureCell> loadFigureCells(const FigureRequest& request,
                                        const std::string& settingsText,
                                        const std::vector<fs::path>& dirs, size_t shardCount) {
  if (dirs.empty()) fail("figure: no folder of cells given");
  struct Found {
    FigureCell cell;
    fs::path file;
  };
  std::map<std::pair<std::string, std::string>, Found> found;
  size_t savedCount = 0;
  for (const fs::path& dir : dirs) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) fail("{}: not a folder of figure cells", dir.string());
    std::vector<fs::path> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec))
      if (entry.path().extension() == ".exr") files.push_back(entry.path());
    if (ec) fail("{}: cannot list the folder: {}", dir.string(), ec.message());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      ImageFrame frame;
      FigureCell cell;
      cell.image = readImage(file, &frame);
      std::map<std::string, std::string> attributes(frame.attributes.begin(),
                                                    frame.attributes.end());
      const auto get = [&](const char* name) -> const std::string& {
        const auto it = attributes.find(name);
        if (it == attributes.end())
          fail("{}: no {} attribute: not a cell of `quadtri figure --cells`", file.string(), name);
        return it->second;
      };
      if (get(figure_attribute::kSettings) != settingsText)
        fail("{}: a cell of another figure: {}", file.string(),
             firstDifference(get(figure_attribute::kSettings), settingsText));
      cell.shape = get(figure_attribute::kShape);
      cell.model = get(figure_attribute::kModel);
      cell.buildSeconds =
          parseNumber(file, figure_attribute::kBuildSeconds, get(figure_attribute::kBuildSeconds));
      const std::string& times = get(figure_attribute::kRenderTimes);
      for (size_t start = 0; start < times.size();) {
        const size_t end = std::min(times.find(';', start), times.size());
        cell.renderTimes.push_back(
            parseNumber(file, figure_attribute::kRenderTimes, times.substr(start, end - start)));
        start = end + 1;
      }
      if (cell.renderTimes.empty())
        fail("{}: {} lists no render time", file.string(), figure_attribute::kRenderTimes);
      cell.renderSeconds = median(cell.renderTimes);
      cell.meanSamplesPerPixel =
          parseNumber(file, figure_attribute::kSamples, get(figure_attribute::kSamples));
      cell.primitives = size_t(
          parseNumber(file, figure_attribute::kPrimitives, get(figure_attribute::kPrimitives)));
      cell.geometryBytes = size_t(parseNumber(file, figure_attribute::kGeometryBytes,
                                              get(figure_attribute::kGeometryBytes)));
      // The shard count the cells were rendered with, when they all say the same.
      if (const auto it = attributes.find(figure_attribute::kShard); it != attributes.end()) {
        const size_t count = Shard::parse(it->second).count;
        savedCount = savedCount == 0 || savedCount == count ? count : size_t(-1);
      }
      const auto key = std::make_pair(cell.shape, cell.model);
      const auto [it, inserted] = found.try_emplace(key, Found{std::move(cell), file});
      if (!inserted)
        fail("figure: the cell {} / {} is in both {} and {}", key.first, key.second,
             it->second.file.string(), file.string());
    }
  }
  if (shardCount == 0 && savedCount != size_t(-1)) shardCount = savedCount;
  std::vector<FigureCell> cells;
  std::string missing;
  for (size_t row = 0; row < request.shapes.size(); ++row)
    for (const std::string& model : request.models) {
      const auto it = found.find({request.shapes[row], model});
      if (it == found.end()) {
        missing += fmt::format("\n  {} / {}", request.shapes[row], model);
        if (shardCount > 0)
          for (size_t i = 1; i <= shardCount; ++i)
            if (Shard{i, shardCount}.holds(row))
              missing += fmt::format(" (rendered by --shard {})", Shard{i, shardCount}.toString());
        continue;
      }
      cells.push_back(std::move(it->second.cell));
    }
  if (!missing.empty()) fail("figure: no folder holds these cells:{}", missing);
  return cells;
}

}  // namespace quadtri
