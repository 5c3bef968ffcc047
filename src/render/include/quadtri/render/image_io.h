// A linear RGB image and its output files.
#pragma once

#include <filesystem>
#include <vector>

#include "quadtri/math/color.h"

namespace quadtri {

/// Row-major linear RGB pixels, (0,0) at the top-left.
struct Image {
  int width = 0, height = 0;
  std::vector<Color> pixels;

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h), Color::Zero()) {}
  Color& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  const Color& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

/// The sRGB opto-electronic transfer function (IEC 61966-2-1) of a linear value clamped to [0, 1].
double linearToSrgb(double linear);

/// Writes `image` by extension: `.exr` as linear 32-bit float RGB, `.png` as 8-bit sRGB
/// (clamped, rounded). The file appears atomically. A NaN or infinite channel is written as 0;
/// returns how many channels were replaced so the caller can report them. Throws Error for an
/// unknown extension or a failed write, naming the file.
size_t writeImage(const Image& image, const std::filesystem::path& path);

}  // namespace quadtri
