#include "quadtri/analysis/heatmaps.h"

#include <fmt/core.h>

#include <cmath>

#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {
namespace {

constexpr int kBarWidth = 110;
const Rgb kBackground{0.12f, 0.12f, 0.12f};
const Rgb kText{0.95f, 0.95f, 0.95f};
const double kSqrt3Half = std::sqrt(3.0) / 2.0;

// The parametric patch and the quadric of patch t, shared by the two implicit fields.
struct ImplicitPair {
  std::vector<std::array<Vec3, 3>> control;
  double scale = 1.0;
};

std::shared_ptr<ImplicitPair> implicitPair(const SurfaceModel& model) {
  auto pair = std::make_shared<ImplicitPair>();
  pair->control = edgeControlPoints(model.mesh());
  const double e = model.mesh().meanEdgeLength();
  pair->scale = e > 0 ? e : 1.0;
  return pair;
}

}  // namespace

PatchLayout::PatchLayout(size_t patchCount, int width) : patches(patchCount) {
  columns = std::max(1, int(std::ceil(std::sqrt(double(std::max<size_t>(patchCount, 1))))));
  cell = std::clamp(width / columns, 12, 200);
}

int PatchLayout::width() const {
  return left + columns * cell + kBarWidth;
}
int PatchLayout::height() const {
  const int rows = int((patches + size_t(columns) - 1) / size_t(columns));
  return top + std::max(rows, 1) * cell + 8;
}

Vec2 PatchLayout::pixel(size_t t, double u, double v) const {
  const int cx = left + int(t % size_t(columns)) * cell, cy = top + int(t / size_t(columns)) * cell;
  const double margin = 0.06 * cell, side = cell - 2 * margin;
  // Corner 0 bottom left, 1 bottom right, 2 top centre.
  const double x = margin + side * (u + 0.5 * v);
  const double y = margin + side * kSqrt3Half * (1.0 - v) + side * (1.0 - kSqrt3Half) * 0.5;
  return Vec2(cx + x, cy + y);
}

std::optional<std::tuple<size_t, double, double>> PatchLayout::patchAt(int x, int y) const {
  if (x < left || y < top) return std::nullopt;
  const size_t col = size_t((x - left) / cell), row = size_t((y - top) / cell);
  if (col >= size_t(columns)) return std::nullopt;
  const size_t t = row * size_t(columns) + col;
  if (t >= patches) return std::nullopt;
  const double margin = 0.06 * cell, side = cell - 2 * margin;
  const double px = (x + 0.5) - (left + double(col) * cell) - margin;
  const double py =
      (y + 0.5) - (top + double(row) * cell) - margin - side * (1.0 - kSqrt3Half) * 0.5;
  const double v = 1.0 - py / (side * kSqrt3Half);
  const double u = px / side - 0.5 * v;
  if (u < 0 || v < 0 || u + v > 1) return std::nullopt;
  return std::make_tuple(t, u, v);
}

PatchField implicitResidualField(const SurfaceModel& model) {
  if (model.quadricPatches().empty()) return {};
  auto pair = implicitPair(model);
  return [&model, pair](size_t t, double u, double v) -> std::optional<double> {
    const QuadraticPatch fp = quadraticPatch(model.mesh(), pair->control, t);
    const Vec3 p = fp.position(u, v);
    const QuadricCoeffs& q = model.quadricPatches()[t].q;
    const double g = quadricGradient(q, p).norm();
    if (!(g > 0)) return std::nullopt;
    return evalQuadric(q, p) / g / pair->scale;
  };
}

PatchField normalMisfitField(const SurfaceModel& model) {
  if (model.quadricPatches().empty()) return {};
  auto pair = implicitPair(model);
  return [&model, pair](size_t t, double u, double v) -> std::optional<double> {
    const QuadraticPatch fp = quadraticPatch(model.mesh(), pair->control, t);
    Vec3 du, dv;
    fp.derivatives(u, v, du, dv);
    const Vec3 np = du.cross(dv);
    const Vec3 ni = quadricGradient(model.quadricPatches()[t].q, fp.position(u, v));
    if (!(np.norm() > 0) || !(ni.norm() > 0)) return std::nullopt;
    return np.normalized().cross(ni.normalized()).norm();
  };
}

Canvas drawHeatmap(const PatchLayout& layout, const PatchField& field, const std::string& title) {
  Canvas canvas(layout.width(), layout.height(), kBackground);
  std::vector<std::optional<double>> values(size_t(layout.width()) * layout.height());
  double lo = kInfinity, hi = -kInfinity;
  for (int y = 0; y < layout.height(); ++y)
    for (int x = 0; x < layout.width(); ++x)
      if (auto at = layout.patchAt(x, y)) {
        auto [t, u, v] = *at;
        std::optional<double> value = field(t, u, v);
        if (value && std::isfinite(*value)) {
          lo = std::min(lo, *value);
          hi = std::max(hi, *value);
          values[size_t(y) * layout.width() + x] = value;
        }
      }
  if (!(lo <= hi)) lo = hi = 0.0;
  const double range = hi > lo ? hi - lo : 1.0;
  for (int y = 0; y < layout.height(); ++y)
    for (int x = 0; x < layout.width(); ++x)
      if (const auto& value = values[size_t(y) * layout.width() + x])
        canvas.set(x, y, viridis((*value - lo) / range));
  // Colour bar with its range.
  const int bx = layout.width() - kBarWidth + 16, by0 = layout.top + 20, by1 = layout.height() - 28;
  for (int y = by0; y < by1; ++y)
    canvas.fillRect(bx, y, bx + 18, y + 1, viridis(1.0 - double(y - by0) / (by1 - by0)));
  canvas.text(bx, by0 - 6, fmt::format("{:.3g}", hi), 13, kText);
  canvas.text(bx, by1 + 16, fmt::format("{:.3g}", lo), 13, kText);
  canvas.text(layout.left, 30, title, 18, kText);
  return canvas;
}

Canvas drawNormalMap(const PatchLayout& layout, const SurfaceModel& model,
                     const std::string& title) {
  Canvas canvas(layout.width(), layout.height(), kBackground);
  // Thesis §5.2: each component normalised by its minimum and maximum over the model.
  Vec3 lo = Vec3::Constant(kInfinity), hi = Vec3::Constant(-kInfinity);
  std::vector<std::pair<int, Vec3>> pixels;
  for (int y = 0; y < layout.height(); ++y)
    for (int x = 0; x < layout.width(); ++x)
      if (auto at = layout.patchAt(x, y)) {
        auto [t, u, v] = *at;
        const Vec3 n = model.evaluate(t, u, v).normal;
        if (!allFinite(n)) continue;
        lo = lo.cwiseMin(n);
        hi = hi.cwiseMax(n);
        pixels.emplace_back(y * layout.width() + x, n);
      }
  const Vec3 range = (hi - lo).cwiseMax(Vec3::Constant(1e-12));
  for (const auto& [index, n] : pixels) {
    const Vec3 c = (n - lo).cwiseQuotient(range);
    canvas.set(index % layout.width(), index / layout.width(),
               Rgb{float(c.x()), float(c.y()), float(c.z())});
  }
  canvas.text(layout.left, 30, title, 18, kText);
  return canvas;
}

std::vector<std::filesystem::path> writeHeatmaps(const SurfaceModel& model,
                                                 const std::filesystem::path& dir,
                                                 const std::string& meshLabel, int width) {
  std::filesystem::create_directories(dir);
  const PatchLayout layout(model.patchCount(), width);
  const std::string name(model.name());
  std::vector<std::filesystem::path> written;
  auto save = [&](const Canvas& canvas, const std::string& suffix) {
    const auto path = dir / (name + "-" + suffix + ".png");
    canvas.savePng(path);
    written.push_back(path);
  };
  save(drawNormalMap(layout, model, fmt::format("{} on {}: normal as colour", name, meshLabel)),
       "normals");
  if (!model.quadricPatches().empty()) {
    save(drawHeatmap(
             layout, implicitResidualField(model),
             fmt::format("{} on {}: (f_i o f_p)(u,v) / |grad f_i| / mean edge", name, meshLabel)),
         "residual");
    save(drawHeatmap(layout, normalMisfitField(model),
                     fmt::format("{} on {}: |n_p x n_i|", name, meshLabel)),
         "normal-misfit");
  }
  return written;
}

}  // namespace quadtri
