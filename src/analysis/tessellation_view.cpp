#include "quadtri/analysis/tessellation_view.h"

#include <fmt/core.h>

#include <cmath>

#include "quadtri/math/error.h"

namespace quadtri {

OrthoView::OrthoView(const TriangleMesh& mesh, const Vec3& towardsEye, int sizePixels)
    : size(sizePixels) {
  if (mesh.positions.empty()) fail("tessellation view: the mesh has no vertices");
  if (size < 16) fail("tessellation view: {} pixels is too small", size);
  const Bounds3 box = mesh.bounds();
  center = box.center();
  double radius = 0.0;
  for (const Vec3& p : mesh.positions) radius = std::max(radius, (p - center).norm());
  back = safeNormalized(towardsEye, Vec3(0, 0, 1));
  // Up is the world's y axis made orthogonal to the view direction (z when looking along y).
  const Vec3 worldUp = std::abs(back.y()) > 0.99 ? Vec3(0, 0, -1) : Vec3(0, 1, 0);
  right = worldUp.cross(back).normalized();
  up = back.cross(right);
  // The bounding sphere plus a 5 % margin fills the square; radius 0 is a single point.
  pixelsPerUnit = 0.5 * size / (1.05 * std::max(radius, 1e-12));
}

Vec3 OrthoView::project(const Vec3& p) const {
  const Vec3 d = p - center;
  return Vec3(0.5 * size + pixelsPerUnit * d.dot(right),
              top + 0.5 * size - pixelsPerUnit * d.dot(up), d.dot(back));
}

Canvas drawTessellationView(const SurfaceModel& model, const Tessellation& tessellation,
                            const OrthoView& view, const std::string& title) {
  const Tessellation used = resolveTessellation(model, tessellation);
  const TriangleMesh mesh = tessellate(model, used);
  const size_t perPatch =
      model.representation() == Representation::InputTriangles ? 1 : used.trianglesPerPatch();
  const int width = view.size, height = view.top + view.size;
  Vec3 lo = Vec3::Constant(kInfinity), hi = Vec3::Constant(-kInfinity);
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(mesh.cornerNormal(t, k));
      hi = hi.cwiseMax(mesh.cornerNormal(t, k));
    }
  const Vec3 range = (hi - lo).cwiseMax(Vec3::Constant(1e-12));

  const size_t pixels = size_t(width) * size_t(height);
  std::vector<double> depth(pixels, -kInfinity);
  std::vector<int64_t> patch(pixels, -1);
  std::vector<Vec3> normal(pixels, Vec3::Zero());
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3 a = view.project(mesh.corner(t, 0)), b = view.project(mesh.corner(t, 1)),
               c = view.project(mesh.corner(t, 2));
    // Signed doubled area in pixels; both windings are drawn (two-sided).
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (!(std::abs(area) > 1e-12)) continue;
    const int x0 = std::max(0, int(std::floor(std::min({a.x(), b.x(), c.x()})))),
              x1 = std::min(width - 1, int(std::ceil(std::max({a.x(), b.x(), c.x()})))),
              y0 = std::max(view.top, int(std::floor(std::min({a.y(), b.y(), c.y()})))),
              y1 = std::min(height - 1, int(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        // Barycentrics of the pixel centre from the edge functions.
        const double w1 = ((px - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (py - a.y())) / area,
                     w2 = ((b.x() - a.x()) * (py - a.y()) - (px - a.x()) * (b.y() - a.y())) / area,
                     w0 = 1.0 - w1 - w2;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double z = w0 * a.z() + w1 * b.z() + w2 * c.z();
        const size_t i = size_t(y) * size_t(width) + size_t(x);
        if (z <= depth[i]) continue;
        depth[i] = z;
        patch[i] = int64_t(t / perPatch);
        normal[i] = w0 * mesh.cornerNormal(t, 0) + w1 * mesh.cornerNormal(t, 1) +
                    w2 * mesh.cornerNormal(t, 2);
      }
  }

  const Rgb white{1, 1, 1}, black{0, 0, 0};
  Canvas canvas(width, height, white);
  for (int y = view.top; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      if (patch[i] < 0) continue;
      auto differs = [&](int nx, int ny) {
        if (nx < 0 || ny < view.top || nx >= width || ny >= height) return true;
        return patch[size_t(ny) * size_t(width) + size_t(nx)] != patch[i];
      };
      if (differs(x - 1, y) || differs(x + 1, y) || differs(x, y - 1) || differs(x, y + 1)) {
        canvas.set(x, y, black);
        continue;
      }
      const Vec3 n = safeNormalized(normal[i], Vec3::Zero());
      const Vec3 colour = (n - lo).cwiseQuotient(range).cwiseMax(0.0).cwiseMin(1.0);
      canvas.set(x, y, Rgb{float(colour.x()), float(colour.y()), float(colour.z())});
    }
  canvas.text(6, view.top - 10, title, 11, black);
  return canvas;
}

std::vector<std::filesystem::path> writeTessellationViews(const SurfaceModel& model,
                                                          const std::filesystem::path& dir,
                                                          int size) {
  std::filesystem::create_directories(dir);
  // Framed on the densest tessellation, which bulges furthest, so both views share one scale.
  const OrthoView view(tessellate(model, Tessellation::thesis()), Vec3(1.0, 0.7, 1.6), size);
  const std::string name(model.name());
  std::vector<std::filesystem::path> written;
  const std::pair<Tessellation, const char*> kinds[] = {
      {Tessellation{Tessellation::Kind::Lattice, 1}, "corners"}, {Tessellation::thesis(), "2500"}};
  for (const auto& [tessellation, suffix] : kinds) {
    const auto path = dir / fmt::format("{}-view-{}.png", name, suffix);
    drawTessellationView(model, tessellation, view,
                         fmt::format("{}: {} uv points per patch", name,
                                     tessellation.kind == Tessellation::Kind::Lattice ? 3 : 2500))
        .savePng(path);
    written.push_back(path);
  }
  return written;
}

}  // namespace quadtri
