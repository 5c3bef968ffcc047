// What a model does at its patches' corners, measured from three evaluations per patch: cheap
// enough to run on every conversion (the folds and fallbacks warning) and the one place the
// corner metrics of `quadtri analyze` come from.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "quadtri/surface/creases.h"
#include "quadtri/surface/model.h"

namespace quadtri {

/// Counts over the 3T corners of a model's T patches. Corner k of patch t is *consistent* when
/// the tangents there that every side of its two edges shares turn the way the patch's side
/// does: with T₁, T₂ the edges k→k+1 and k→k+2 projected onto the tangent plane of n_k (onto
/// the crease line at a crease end, EdgeEnd::tangentPart) and s = patchOrientation(t) (the
/// side the corner normals mostly point to), s (T₁ × T₂) · n_k > 0. Without creases that is
/// s (v1 − v0) × (v2 − v0) · n_k > 0: the triangle faces n_k (a zero-area triangle has no
/// consistent corner). Elsewhere constraint (2) contradicts the triangle (or the crease line
/// its neighbour shares) and no patch whose edges leave the corner along those tangents can
/// meet it without folding. Its patch *folds* there when the patch's normal n at the corner
/// points away from n_k: n · n_k < 0.
struct CornerStats {
  size_t corners = 0;
  size_t inconsistent = 0;         ///< corners that are not consistent
  size_t flips = 0;                ///< corners (all) where the patch folds
  size_t consistentFlips = 0;      ///< consistent corners where the patch folds
  double maxNormalErrorDeg = 0.0;  ///< max angle (degrees) between n and n_k, all corners
  /// The same over consistent corners; nullopt when there are none.
  std::optional<double> maxConsistentNormalErrorDeg;
  /// Corners where evaluate gave a non-finite position or normal (left out of the figures
  /// above), and the first such patch and corner.
  size_t nonFinite = 0;
  size_t firstNonFinitePatch = 0;
  int firstNonFiniteCorner = 0;

  size_t consistent() const { return corners - inconsistent; }
  double inconsistentRate() const { return corners ? double(inconsistent) / double(corners) : 0; }
  double flipRate() const { return corners ? double(flips) / double(corners) : 0.0; }
  /// consistentFlips / consistent(); nullopt when no corner is consistent.
  std::optional<double> consistentFlipRate() const;
};

/// Whether corner k of triangle t is consistent (CornerStats); `ends` = edgeEnds(mesh).
bool consistentCorner(const TriangleMesh& mesh, const EdgeEnds& ends, size_t t, int k);
/// The same with `orientation` = patchOrientation(mesh, t), computed once for the patch.
bool consistentCorner(const TriangleMesh& mesh, const EdgeEnds& ends, size_t t, int k,
                      double orientation);

/// Evaluates every patch at its three corners (in parallel; the result does not depend on the
/// thread count).
CornerStats cornerStats(const SurfaceModel& model);

/// The share of the model's patches that fell back (SurfaceModel::fellBack); 0 without patches.
double fallbackRate(const SurfaceModel& model);

/// Share of consistent corners that fold, or of patches that fall back, above which
/// conversionWarning speaks.
constexpr double kConversionWarningRate = 0.01;

/// One line for a freshly built model that folds at more than kConversionWarningRate of its
/// consistent corners or falls back on more than kConversionWarningRate of its patches, with
/// both figures, e.g. "bunny.obj: quadric-param folds at 2.31% of consistent corners (690 of
/// 29,868) and falls back on 0.1% of patches (10 of 9,956)"; nullopt otherwise, and always for
/// the models that keep the mesh's triangles (Representation::InputTriangles). `mesh` names the
/// mesh in the line.
std::optional<std::string> conversionWarning(const SurfaceModel& model, std::string_view mesh);

}  // namespace quadtri
