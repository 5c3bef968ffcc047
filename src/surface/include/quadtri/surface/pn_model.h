// `pn`: curved PN triangles (Vlachos, Peters, Boyd and Mitchell, I3D 2001).
#pragma once

#include <array>
#include <vector>

#include "quadtri/surface/creases.h"
#include "quadtri/surface/model.h"

namespace quadtri {

/// One PN triangle: the cubic Bézier geometry b(λ) = Σ_{i+j+k=3} 3!/(i!j!k!) λ0^i λ1^j λ2^k b_ijk
/// and the quadratic normal field n(λ) = Σ_{i+j+k=2} n_ijk λ0^i λ1^j λ2^k (the paper's
/// n200 w² + n110 wu + ..., no binomial factors), indices counting powers of (λ0, λ1, λ2).
struct PnPatch {
  /// Coefficients c[i][j] for i + j ≤ N, row after row, without the unused half of an
  /// (N+1)×(N+1) array (a PN patch is 384 bytes instead of 600).
  template <int N>
  class Triangular {
   public:
    Vec3* operator[](int i) { return values_.data() + offset(i); }
    const Vec3* operator[](int i) const { return values_.data() + offset(i); }

   private:
    static constexpr int offset(int i) { return i * (2 * N + 3 - i) / 2; }
    std::array<Vec3, (N + 1) * (N + 2) / 2> values_;
  };
  /// b[i][j] = b_{i,j,3−i−j}.
  Triangular<3> b;
  /// n[i][j] = n_{i,j,2−i−j}.
  Triangular<2> n;

  /// The paper's coefficients from corners p and unit normals nrm: edge points
  /// b_ij = (2p_i + p_j − w_ij n_i)/3 with w_ij = (p_j − p_i)·n_i; centre b111 = E + (E − V)/2
  /// (E the mean of the six edge points, V the centroid); n_ii = n_i; the edge normal n_ij is
  /// n_i + n_j − v_ij (p_j − p_i) normalised, v_ij = 2 (p_j − p_i)·(n_i + n_j) / |p_j − p_i|²,
  /// the mirror image of n_i + n_j in the plane normal to the edge.
  ///
  /// With `ends` (edgeEnds of the patch's triangle), an edge end where the mesh splits
  /// normals uses data both sides share: at a crease the edge point is (2p_i + p_j)/3
  /// projected onto the crease line through p_i, p_i + ((p_j − p_i)·d) d/3, instead of onto
  /// the tangent plane; nearly equal split normals are replaced by their mean.
  static PnPatch fromCorners(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& nrm,
                             const std::array<std::array<EdgeEnd, 2>, 3>* ends = nullptr);
  /// fromCorners' six edge points (edgePoints' order), without the rest of the patch.
  static std::array<Vec3, 6> cornerEdgePoints(
      const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& nrm,
      const std::array<std::array<EdgeEnd, 2>, 3>* ends = nullptr);
  /// The geometry from corners p and the six edge points (edgePoints' order), the centre
  /// computed as fromCorners computes it, bit for bit; the normal field is left unset.
  static PnPatch fromEdgePoints(const std::array<Vec3, 3>& p,
                                const std::array<Vec3, 6>& edgePoints);
  /// Sets the normal field n from corners p and unit normals nrm, as fromCorners does.
  void setNormalField(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& nrm);
  /// b_ab for (a, b) = (0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1): the points that depend
  /// on more than the corners (b_ab next to corner a towards b).
  std::array<Vec3, 6> edgePoints() const;

  Vec3 position(double u, double v) const;
  /// ∂b/∂u and ∂b/∂v: 3 Σ_{i+j+k=2} B²_ijk(λ) (b_{i,j+1,k} − b_{i+1,j,k}) and likewise for v.
  void derivatives(double u, double v, Vec3& du, Vec3& dv) const;
  /// The quadratic normal field at (u, v), not normalised.
  Vec3 normalField(double u, double v) const;
};

/// Curved PN triangles. evaluate() returns the cubic's geometric normal, so analysis measures
/// the geometry; the paper's own quadratic normal field, which a PN renderer shades with, is
/// pnNormal(). Each cubic boundary depends only on its edge's two corners and the data its
/// sides share there (their normal, or at a crease the crease line n₁ × n₂), so neighbours
/// always share edges (C0), split normals included. The corner tangent planes are the vertex
/// tangent planes, so the geometric normal at each corner is the vertex normal (at a crease
/// too: the crease line lies in the side's own tangent plane).
class PnModel final : public SurfaceModel {
 public:
  explicit PnModel(std::shared_ptr<const TriangleMesh> mesh);
  std::string_view name() const override { return "pn"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  Vec3 position(size_t t, double u, double v) const override;
  void positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const override;
  void patchRecord(size_t t, PatchRecord& out) const override;

  /// The paper's quadratic normal field of patch t at (u, v), normalised (falls back to the
  /// geometric normal where the field vanishes).
  Vec3 pnNormal(size_t t, double u, double v) const;
  /// Patch t, normal field included, rebuilt from the corners and its edge points.
  PnPatch patch(size_t t) const;

 private:
  /// Patch t's geometry without its normal field (what evaluate and position read).
  PnPatch geometry(size_t t) const;
  /// Patch t's six edge points: stored, or computed from its corners where nothing is stored.
  std::array<Vec3, 6> edgePoints(size_t t, const std::array<Vec3, 3>& p) const;
  /// At most the six edge points of each patch are kept (144 bytes, where the whole patch took
  /// 384): the corners are the mesh's and the centre and normal field follow from them. Where
  /// edgeEndsNeedTopology is false (no vertex whose corners carry different normals, so every
  /// end is Shared) the points follow from the corners and their normals alone and none is
  /// kept: computing them again costs less than the 144 MB a million triangles would take
  /// (and the time to fill them).
  std::vector<std::array<Vec3, 6>> edgePoints_;
};

}  // namespace quadtri
