#include "quadtri/render/tiles.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <set>

#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"
#include "quadtri/render/image_io.h"

namespace quadtri {
namespace {

bool parseInt(const std::string& text, int& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end && !text.empty();
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t i = 0; i <= text.size(); ++i)
    if (i == text.size() || text[i] == sep) {
      parts.push_back(text.substr(start, i - start));
      start = i + 1;
    }
  return parts;
}

// One tile file as read: its window on the film, its film size, attributes and pixels.
struct Tile {
  std::string path;
  PixelWindow window;
  int filmWidth = 0, filmHeight = 0;
  std::map<std::string, std::string> attributes;
  Image image;
};

// Seed, samples and model first: they name the difference; the scene key catches the rest.
const char* const kCompared[] = {tile_attribute::kSeed, tile_attribute::kSamples,
                                 tile_attribute::kModel, tile_attribute::kSceneKey};

Tile readTile(const std::filesystem::path& path) {
  Tile tile;
  tile.path = path.string();
  ImageFrame frame;
  tile.image = readImage(path, &frame);
  tile.window = {frame.x, frame.y, tile.image.width, tile.image.height};
  tile.filmWidth = frame.filmWidth;
  tile.filmHeight = frame.filmHeight;
  if (frame.x < 0 || frame.y < 0 || frame.x + tile.image.width > frame.filmWidth ||
      frame.y + tile.image.height > frame.filmHeight)
    fail("{}: the data window {} does not lie on the {}x{} film", tile.path, tile.window.toString(),
         frame.filmWidth, frame.filmHeight);
  for (const auto& [name, value] : frame.attributes) tile.attributes[name] = value;
  for (const char* name : kCompared)
    if (!tile.attributes.count(name))
      fail("{}: no {} attribute: not a tile of `quadtri render` (--tile/--crop to .exr)", tile.path,
           name);
  return tile;
}

// The uncovered pixels as rectangles: the first uncovered pixel in row-major order grows
// right while uncovered, then down while the whole span is uncovered.
std::vector<PixelWindow> uncoveredRectangles(std::vector<int> count, int width, int height) {
  std::vector<PixelWindow> rects;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (count[size_t(y) * size_t(width) + size_t(x)] != 0) continue;
      int w = 0;
      while (x + w < width && count[size_t(y) * size_t(width) + size_t(x + w)] == 0) ++w;
      int h = 1;
      for (; y + h < height; ++h) {
        bool free = true;
        for (int i = 0; i < w && free; ++i)
          free = count[size_t(y + h) * size_t(width) + size_t(x + i)] == 0;
        if (!free) break;
      }
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) count[size_t(y + j) * size_t(width) + size_t(x + i)] = 1;
      rects.push_back({x, y, w, h});
    }
  return rects;
}

}  // namespace

PixelWindow PixelWindow::parse(const std::string& text) {
  const std::vector<std::string> parts = split(text, ',');
  PixelWindow w;
  if (parts.size() != 4 || !parseInt(parts[0], w.x) || !parseInt(parts[1], w.y) ||
      !parseInt(parts[2], w.width) || !parseInt(parts[3], w.height) || w.x < 0 || w.y < 0 ||
      w.width < 1 || w.height < 1)
    fail("--crop {}: expected X,Y,W,H with X, Y >= 0 and W, H >= 1, e.g. 0,0,64,32", text);
  return w;
}

std::string PixelWindow::toString() const {
  return fmt::format("{},{},{},{}", x, y, width, height);
}

TileIndex TileIndex::parse(const std::string& text) {
  const std::vector<std::string> parts = split(text, '/');
  TileIndex t;
  if (parts.size() != 2 || !parseInt(parts[0], t.index) || !parseInt(parts[1], t.count) ||
      t.count < 1 || t.index < 1 || t.index > t.count)
    fail("--tile {}: expected I/N with 1 <= I <= N, e.g. 2/4", text);
  return t;
}

std::string TileIndex::toString() const {
  return fmt::format("{}/{}", index, count);
}

PixelWindow tileWindow(const TileIndex& tile, int filmWidth, int filmHeight) {
  if (tile.count > filmHeight)
    fail("--tile {}: {} tiles are row bands of the {}x{} film, at most {} (its height)",
         tile.toString(), tile.count, filmWidth, filmHeight, filmHeight);
  const auto row = [&](int i) { return int(int64_t(i) * filmHeight / tile.count); };
  const int y0 = row(tile.index - 1), y1 = row(tile.index);
  return {0, y0, filmWidth, y1 - y0};
}

// The black pixels a cut-short render left in the tile; 0 for a tile written before the
// attribute existed (it cannot tell).
size_t unfinishedPixels(const Tile& tile) {
  const auto it = tile.attributes.find(tile_attribute::kUnfinished);
  if (it == tile.attributes.end()) return 0;
  size_t n = 0;
  const char* end = it->second.data() + it->second.size();
  const auto [ptr, ec] = std::from_chars(it->second.data(), end, n);
  if (ec != std::errc() || ptr != end)
    fail("{}: {} is '{}', expected a count of pixels", tile.path, tile_attribute::kUnfinished,
         it->second);
  return n;
}

MergeSummary mergeTiles(const std::vector<std::filesystem::path>& paths,
                        const std::filesystem::path& output, const MergeOptions& options) {
  if (paths.empty()) fail("merge: no tiles given");
  checkDistinctFiles(paths, output, "tile");
  std::vector<Tile> tiles;
  tiles.reserve(paths.size());
  for (const auto& path : paths) tiles.push_back(readTile(path));

  // One render: the film and the compared attributes of the first tile.
  const Tile& first = tiles.front();
  for (const Tile& t : tiles) {
    if (t.filmWidth != first.filmWidth || t.filmHeight != first.filmHeight)
      fail("{}: a tile of a {}x{} film, but {} is of a {}x{} film", t.path, t.filmWidth,
           t.filmHeight, first.path, first.filmWidth, first.filmHeight);
    for (const char* name : kCompared)
      if (t.attributes.at(name) != first.attributes.at(name))
        fail("{}: {} {}, but {} has {}: the tiles are not of one render", t.path, name,
             t.attributes.at(name), first.path, first.attributes.at(name));
  }

  // Exactly once: no two windows overlap, and together they cover the film.
  std::vector<std::string> problems;
  for (size_t i = 0; i < tiles.size(); ++i)
    for (size_t j = i + 1; j < tiles.size(); ++j) {
      const PixelWindow &a = tiles[i].window, &b = tiles[j].window;
      const int x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
      const int x1 = std::min(a.x + a.width, b.x + b.width);
      const int y1 = std::min(a.y + a.height, b.y + b.height);
      if (x0 < x1 && y0 < y1)
        problems.push_back(fmt::format(
            "{} and {} both cover the {} pixels of window {}", tiles[i].path, tiles[j].path,
            int64_t(x1 - x0) * int64_t(y1 - y0), PixelWindow{x0, y0, x1 - x0, y1 - y0}.toString()));
    }
  const int width = first.filmWidth, height = first.filmHeight;
  std::vector<int> count(size_t(width) * size_t(height), 0);
  for (const Tile& t : tiles)
    for (int y = 0; y < t.window.height; ++y)
      for (int x = 0; x < t.window.width; ++x)
        ++count[size_t(y + t.window.y) * size_t(width) + size_t(x + t.window.x)];
  const std::vector<PixelWindow> missing = uncoveredRectangles(count, width, height);
  if (!missing.empty()) {
    // When the --tile I/N tiles (crop windows aside) share one N, name the I that are absent.
    std::set<int> present;
    int n = 0;
    bool banded = true;
    for (const Tile& t : tiles) {
      const auto it = t.attributes.find(tile_attribute::kTile);
      if (it == t.attributes.end() || it->second.find('/') == std::string::npos) continue;
      const TileIndex index = TileIndex::parse(it->second);
      if (n != 0 && index.count != n) banded = false;
      n = index.count;
      present.insert(index.index);
    }
    std::string absent;
    if (banded)
      for (int i = 1; i <= n; ++i)
        if (!present.count(i))
          absent +=
              fmt::format("{}--tile {}", absent.empty() ? "" : ", ", TileIndex{i, n}.toString());
    std::string windows;
    const size_t shown = std::min<size_t>(missing.size(), 8);
    for (size_t i = 0; i < shown; ++i)
      windows += fmt::format("{}{}", i ? "; " : "", missing[i].toString());
    if (shown < missing.size()) windows += fmt::format("; and {} more", missing.size() - shown);
    problems.push_back(fmt::format("no tile covers film window{} (--crop X,Y,W,H) {}{}",
                                   missing.size() > 1 ? "s" : "", windows,
                                   absent.empty() ? "" : fmt::format(": missing {}", absent)));
  }
  if (!problems.empty()) {
    std::string text;
    for (const std::string& p : problems) text += "\n  " + p;
    fail("merge: {} not cover the {}x{} film exactly once:{}",
         tiles.size() == 1 ? std::string("the 1 tile does")
                           : fmt::format("the {} tiles do", tiles.size()),
         width, height, text);
  }

  // A tile cut short by --time or a signal has black pixels that look rendered.
  size_t unfinished = 0;
  std::string cutShort;
  for (const Tile& t : tiles)
    if (const size_t n = unfinishedPixels(t)) {
      unfinished += n;
      cutShort += fmt::format("\n  {}: {} of its {} pixels are not rendered", t.path, n,
                              int64_t(t.window.width) * int64_t(t.window.height));
    }
  if (!cutShort.empty() && !options.allowUnfinished)
    fail(
        "merge: a render was cut short (--time or a signal) in these tiles:{}\nrender them again "
        "(with --checkpoint and --resume for long ones), or merge with --allow-unfinished to keep "
        "their unfinished pixels black",
        cutShort);

  Image image(width, height);
  for (const Tile& t : tiles)
    for (int y = 0; y < t.window.height; ++y)
      for (int x = 0; x < t.window.width; ++x)
        image.at(x + t.window.x, y + t.window.y) = t.image.at(x, y);
  ImageFrame frame;
  for (const auto& [name, value] : first.attributes)
    if (name != tile_attribute::kTile && name != tile_attribute::kUnfinished)
      frame.attributes.emplace_back(name, value);
  frame.attributes.emplace_back(tile_attribute::kTile, "film");
  frame.attributes.emplace_back(tile_attribute::kUnfinished, std::to_string(unfinished));
  MergeSummary summary;
  summary.width = width;
  summary.height = height;
  summary.tiles = tiles.size();
  summary.unfinishedPixels = unfinished;
  summary.nonFiniteReplaced = writeImage(image, output, frame);
  return summary;
}

}  // namespace quadtri
