// `nagata`: quadratic patches from Nagata, "Simple local interpolation of surfaces using
// normal vectors", CAGD 22 (2005) 327–347.
#pragma once

#include <array>
#include <vector>

#include "quadtri/surface/quadratic_model.h"

namespace quadtri {

/// Nagata's curvature coefficient of the edge x0 → x1 with unit normals n0, n1: the vector c
/// of the quadratic x(t) = x0 + (Δx − c) t + c t², Δx = x1 − x0, whose end tangents lie in the
/// tangent planes (n0·x'(0) = 0, n1·x'(1) = 0) with the least |c|. In the paper's notation
/// v = (n0 + n1)/2, Δv = (n0 − n1)/2, Δc = n0·Δv, c = 1 − 2Δc = n0·n1:
///   c = [⟨Δx, Δv⟩ / (1 − Δc)] v + [⟨Δx, v⟩ / Δc] Δv   (c ≠ ±1),   c = 0   (c = ±1).
/// The paper's zero rule for parallel or opposite normals is applied within 0.1°
/// (|n0·n1| ≥ cos 0.1°) so round-off cannot be amplified by the vanishing denominators. Near
/// (but beyond) opposite normals the coefficient still grows like 1/|v|, as published; Neto et
/// al. (CAD 45, 2013) discuss this limitation. Symmetric: swapping the ends gives the same c.
/// `gaveUp`, when given, is set to whether the zero rule left the edge straight although its
/// chord leaves one of the tangent planes by more than 0.1° (so x'(0) or x'(1) is not tangent).
Vec3 nagataCurvature(const Vec3& x0, const Vec3& n0, const Vec3& x1, const Vec3& n1,
                     bool* gaveUp = nullptr);

/// Nagata's patch x(η,ζ) = x00 + (x10 − x00 − c1) η + (x11 − x10 + c1 − c3) ζ + (c3 − c1 − c2) ηζ
/// + c1 η² + c2 ζ² on 0 ≤ ζ ≤ η ≤ 1 is the quadratic Bézier triangle over the same corners
/// whose edge control points are the chord midpoints minus c/2 (with barycentrics 1 − η, η − ζ,
/// ζ). It is stored as that QuadraticPatch, in quadtri's (u, v).
///
/// Like the thesis' edgeControlPoint, Nagata's control point lies on both end tangent planes,
/// i.e. on the line where they meet; Nagata takes the point of that line nearest the chord
/// midpoint (c ∈ span(n0, n1)), the thesis the point on its edge plane. They coincide where the
/// normals are symmetric about the edge (a sphere) and differ elsewhere.
///
/// Corners are interpolated and the corner tangent planes are the vertex tangent planes, so the
/// geometric normal there is the vertex normal (except on edges the zero rule flattens). Each
/// boundary depends only on its edge's corners and the data its sides share there, so
/// neighbours always share edges (C0): where the mesh splits normals at an end of an edge,
/// the edge takes creaseControlPoint (its tangent along the crease line n₁ × n₂) and
/// c = x0 + x1 − 2b; nearly equal split normals are replaced by their mean. fellBack(t): the zero
/// rule gave up an end tangent of one of the patch's edges (see nagataCurvature).
class NagataModel final : public QuadraticPatchModel {
 public:
  explicit NagataModel(std::shared_ptr<const TriangleMesh> mesh);
  std::string_view name() const override { return "nagata"; }
  void patchRecord(size_t t, PatchRecord& out) const override;

  /// Curvature coefficient of local edge k of patch t (corner k towards corner k+1).
  Vec3 curvature(size_t t, int k) const;

 private:
  /// On a mesh without split normals (edgeEndsNeedTopology) nothing is kept: a triangle's
  /// points follow from its corners and their normals (b = (x0 + x1)/2 − c/2).
  std::array<Vec3, 3> computeControlPoints(size_t t) const override;
  /// Per triangle where the mesh splits normals; empty on a smooth mesh, whose coefficients
  /// are computed when asked, as its control points are (only patchJson reads them).
  std::vector<std::array<Vec3, 3>> curvatures_;
};

}  // namespace quadtri
