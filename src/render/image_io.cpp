#include "quadtri/render/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"

namespace quadtri {

double linearToSrgb(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

size_t writeImage(const Image& image, const std::filesystem::path& path) {
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

  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out) fail("{}: cannot create an image writer: {}", path.string(), OIIO::geterror());
    const OIIO::TypeDesc type = exr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(image.width, image.height, 3, type);
    if (exr)
      spec.attribute("compression", "zip");
    else
      spec.attribute("oiio:ColorSpace", "sRGB");
    const void* data =
        exr ? static_cast<const void*>(linear.data()) : static_cast<const void*>(srgb.data());
    if (!out->open(tmp.string(), spec) || !out->write_image(type, data) || !out->close())
      fail("{}: writing the image failed: {}", path.string(), out->geterror());
  });
  return nonFinite;
}

}  // namespace quadtri
