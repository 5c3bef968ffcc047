// Thesis figs. 5.3-5.4: a model's tessellation seen in 3D, the normal as colour and the patch
// boundaries drawn, to check constraints (1)-(4) by eye.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "quadtri/io/canvas.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

/// An orthographic camera looking along -towardsEye at a mesh's bounding sphere, which fills a
/// square of `size` pixels below a title band of `top` pixels.
struct OrthoView {
  Vec3 center, right, up, back;
  double pixelsPerUnit = 1.0;
  int size = 320, top = 28;

  OrthoView(const TriangleMesh& mesh, const Vec3& towardsEye, int size = 320);
  /// (x, y) pixel coordinates (x right, y down, title band included) and the depth of p
  /// (larger is closer to the eye).
  Vec3 project(const Vec3& p) const;
};

/// Rasterises tessellate(model, tessellation) with a z-buffer. A pixel's colour is the vertex
/// normals interpolated over the visible triangle, each component mapped from its range over
/// all the tessellation's normals to [0, 1] (thesis §5.2). A pixel whose patch differs from a
/// 4-neighbour's (another patch, or the background) is black: the patch boundaries and the
/// silhouette; the edges inside a patch are not drawn. The background is white.
Canvas drawTessellationView(const SurfaceModel& model, const Tessellation& tessellation,
                            const OrthoView& view, const std::string& title);

/// Writes MODEL-view-corners.png (lattice level 1: the 3 corner points per patch, thesis fig.
/// 5.3) and MODEL-view-2500.png (the thesis' 50×50 grid, fig. 5.4) into `dir` (created if
/// missing), seen from a fixed oblique direction. Returns the paths written.
std::vector<std::filesystem::path> writeTessellationViews(const SurfaceModel& model,
                                                          const std::filesystem::path& dir,
                                                          int size = 320);

}  // namespace quadtri
