// A linear RGB image and its output files.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
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

/// Where an image lies on its film, and the text attributes written with it.
struct ImageFrame {
  int x = 0, y = 0;  ///< the image's top-left pixel on the film (the EXR data window's origin)
  /// The whole film (the EXR display window); 0: the image's own size.
  int filmWidth = 0, filmHeight = 0;
  /// name=value string attributes of the EXR header (a PNG does not keep them).
  std::vector<std::pair<std::string, std::string>> attributes;
  /// Whether the image is all of its film (a PNG holds nothing else).
  bool wholeFilm(const Image& image) const;
};

/// writeImage with the image placed on its film: an EXR gets `frame`'s data and display windows
/// and attributes. A PNG is refused (Error) unless the image is the whole film: it cannot say
/// where a window lies.
size_t writeImage(const Image& image, const std::filesystem::path& path, const ImageFrame& frame);

/// Reads an RGB image (an EXR of writeImage, or any 3-channel file OpenImageIO reads) into
/// linear values; `frame`, when given, gets its data window's origin, its film (display window)
/// and its string attributes. Throws Error naming the file when it cannot be read, has other
/// than 3 channels, or its display window does not start at 0,0.
Image readImage(const std::filesystem::path& path, ImageFrame* frame = nullptr);

}  // namespace quadtri
