// Per-patch images of how well a model meets the constraints (thesis figures 5.3-5.6, 6.2).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/io/canvas.h"
#include "quadtri/surface/model.h"

namespace quadtri {

/// A scalar field over patches: value(t, u, v), or nullopt where it is undefined.
using PatchField = std::function<std::optional<double>(size_t t, double u, double v)>;

/// Where patch t and its barycentric (u, v) land in a heatmap: patches are laid out row by row
/// in square cells, each drawn as an equilateral triangle (corner 0 bottom left, 1 bottom
/// right, 2 top). Inverse maps a pixel back to (t, u, v).
struct PatchLayout {
  size_t patches = 0;
  int columns = 1, cell = 64, left = 8, top = 48;

  /// Square cells of width / columns pixels (12 to 200) for about `width` pixels of patches.
  explicit PatchLayout(size_t patchCount, int width = 1200);
  int width() const;
  int height() const;
  /// Pixel centre of (t, u, v).
  Vec2 pixel(size_t t, double u, double v) const;
  /// The patch and barycentrics under pixel (x, y), if any.
  std::optional<std::tuple<size_t, double, double>> patchAt(int x, int y) const;
};

/// Thesis fig. 5.6a: the implicit quadric evaluated on its parametric patch, (f_i∘f_p)(u, v),
/// divided by |∇f_i| (a first-order distance) and by the mean edge length, so it is scale-free.
/// Defined for models with quadric patches only.
PatchField implicitResidualField(const SurfaceModel& model);
/// Thesis fig. 5.6b: |n_p × n_i|, the sine of the angle between the parametric normal and the
/// implicit quadric's normal at f_p(u, v). Defined for models with quadric patches only.
PatchField normalMisfitField(const SurfaceModel& model);

/// Draws `field` with the viridis map, a colour bar labelled with the range and a title.
Canvas drawHeatmap(const PatchLayout& layout, const PatchField& field, const std::string& title);
/// Thesis figs. 5.3-5.4: the model's normal as colour, each component mapped from its range
/// over the model to [0, 1].
Canvas drawNormalMap(const PatchLayout& layout, const SurfaceModel& model,
                     const std::string& title);

/// Writes MODEL-normals.png for every model and, for models with quadric patches,
/// MODEL-residual.png and MODEL-normal-misfit.png into `dir` (created if missing), laid out
/// about `width` pixels wide. Returns the paths written.
std::vector<std::filesystem::path> writeHeatmaps(const SurfaceModel& model,
                                                 const std::filesystem::path& dir,
                                                 const std::string& meshLabel, int width = 1200);

}  // namespace quadtri
