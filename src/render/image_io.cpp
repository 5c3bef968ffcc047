#include "quadtri/render/image_io.h"

#include <algorithm>
#include <cmath>

#include "quadtri/io/atomic_file.h"
#include "quadtri/io/image_module.h"
#include "quadtri/math/error.h"

namespace quadtri {

double linearToSrgb(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

bool ImageFrame::wholeFilm(const Image& image) const {
  return x == 0 && y == 0 && (filmWidth == 0 || filmWidth == image.width) &&
         (filmHeight == 0 || filmHeight == image.height);
}

size_t writeImage(const Image& image, const std::filesystem::path& path) {
  return writeImage(image, path, ImageFrame{});
}

size_t writeImage(const Image& image, const std::filesystem::path& path, const ImageFrame& frame) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  const bool exr = ext == ".exr", png = ext == ".png";
  if (!exr && !png)
    fail("{}: unknown image format '{}': expected .exr or .png", path.string(), ext);
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != size_t(image.width) * size_t(image.height))
    fail("{}: the image is empty or inconsistent ({}x{})", path.string(), image.width,
         image.height);
  const int filmWidth = frame.filmWidth > 0 ? frame.filmWidth : image.width;
  const int filmHeight = frame.filmHeight > 0 ? frame.filmHeight : image.height;
  if (frame.x < 0 || frame.y < 0 || frame.x + image.width > filmWidth ||
      frame.y + image.height > filmHeight)
    fail("{}: the {}x{} image at {},{} does not lie on the {}x{} film", path.string(), image.width,
         image.height, frame.x, frame.y, filmWidth, filmHeight);
  if (png && !frame.wholeFilm(image))
    fail(
        "{}: the {}x{} window at {},{} of the {}x{} film can only be written as .exr (a PNG "
        "cannot say where it lies); merge the tiles with `quadtri merge`, then convert",
        path.string(), image.width, image.height, frame.x, frame.y, filmWidth, filmHeight);

  size_t nonFinite = 0;
  std::vector<float> linear(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = image.pixels[i][c];
      if (!std::isfinite(v)) ++nonFinite;
      linear[3 * i + c] = std::isfinite(v) ? float(v) : 0.0f;
    }
  std::vector<unsigned char> srgb;
  if (png) {
    srgb.resize(linear.size());
    for (size_t i = 0; i < linear.size(); ++i)
      srgb[i] = (unsigned char)std::lround(255.0 * linearToSrgb(linear[i]));
  }

  ImageFileSpec spec;
  spec.width = image.width;
  spec.height = image.height;
  spec.floatPixels = exr;
  if (exr) {
    spec.compression = "zip";
    spec.x = frame.x;
    spec.y = frame.y;
    spec.fullWidth = filmWidth;
    spec.fullHeight = filmHeight;
    spec.attributes = frame.attributes;
  } else
    spec.colorSpace = "sRGB";
  const void* data =
      exr ? static_cast<const void*>(linear.data()) : static_cast<const void*>(srgb.data());
  const ImageModule& module = imageModule();
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    if (const std::string error = module.write(tmp.string(), spec, data); !error.empty())
      fail("{}: writing the image failed: {}", path.string(), error);
  });
  return nonFinite;
}

Image readImage(const std::filesystem::path& path, ImageFrame* frame) {
  const std::string name = path.string();
  ImageFileSpec spec;
  std::vector<float> rgb;
  if (const std::string error = imageModule().read(name, spec, rgb); !error.empty())
    fail("{}: cannot read the image: {}", name, error);
  if (spec.channels != 3)
    fail("{}: {} channels, expected the 3 (RGB) quadtri writes", name, spec.channels);
  if (spec.fullX != 0 || spec.fullY != 0)
    fail("{}: the display window starts at {},{}, expected 0,0", name, spec.fullX, spec.fullY);
  Image image(spec.width, spec.height);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = Color(double(rgb[3 * i]), double(rgb[3 * i + 1]), double(rgb[3 * i + 2]));
  if (frame) {
    frame->x = spec.x;
    frame->y = spec.y;
    frame->filmWidth = spec.fullWidth;
    frame->filmHeight = spec.fullHeight;
    frame->attributes = std::move(spec.attributes);
  }
  return image;
}

}  // namespace quadtri
