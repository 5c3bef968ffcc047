#include "quadtri/io/canvas.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "quadtri/io/atomic_file.h"
#include "quadtri/io/image_module.h"
#include "quadtri/math/error.h"

namespace quadtri {

// Interleaved RGB floats, row by row from the top.
struct Canvas::Impl {
  std::vector<float> rgb;
};

Canvas::Canvas(int width, int height, const Rgb& background)
    : impl_(std::make_unique<Impl>()), width_(std::max(0, width)), height_(std::max(0, height)) {
  impl_->rgb.resize(size_t(width_) * size_t(height_) * 3);
  fillRect(0, 0, width_, height_, background);
}

Canvas::~Canvas() = default;
Canvas::Canvas(Canvas&&) noexcept = default;
Canvas& Canvas::operator=(Canvas&&) noexcept = default;

void Canvas::set(int x, int y, const Rgb& c) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  std::copy(c.begin(), c.end(), impl_->rgb.begin() + 3 * (ptrdiff_t(y) * width_ + x));
}

Rgb Canvas::get(int x, int y) const {
  Rgb c{0, 0, 0};
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return c;
  const float* p = impl_->rgb.data() + 3 * (ptrdiff_t(y) * width_ + x);
  std::copy(p, p + 3, c.begin());
  return c;
}

void Canvas::fillRect(int x0, int y0, int x1, int y1, const Rgb& c) {
  for (int y = std::max(0, y0); y < std::min(height_, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(width_, x1); ++x) set(x, y, c);
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
  const std::string error = imageModule().drawText(impl_->rgb.data(), width_, height_, x, y, s,
                                                   size, labelFontPath(), c.data(), centered);
  if (!error.empty())
    fail("cannot draw text with the font {} ({}): install fonts-dejavu-core or set QUADTRI_FONT",
         labelFontPath(), error);
}

void Canvas::paste(const Canvas& other, int x, int y) {
  for (int j = 0; j < other.height_; ++j)
    for (int i = 0; i < other.width_; ++i) set(x + i, y + j, other.get(i, j));
}

void Canvas::savePng(const std::filesystem::path& path) const {
  // Clamped to [0, 1] and rounded to 8 bits, as OpenImageIO converts floats.
  std::vector<unsigned char> bytes(impl_->rgb.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    const float v = impl_->rgb[i];
    bytes[i] = (unsigned char)(std::clamp(v == v ? v : 0.0f, 0.0f, 1.0f) * 255.0f + 0.5f);
  }
  ImageFileSpec spec;
  spec.width = width_;
  spec.height = height_;
  spec.floatPixels = false;
  const ImageModule& module = imageModule();
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    if (const std::string error = module.write(tmp.string(), spec, bytes.data()); !error.empty())
      fail("{}: cannot write PNG ({})", path.string(), error);
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
