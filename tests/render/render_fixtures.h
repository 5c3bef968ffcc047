// Small scenes with known answers and the statistics to compare renders against them.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "quadtri/math/error.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/render/bsdf/diffuse.h"
#include "quadtri/render/integrator/integrator.h"
#include "quadtri/render/render_scene.h"
#include "quadtri/render/renderer.h"
#include "quadtri/render/sampling/warp.h"
#include "quadtri/surface/model.h"
#include "render/chi2.h"

namespace quadtri::testing {

/// Mitsuba's lookat: columns (left = up×dir, dir×left, dir, origin).
inline Mat4 lookAt(const Vec3& origin, const Vec3& target, const Vec3& up) {
  const Vec3 dir = (target - origin).normalized();
  const Vec3 left = up.cross(dir).normalized();
  const Vec3 newUp = dir.cross(left);
  Mat4 m = Mat4::Identity();
  m.block<3, 1>(0, 0) = left;
  m.block<3, 1>(0, 1) = newUp;
  m.block<3, 1>(0, 2) = dir;
  m.block<3, 1>(0, 3) = origin;
  return m;
}

inline PerspectiveCamera makeCamera(const Vec3& origin, const Vec3& target, double fov, int width,
                                    int height) {
  PerspectiveCamera::Params p;
  p.cameraToWorld =
      lookAt(origin, target,
             std::abs((target - origin).normalized().y()) > 0.9 ? Vec3(0, 0, 1) : Vec3(0, 1, 0));
  p.fovDegrees = fov;
  p.width = width;
  p.height = height;
  return PerspectiveCamera(p);
}

inline std::shared_ptr<const Bsdf> diffuse(double albedo) {
  return std::make_shared<Diffuse>(Color::Constant(albedo));
}

/// A world-space mesh rendered by the named model.
inline void addMesh(RenderScene& scene, TriangleMesh mesh, const std::string& model,
                    std::shared_ptr<const Bsdf> bsdf,
                    const std::optional<Color>& radiance = std::nullopt) {
  scene.addModel(std::shared_ptr<const SurfaceModel>(
                     makeModel(model, std::make_shared<TriangleMesh>(std::move(mesh)))),
                 Tessellation{}, std::move(bsdf), radiance, model);
}

/// The axis-aligned box [lo, hi] as 12 triangles whose winding normals face inwards.
inline TriangleMesh inwardBox(const Vec3& lo, const Vec3& hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                             i & 4 ? hi.z() : lo.z());
  // Outward-wound quads (a, b, c, d), reversed below.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({uint32_t(q[0]), uint32_t(q[2]), uint32_t(q[1])});
    m.triangles.push_back({uint32_t(q[0]), uint32_t(q[3]), uint32_t(q[2])});
  }
  return m;
}

/// Mean and standard error of a pixel's luminance from `count` camera samples (box filter).
struct PixelEstimate {
  double mean = 0.0, standardError = 0.0;
};

inline PixelEstimate estimatePixel(const RenderScene& scene, const Integrator& integrator, int x,
                                   int y, int count, uint64_t seed) {
  Pcg32 rng(seed, uint64_t(y) * 1000003u + uint64_t(x));
  double sum = 0.0, sumSq = 0.0;
  uint64_t rays = 0;
  for (int i = 0; i < count; ++i) {
    const Ray ray = scene.camera().generateRay(Vec2(x, y) + rng.next2D());
    const double l = luminance(integrator.radiance(scene, ray, rng, rays));
    sum += l;
    sumSq += l * l;
  }
  PixelEstimate e;
  e.mean = sum / count;
  e.standardError = std::sqrt(std::max(0.0, sumSq / count - e.mean * e.mean) / (count - 1));
  return e;
}

/// Z-tests every pixel of the camera's image against `expected` (luminance), at a family-wise
/// level `level` (Šidák); a zero-variance pixel must match to 1e-9.
inline void expectPixelsMatch(const RenderScene& scene, const Integrator& integrator,
                              double expected, int samples, double level = 1e-4) {
  const int w = scene.camera().width(), h = scene.camera().height();
  const double perPixel = sidakLevel(level, w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const PixelEstimate e = estimatePixel(scene, integrator, x, y, samples, 7);
      if (e.standardError == 0.0) {
        EXPECT_NEAR(e.mean, expected, 1e-9 * std::max(1.0, expected)) << "pixel " << x << "," << y;
        continue;
      }
      const double z = (e.mean - expected) / e.standardError;
      EXPECT_GT(twoSidedNormalPValue(z), perPixel)
          << "pixel " << x << "," << y << ": mean " << e.mean << " ± " << e.standardError
          << ", expected " << expected;
    }
}

/// Mean luminance of an image and its standard error from the spread of its pixels (valid
/// when every pixel has the same expectation, as in a furnace).
inline PixelEstimate imageMean(const Image& image) {
  double sum = 0.0, sumSq = 0.0;
  for (const Color& c : image.pixels) {
    sum += luminance(c);
    sumSq += luminance(c) * luminance(c);
  }
  const double n = double(image.pixels.size());
  PixelEstimate e;
  e.mean = sum / n;
  e.standardError = std::sqrt(std::max(0.0, sumSq / n - e.mean * e.mean) / (n - 1));
  return e;
}

}  // namespace quadtri::testing
