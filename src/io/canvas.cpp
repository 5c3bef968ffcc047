#include "quadtri/io/canvas.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"

namespace quadtri {

struct Canvas::Impl {
  OIIO::ImageBuf buf;
};

Canvas::Canvas(int width, int height, const Rgb& background)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  impl_->buf.reset(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT));
  OIIO::ImageBufAlgo::fill(impl_->buf, background);
}

Canvas::~Canvas() = default;
Canvas::Canvas(Canvas&&) noexcept = default;
Canvas& Canvas::operator=(Canvas&&) noexcept = default;

void Canvas::set(int x, int y, const Rgb& c) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  impl_->buf.setpixel(x, y, c.data(), 3);
}

Rgb Canvas::get(int x, int y) const {
  Rgb c{0, 0, 0};
  impl_->buf.getpixel(x, y, c.data(), 3);
  return c;
}

void Canvas::fillRect(int x0, int y0, int x1, int y1, const Rgb& c) {
  OIIO::ImageBufAlgo::fill(impl_->buf, c,
                           OIIO::ROI(std::max(0, x0), std::min(width_, x1), std::max(0, y0),
                                     std::min(height_, y1), 0, 1, 0, 3));
}

const std::string& labelFontPath() {
  // Found at run time, so the installed library carries no path of the build machine: the
  // QUADTRI_FONT environment variable first, then where Debian and other distributions put
  // DejaVu Sans.
  static const std::string path = [] {
    if (const char* env = std::getenv("QUADTRI_FONT"); env && *env) return std::string(env);
    static constexpr std::array candidates = {
        "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
        "/usr/share/fonts/dejavu/DejaVuSans.ttf",
        "/usr/share/fonts/TTF/DejaVuSans.ttf",
        "/usr/local/share/fonts/DejaVuSans.ttf",
    };
    for (const char* c : candidates) {
      std::error_code ec;
      if (std::filesystem::is_regular_file(c, ec)) return std::string(c);
    }
    return std::string(candidates[0]);
  }();
  return path;
}

void Canvas::text(int x, int y, const std::string& s, int size, const Rgb& c, bool centered) {
  const bool ok = OIIO::ImageBufAlgo::render_text(
      impl_->buf, x, y, s, size, labelFontPath(), c,
      centered ? OIIO::ImageBufAlgo::TextAlignX::Center : OIIO::ImageBufAlgo::TextAlignX::Left,
      centered ? OIIO::ImageBufAlgo::TextAlignY::Center : OIIO::ImageBufAlgo::TextAlignY::Baseline);
  if (!ok)
    fail("cannot draw text with the font {} ({}): install fonts-dejavu-core or set QUADTRI_FONT",
         labelFontPath(), impl_->buf.geterror());
}

void Canvas::paste(const Canvas& other, int x, int y) {
  OIIO::ImageBufAlgo::paste(impl_->buf, x, y, 0, 0, other.impl_->buf);
}

void Canvas::savePng(const std::filesystem::path& path) const {
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    OIIO::ImageBuf out = OIIO::ImageBufAlgo::clamp(impl_->buf, 0.0f, 1.0f);
    if (!out.write(tmp.string(), OIIO::TypeDesc::UINT8))
      fail("{}: cannot write PNG ({})", path.string(), out.geterror());
  });
}

Rgb viridis(double t) {
  static constexpr float table[9][3] = {
      {0.267004f, 0.004874f, 0.329415f}, {0.278826f, 0.175490f, 0.483397f},
      {0.229739f, 0.322361f, 0.545706f}, {0.172719f, 0.448791f, 0.557885f},
      {0.127568f, 0.566949f, 0.550556f}, {0.157851f, 0.683765f, 0.501686f},
      {0.369214f, 0.788888f, 0.382914f}, {0.678489f, 0.863742f, 0.189503f},
      {0.993248f, 0.906157f, 0.143936f}};
  if (!std::isfinite(t)) t = 0.0;
  const double x = std::clamp(t, 0.0, 1.0) * 8.0;
  const int i = std::min(7, int(x));
  const float f = float(x - i);
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = table[i][k] * (1 - f) + table[i + 1][k] * f;
  return c;
}

}  // namespace quadtri
