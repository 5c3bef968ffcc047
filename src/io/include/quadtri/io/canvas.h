// An RGB image in linear [0,1] floats for figures: pixels, rectangles and text, saved as PNG.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>

namespace quadtri {

using Rgb = std::array<float, 3>;

/// The TrueType font of figure labels: $QUADTRI_FONT if set, else the first DejaVu Sans found
/// in the usual system folders (looked up once, at the first call).
const std::string& labelFontPath();

/// Figures (heatmaps, labelled grids) are drawn here and written as 8-bit PNG without any
/// transfer curve: the values are display values already.
class Canvas {
 public:
  Canvas(int width, int height, const Rgb& background);
  ~Canvas();
  Canvas(Canvas&&) noexcept;
  Canvas& operator=(Canvas&&) noexcept;

  int width() const { return width_; }
  int height() const { return height_; }
  void set(int x, int y, const Rgb& c);
  Rgb get(int x, int y) const;
  void fillRect(int x0, int y0, int x1, int y1, const Rgb& c);
  /// Draws text with DejaVu Sans; (x, y) is the left end of the baseline, or its centre when
  /// `centered`. Throws Error when the font cannot be found.
  void text(int x, int y, const std::string& s, int size, const Rgb& c, bool centered = false);
  /// Copies `other` with its top-left corner at (x, y), clipped to this canvas.
  void paste(const Canvas& other, int x, int y);
  /// Writes an 8-bit PNG atomically.
  void savePng(const std::filesystem::path& path) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_ = 0, height_ = 0;
};

/// The viridis colour map (perceptually uniform) at t in [0, 1], interpolated linearly between
/// 9 samples of matplotlib's published table.
Rgb viridis(double t);

}  // namespace quadtri
