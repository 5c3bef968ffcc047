// libquadtri_image.so: the OpenImageIO side of quadtri/io/image_module.h. Built as a module
// that only imageModule() loads, so that programs which write no image never load OpenImageIO.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <exception>

#include "quadtri/io/image_module.h"

namespace {

using quadtri::ImageFileSpec;

std::string writeImage(const std::string& path, const ImageFileSpec& spec, const void* pixels) {
  try {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return "cannot create an image writer: " + OIIO::geterror();
    const OIIO::TypeDesc type = spec.floatPixels ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec s(spec.width, spec.height, spec.channels, type);
    s.x = spec.x;
    s.y = spec.y;
    s.full_x = spec.fullX;
    s.full_y = spec.fullY;
    s.full_width = spec.fullWidth > 0 ? spec.fullWidth : spec.width;
    s.full_height = spec.fullHeight > 0 ? spec.fullHeight : spec.height;
    if (!spec.compression.empty()) s.attribute("compression", spec.compression);
    if (!spec.colorSpace.empty()) s.attribute("oiio:ColorSpace", spec.colorSpace);
    for (const auto& [name, value] : spec.attributes) s.attribute(name, value);
    if (!out->open(path, s) || !out->write_image(type, pixels) || !out->close()) {
      const std::string error = out->geterror();
      return error.empty() ? std::string("the writer gave no reason") : error;
    }
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string readImage(const std::string& path, ImageFileSpec& spec, std::vector<float>& pixels) {
  try {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return OIIO::geterror();
    const OIIO::ImageSpec& s = in->spec();
    spec = ImageFileSpec{};
    spec.width = s.width;
    spec.height = s.height;
    spec.channels = s.nchannels;
    spec.floatPixels = s.format == OIIO::TypeDesc::FLOAT;
    spec.x = s.x;
    spec.y = s.y;
    spec.fullX = s.full_x;
    spec.fullY = s.full_y;
    spec.fullWidth = s.full_width;
    spec.fullHeight = s.full_height;
    for (const OIIO::ParamValue& p : s.extra_attribs)
      if (p.type() == OIIO::TypeDesc::STRING)
        spec.attributes.emplace_back(p.name().string(), p.get_string());
    pixels.assign(size_t(s.width) * size_t(s.height) * size_t(s.nchannels), 0.0f);
    if (!in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
      return "reading the pixels failed: " + in->geterror();
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string drawText(float* rgb, int width, int height, int x, int y, const std::string& text,
                     int size, const std::string& fontPath, const float color[3], bool centered) {
  try {
    // The canvas' own pixels, wrapped: render_text writes into them.
    OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT), rgb);
    const bool ok = OIIO::ImageBufAlgo::render_text(
        buf, x, y, text, size, fontPath, {color[0], color[1], color[2]},
        centered ? OIIO::ImageBufAlgo::TextAlignX::Center : OIIO::ImageBufAlgo::TextAlignX::Left,
        centered ? OIIO::ImageBufAlgo::TextAlignY::Center
                 : OIIO::ImageBufAlgo::TextAlignY::Baseline);
    if (!ok) {
      const std::string error = buf.geterror();
      return error.empty() ? std::string("render_text failed") : error;
    }
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

const quadtri::ImageModule kModule{&writeImage, &readImage, &drawText};

}  // namespace

extern "C" __attribute__((visibility("default"))) const quadtri::ImageModule*
quadtri_image_module() {
  return &kModule;
}
