// `phong`: Phong tessellation (Boubekeur and Alexa, "Phong Tessellation", SIGGRAPH Asia 2008).
#pragma once

#include <array>
#include <vector>

#include "quadtri/surface/quadratic_model.h"

namespace quadtri {

/// Phong tessellation: p*(u,v) = (1−α) p(u,v) + α Σ_i λ_i π_i(p(u,v)), where p is the flat
/// triangle, λ = (1−u−v, u, v) and π_i(q) = q − ((q − p_i)·n_i) n_i projects onto corner i's
/// tangent plane; α is the paper's shape factor (3/4 recommended). The patch is quadratic:
/// with p − p_i = Σ_j λ_j (p_j − p_i) it is the quadratic Bézier triangle over the corners whose
/// edge control points are b_ij = (p_i + p_j)/2 − (α/2)(R_i(e) − R_j(e)), e = p_j − p_i and
/// R_i(e) = (e·n_i) n_i, what π_i removes from the chord; that is how it is evaluated.
///
/// Normal: the paper shades with the interpolated vertex normals; this model returns the
/// geometric normal (∂p*/∂u × ∂p*/∂v, analytic) instead, because quadtri's point is that the
/// geometric normal is the shading normal, and analysis must measure the geometry.
///
/// What holds (tested): corners are interpolated exactly; each boundary curve depends only on
/// its edge's two corners and the data its sides share there, so neighbours always share their
/// edges. Where the mesh splits normals at an end of an edge, R uses that shared data: at a
/// crease R(e) = e − (e·d)d, the part of the chord off the crease line d = n₁ × n₂ (the
/// projection onto the crease line instead of a tangent plane, so a straight crease stays
/// straight); nearly equal split normals are replaced by their mean. The geometric normal at a
/// corner is not the vertex normal in general (the other corners' tangent planes pull the
/// corner tangents out of it: 2.64° on an icosahedron with sphere normals at α = 3/4); flat
/// input gives the flat triangle.
class PhongModel final : public QuadraticPatchModel {
 public:
  explicit PhongModel(std::shared_ptr<const TriangleMesh> mesh, double alpha = 0.75);
  std::string_view name() const override { return "phong"; }
  void patchRecord(size_t t, PatchRecord& out) const override;
  double alpha() const { return alpha_; }

 private:
  /// On a mesh without split normals (edgeEndsNeedTopology) nothing is kept: each triangle's
  /// points are computed from its corners and normals when asked.
  std::array<Vec3, 3> computeControlPoints(size_t t) const override;
  double alpha_;
};

}  // namespace quadtri
