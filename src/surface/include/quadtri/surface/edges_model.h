// `quadric-edges` and `quadric-edges-eq42`: quadratic edge curves blended over the triangle
// (thesis §4.1).
#pragma once

#include <array>
#include <vector>

#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/model.h"

namespace quadtri {

/// The quadratic Bézier curve (1-s)² a + 2s(1-s) b + s² c, s in [0, 1].
struct EdgeCurve {
  Vec3 a, b, c;

  // Inline: the blends evaluate six curves a point (the auto tessellation's level check
  // evaluates 13 points a patch).
  Vec3 at(double s) const {
    return (1.0 - s) * (1.0 - s) * a + 2.0 * s * (1.0 - s) * b + s * s * c;
  }
  /// d/ds of at(s).
  Vec3 tangent(double s) const { return 2.0 * ((1.0 - s) * (b - a) + s * (c - b)); }
  /// The thesis' eq. 4.1 coefficients {c0, c1, c2} of f(s) = s² c2 + s c1 + c0.
  std::array<Vec3, 3> coefficients() const;
};

/// The thesis' three edge curves of a patch as eq. 4.3 assigns them: f_u from v0 to v1, f_v
/// from v2 to v0, f_w from v1 to v2 (in that order).
std::array<EdgeCurve, 3> thesisEdgeCurves(const QuadraticPatch& patch);

/// Each triangle's edges become the quadratic curves of edge_curves.h (the closed form of the
/// thesis' 27×27 system, eq. 4.3-4.5), shared by both triangles of an edge, blended over the
/// triangle by one of two formulas:
///
/// - Transfinite (`quadric-edges`): P(λ) = Σ_i λ_i [e_ij(λ_j) + e_ik(λ_k) − v_i] with
///   λ = (1-u-v, u, v), {i, j, k} = {0, 1, 2} and e_ij the edge curve from v_i to v_j. On the
///   edge λ_k = 0 it reduces to λ_i e_ij(λ_j) + λ_j e_ji(λ_i) = e_ij(λ_j), so every boundary is
///   its edge curve exactly (C0 with the neighbour), and at corner i the tangents are the edge
///   curves' tangents, which lie in the tangent plane of n_i. The surface is cubic.
///
/// - ThesisEq42 (`quadric-edges-eq42`, a reproduction that cracks): the thesis' eq. 4.2 as
///   printed, f_p(u',v') = u'(f_u(v') + f_w(1-w) − f_u(0)) + v'(f_v(w) + f_u(1-u') − f_v(0))
///   + w(f_w(u') + f_v(1-v') − f_w(0)), w = 1-u'-v'. Its corners are (0,0) → v0, (1,0) → v2,
///   (0,1) → v1, so evaluate(t, u, v) = f_p(u' = v, v' = u) to keep the interface's corner
///   order. Each printed boundary is its chord plus another edge's bulge 2s(1-s)(b − m)
///   (m the chord midpoint): edge v0v1 carries v2v0's, v1v2 carries v0v1's, v2v0 carries
///   v1v2's, so the boundary misses its edge curve by up to |Δbulge|/2, and the corner tangents
///   are not in the tangent planes. sharesEdges() is false so its tessellation is not welded.
///
/// fellBack(t): one of the patch's edge control points gave up its tangent planes (clamped, or a
/// damped solve off them: edge_curves.h).
///
/// patchJson(t): {"vertices": [v0, v1, v2], "control_points": {"b01", "b12", "b20"},
/// "edge_curves": {"f_u": [c0, c1, c2], "f_v": [...], "f_w": [...]}} (eq. 4.1, 4.3).
class EdgesModel final : public SurfaceModel {
 public:
  enum class Blend { Transfinite, ThesisEq42 };

  EdgesModel(std::shared_ptr<const TriangleMesh> mesh, Blend blend);
  std::string_view name() const override {
    return blend_ == Blend::Transfinite ? "quadric-edges" : "quadric-edges-eq42";
  }
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  Vec3 position(size_t t, double u, double v) const override;
  void positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const override;
  bool sharesEdges() const override { return blend_ == Blend::Transfinite; }
  void patchRecord(size_t t, PatchRecord& out) const override;

  /// Corners and edge control points of triangle t (edge k joins corners k and k+1).
  QuadraticPatch edges(size_t t) const { return quadraticPatch(mesh(), controlPoints_, t); }

 private:
  /// position() of the patch p: the blend's sums without their derivatives.
  Vec3 blendPosition(const QuadraticPatch& p, double u, double v) const;
  Blend blend_;
  std::vector<std::array<Vec3, 3>> controlPoints_;
};

}  // namespace quadtri
