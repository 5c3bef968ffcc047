// Renders split into windows of the film (`quadtri render --crop/--tile`) and their assembly
// (`quadtri merge`). A tile is an EXR of its window: the data window places it on the film, the
// display window is the whole film, and string attributes say which render it belongs to.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "quadtri/render/image_io.h"

namespace quadtri {

/// A rectangle of film pixels [x, x + width) × [y, y + height).
struct PixelWindow {
  int x = 0, y = 0, width = 0, height = 0;
  /// "X,Y,W,H" (Mitsuba's crop_offset_x/y, crop_width/height). Throws Error naming `text`.
  static PixelWindow parse(const std::string& text);
  std::string toString() const;  ///< "X,Y,W,H", as parse reads it
  bool operator==(const PixelWindow&) const = default;
};

/// Tile I of N (1 <= I <= N) of a film, as `--tile I/N` gives it.
struct TileIndex {
  int index = 1, count = 1;
  /// "I/N". Throws Error naming `text`.
  static TileIndex parse(const std::string& text);
  std::string toString() const;  ///< "I/N"
};

/// The window of tile I/N: row bands, band I holding film rows [floor((I-1)·H/N),
/// floor(I·H/N)) across the whole width, so the N bands cover the film exactly once and differ
/// by at most one row. Throws Error when N exceeds the film's height (a band would be empty).
PixelWindow tileWindow(const TileIndex& tile, int filmWidth, int filmHeight);

/// The EXR attributes that tie a tile to its render; `quadtri merge` requires them equal on
/// every tile. The scene key is the render key of the whole film (render_key.h): the scene
/// file's and meshes' bytes, the defines, the model override, samples per pixel and seed.
namespace tile_attribute {
inline constexpr const char* kSceneKey = "quadtri_scene_key";  ///< 16 hex digits
inline constexpr const char* kScene = "quadtri_scene";         ///< the scene file's name
inline constexpr const char* kSeed = "quadtri_seed";
inline constexpr const char* kSamples = "quadtri_spp";
inline constexpr const char* kModel = "quadtri_model";  ///< the --model override, or "scene"
/// "I/N" of --tile, "crop" for --crop, "film" for a whole render (not compared).
inline constexpr const char* kTile = "quadtri_tile";
/// How many of the window's pixels the render left black, stopped by --time or a signal
/// (not compared: merge refuses a tile where it is not 0, unless told to allow it).
inline constexpr const char* kUnfinished = "quadtri_unfinished_pixels";
}  // namespace tile_attribute

/// What mergeTiles assembled.
struct MergeSummary {
  int width = 0, height = 0;  ///< the film
  size_t tiles = 0;
  size_t nonFiniteReplaced = 0;  ///< channels writeImage wrote as 0 (none for quadtri's tiles)
  size_t unfinishedPixels = 0;   ///< black pixels of cut-short tiles (allowUnfinished only)
};

struct MergeOptions {
  /// Merge tiles that a time limit or a signal cut short (their unfinished pixels stay black)
  /// instead of refusing them.
  bool allowUnfinished = false;
};

/// Reads the tile EXRs, checks that they come from one render (the same film size and the same
/// tile_attribute values but kTile) and that their windows cover the film exactly once, then
/// writes the assembled film to `output` (.exr) atomically, with the tiles' attributes. Throws
/// Error before anything is written: naming the tile that cannot be read or differs from the
/// first (and in what), the pairs of tiles that overlap (and where), and the film rectangles no
/// tile covers (as --crop windows, with the --tile I/N that is missing when the tiles say), and
/// every tile whose kUnfinished attribute says the render was cut short (unless allowed).
MergeSummary mergeTiles(const std::vector<std::filesystem::path>& tiles,
                        const std::filesystem::path& output, const MergeOptions& options = {});

}  // namespace quadtri
