#include "quadtri/surface/edges_model.h"

#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"

namespace quadtri {
namespace {

// The edge curve from corner i to corner j of a patch: edge i forwards or edge j backwards.
EdgeCurve curve(const QuadraticPatch& p, int i, int j) {
  if (j == (i + 1) % 3) return {p.v[i], p.b[i], p.v[j]};
  return {p.v[i], p.b[j], p.v[j]};
}

// Transfinite interpolant P = Σ_m λ_m g_m, g_m = e_mj(λ_j) + e_mk(λ_k) − v_m (j, k the other two
// corners), and its partial derivatives. Expanded in the control net, P = Σ_i W_i v_i + Σ W_e b_e
// with W_i = λ_i (1 − 2 (λ_j + λ_k) + (λ_j² + λ_k²) + λ_i (1 − λ_i)) (the last term from the two
// curves that end at v_i, as λ_j + λ_k = 1 − λ_i) and, for the control point b of edge (i, j),
// W_e = 2 λ_i λ_j (2 − (λ_i + λ_j)): one weighted sum of six points instead of six curves (the
// automatic level's check evaluates 13 points a patch, the tessellation and the fold check
// more). Each weight is symmetric in the corners it pairs, to the bit; on an edge (λ_k = 0) only
// the edge's two corners and its control point remain, and the corners' two terms are added
// first (a sum of two is the same either way round), so both triangles of the edge compute its
// points with the same bits (C0 exactly), whichever way round each numbers the edge.
Vec3 transfinitePosition(const QuadraticPatch& p, const std::array<double, 3>& l) {
  const auto cornerWeight = [&](int i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    return l[i] * (1.0 - 2.0 * (l[j] + l[k]) + (l[j] * l[j] + l[k] * l[k]) + l[i] * (1.0 - l[i]));
  };
  const auto edgeWeight = [&](int i) {
    const int j = (i + 1) % 3;
    return 2.0 * l[i] * l[j] * (2.0 - (l[i] + l[j]));
  };
  for (int k = 0; k < 3; ++k) {
    if (l[k] != 0.0) continue;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    return (cornerWeight(i) * p.v[i] + cornerWeight(j) * p.v[j]) + edgeWeight(i) * p.b[i];
  }
  Vec3 pos = Vec3::Zero();
  for (int i = 0; i < 3; ++i) pos += cornerWeight(i) * p.v[i] + edgeWeight(i) * p.b[i];
  return pos;
}

// Treating λ0, λ1, λ2 as independent, ∂P/∂λ_m = g_m + Σ_{i≠m} λ_i e_im'(λ_m); then
// p_u = ∂P/∂λ1 − ∂P/∂λ0 and p_v = ∂P/∂λ2 − ∂P/∂λ0 since λ0 = 1-u-v. The position is
// transfinitePosition's, with or without the derivatives.
Vec3 transfinite(const QuadraticPatch& p, double u, double v, Vec3* pu, Vec3* pv) {
  const std::array<double, 3> l = {1.0 - u - v, u, v};
  const Vec3 pos = transfinitePosition(p, l);
  if (pu) {
    std::array<Vec3, 3> dl;
    for (int m = 0; m < 3; ++m) {
      const int j = (m + 1) % 3, k = (m + 2) % 3;
      const Vec3 g = curve(p, m, j).at(l[j]) + curve(p, m, k).at(l[k]) - p.v[m];
      dl[m] = g + l[j] * curve(p, j, m).tangent(l[m]) + l[k] * curve(p, k, m).tangent(l[m]);
    }
    *pu = dl[1] - dl[0];
    *pv = dl[2] - dl[0];
  }
  return pos;
}

// The thesis' eq. 4.2 in its own coordinates (u', v'), w = 1-u'-v':
//   P = u'A + v'B + wC, A = f_u(v') + f_w(1-w) − v0, B = f_v(w) + f_u(1-u') − v2,
//   C = f_w(u') + f_v(1-v') − v1.
// With ∂w/∂u' = ∂w/∂v' = −1:
//   ∂P/∂u' = A − C + u' f_w'(1-w) − v'(f_v'(w) + f_u'(1-u')) + w f_w'(u')
//   ∂P/∂v' = B − C + u'(f_u'(v') + f_w'(1-w)) − v' f_v'(w) − w f_v'(1-v')
// With dup and dvp null only the position is computed.
Vec3 thesisEq42(const QuadraticPatch& p, double up, double vp, Vec3* dup, Vec3* dvp) {
  const auto [fu, fv, fw] = thesisEdgeCurves(p);
  const double w = 1.0 - up - vp;
  const Vec3 A = fu.at(vp) + fw.at(1.0 - w) - p.v[0];
  const Vec3 B = fv.at(w) + fu.at(1.0 - up) - p.v[2];
  const Vec3 C = fw.at(up) + fv.at(1.0 - vp) - p.v[1];
  if (dup) {
    *dup = A - C + up * fw.tangent(1.0 - w) - vp * (fv.tangent(w) + fu.tangent(1.0 - up)) +
           w * fw.tangent(up);
    *dvp = B - C + up * (fu.tangent(vp) + fw.tangent(1.0 - w)) - vp * fv.tangent(w) -
           w * fv.tangent(1.0 - vp);
  }
  return up * A + vp * B + w * C;
}

void addCurve(PatchRecord& out, PatchRecord::Ref object, std::string_view key, const EdgeCurve& c) {
  const PatchRecord::Ref list = out.setArray(object, key);
  for (const Vec3& coefficient : c.coefficients()) out.push(list, coefficient);
}

}  // namespace

std::array<Vec3, 3> EdgeCurve::coefficients() const {
  return {a, 2.0 * (b - a), a - 2.0 * b + c};
}

std::array<EdgeCurve, 3> thesisEdgeCurves(const QuadraticPatch& patch) {
  return {curve(patch, 0, 1), curve(patch, 2, 0), curve(patch, 1, 2)};
}

EdgesModel::EdgesModel(std::shared_ptr<const TriangleMesh> mesh, Blend blend)
    : SurfaceModel(std::move(mesh)), blend_(blend) {
  std::vector<uint8_t> fallbacks;
  controlPoints_ = edgeControlPoints(this->mesh(), &fallbacks);
  setFallbacks(std::move(fallbacks));
}

SurfacePoint EdgesModel::evaluate(size_t t, double u, double v) const {
  const QuadraticPatch p = edges(t);
  Vec3 pu, pv, pos;
  if (blend_ == Blend::Transfinite) {
    pos = transfinite(p, u, v, &pu, &pv);
  } else {
    // Printed (u', v') = (v, u): ∂/∂u = ∂/∂v' and ∂/∂v = ∂/∂u'.
    pos = thesisEq42(p, v, u, &pv, &pu);
  }
  return {pos, orientedPatchNormal(mesh(), t, u, v, pu, pv)};
}

Vec3 EdgesModel::blendPosition(const QuadraticPatch& p, double u, double v) const {
  return blend_ == Blend::Transfinite ? transfinite(p, u, v, nullptr, nullptr)
                                      : thesisEq42(p, v, u, nullptr, nullptr);
}

Vec3 EdgesModel::position(size_t t, double u, double v) const {
  return blendPosition(edges(t), u, v);
}

void EdgesModel::positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const {
  const QuadraticPatch p = edges(t);
  for (size_t i = 0; i < count; ++i) out[i] = blendPosition(p, uv[i].x(), uv[i].y());
}

void EdgesModel::patchRecord(size_t t, PatchRecord& out) const {
  const QuadraticPatch p = edges(t);
  addControlNet(p, out);
  const auto [fu, fv, fw] = thesisEdgeCurves(p);
  const PatchRecord::Ref curves = out.setObject(PatchRecord::kRoot, "edge_curves");
  addCurve(out, curves, "f_u", fu);
  addCurve(out, curves, "f_v", fv);
  addCurve(out, curves, "f_w", fw);
}

}  // namespace quadtri
