#include "quadtri/surface/g1_model.h"

#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"

namespace quadtri {
namespace {

// κ, η with d ≈ κ a + η b (least squares over span(a, b)); false where a and b are (nearly)
// parallel or vanish.
bool decompose(const Vec3& d, const Vec3& a, const Vec3& b, double& kappa, double& eta) {
  const double aa = a.dot(a), ab = a.dot(b), bb = b.dot(b);
  const double det = aa * bb - ab * ab;
  if (!(det > 1e-20 * aa * bb) || !std::isfinite(det)) return false;
  const double da = d.dot(a), db = d.dot(b);
  kappa = (da * bb - db * ab) / det;
  eta = (db * aa - da * ab) / det;
  return std::isfinite(kappa) && std::isfinite(eta);
}

}  // namespace

std::array<BezierTriangle, 3> g1Pieces(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n,
                                       const std::array<std::array<EdgeEnd, 2>, 3>* ends,
                                       bool* gaveUp) {
  // T[a][b]: the tangent of edge ab at p_a (the chord's tangent part there), alpha[a][b] the
  // unit transversal n_a × T[a][b] in a's tangent plane (zero where T vanishes).
  Vec3 T[3][3], alpha[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (a == b) continue;
      // The end of edge ab at a: local edge a (a → a+1) starts there, edge b (b → a) ends there.
      const EdgeEnd* end = nullptr;
      if (ends) end = b == (a + 1) % 3 ? &(*ends)[a][0] : &(*ends)[b][1];
      const Vec3 chord = p[b] - p[a];
      const Vec3& normal = end ? end->normalFor(n[a]) : n[a];
      T[a][b] = end ? end->tangentPart(chord, n[a]) : Vec3(chord - chord.dot(normal) * normal);
      alpha[a][b] = safeNormalized(normal.cross(T[a][b]), Vec3::Zero());
    }
  bool gave = false;

  // Edge k (corner k → k+1): its cubic c, raised to the quartic e, and the row next to it.
  std::array<std::array<Vec3, 5>, 3> e;
  std::array<std::array<Vec3, 2>, 3> row;  // s_{2,1,1} and s_{1,2,1} of piece k
  // ring[k] = s_{3,0,1} of piece k = s_{0,3,1} of piece k−1: the corner's ring point towards c.
  std::array<Vec3, 3> ring;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    ring[k] = p[k] + (T[k][k1] + T[k][k2]) / 12.0;
  }
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const Vec3 c1 = p[k] + T[k][k1] / 3.0, c2 = p[k1] + T[k1][k] / 3.0;
    // Written symmetrically, so the other side of the edge computes the same points bit for bit.
    e[k] = {p[k], (p[k] + 3.0 * c1) / 4.0, (c1 + c2) / 2.0, (3.0 * c2 + p[k1]) / 4.0, p[k1]};
    // b'(t) = Σ B²_j r_j.
    const std::array<Vec3, 3> r = {3.0 * (c1 - p[k]), 3.0 * (c2 - c1), 3.0 * (p[k1] - c2)};
    // D(t), the derivative towards the centroid along the edge, has Bézier coefficients
    // d_j = 4 (s_{3−j,j,1} − s_{4−j,j,0}); its ends are fixed by the corner rings.
    const Vec3 d0 = 4.0 * (ring[k] - e[k][0]);
    const Vec3 d3 = 4.0 * (ring[k1] - e[k][3]);
    const Vec3 a0 = alpha[k][k1], a1 = -alpha[k1][k];
    double kappa0, eta0, kappa1, eta1;
    Vec3 d1, d2;
    if (decompose(d0, a0, r[0], kappa0, eta0) && decompose(d3, a1, r[2], kappa1, eta1)) {
      // κ(t) a(t): quadratic, raised to degree 3; η(t) b'(t): cubic.
      const Vec3 q0 = kappa0 * a0, q1 = 0.5 * (kappa0 * a1 + kappa1 * a0);
      const Vec3 q2 = kappa1 * a1;
      d1 = (q0 + 2.0 * q1) / 3.0 + (2.0 * eta0 * r[1] + eta1 * r[0]) / 3.0;
      d2 = (2.0 * q1 + q2) / 3.0 + (eta0 * r[2] + 2.0 * eta1 * r[1]) / 3.0;
    } else {
      gave = true;
      d1 = (2.0 * d0 + d3) / 3.0;
      d2 = (d0 + 2.0 * d3) / 3.0;
    }
    row[k] = {e[k][1] + d1 / 4.0, e[k][2] + d2 / 4.0};
    (void)k2;
  }

  // Internal edge k (p_k → centroid): points E0 = p_k, E1 = ring[k], E2, F, Q. C1 across it
  // between piece k and piece k−1 (the centroid split makes p_{k−1} = 3c − p_k − p_{k+1}):
  // A_m + B_m = 3 E_{m+1} − E_m for the off-edge points A_m of piece k and B_m of piece k−1.
  std::array<Vec3, 3> E2, F, G;
  for (int k = 0; k < 3; ++k) {
    const int km = (k + 2) % 3;
    E2[k] = (row[k][0] + row[km][1] + ring[k]) / 3.0;
  }
  // F chosen so that each internal edge is a raised cubic (zero fourth difference) with
  // Q = (F0 + F1 + F2)/3 (C1 at the centroid): 4 F_k − ΣF/3 = r_k.
  std::array<Vec3, 3> rk;
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    rk[k] = p[k] - 4.0 * ring[k] + 6.0 * E2[k];
    sum += rk[k];
  }
  const Vec3 fSum = sum / 3.0;
  for (int k = 0; k < 3; ++k) F[k] = (rk[k] + fSum / 3.0) / 4.0;
  const Vec3 Q = (F[0] + F[1] + F[2]) / 3.0;
  // G_k = s_{1,1,2} of piece k: G_k + G_{k−1} = R_k = 3 F_k − E2_k.
  std::array<Vec3, 3> R;
  for (int k = 0; k < 3; ++k) R[k] = 3.0 * F[k] - E2[k];
  G[0] = (R[0] + R[1] - R[2]) / 2.0;
  G[1] = (R[1] + R[2] - R[0]) / 2.0;
  G[2] = (R[2] + R[0] - R[1]) / 2.0;

  std::array<BezierTriangle, 3> pieces;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    BezierTriangle& s = pieces[size_t(k)];
    for (int j = 0; j <= 4; ++j) s.at(4 - j, j, 0) = e[k][size_t(j)];
    s.at(3, 0, 1) = ring[k];
    s.at(2, 1, 1) = row[k][0];
    s.at(1, 2, 1) = row[k][1];
    s.at(0, 3, 1) = ring[k1];
    s.at(2, 0, 2) = E2[k];
    s.at(1, 1, 2) = G[k];
    s.at(0, 2, 2) = E2[k1];
    s.at(1, 0, 3) = F[k];
    s.at(0, 1, 3) = F[k1];
    s.at(0, 0, 4) = Q;
    s.piece = uint8_t(k);
  }
  if (gaveUp) *gaveUp = gave;
  return pieces;
}

G1PieceCoords g1PieceCoords(double u, double v) {
  const double l[3] = {1.0 - u - v, u, v};
  // Piece k spans (p_k, p_{k+1}, c): it holds the points whose smallest weight is λ_{k+2}.
  int m = 0;
  if (l[1] < l[m]) m = 1;
  if (l[2] < l[m]) m = 2;
  const int k = (m + 1) % 3;
  return {k, l[(k + 1) % 3] - l[m], 3.0 * l[m]};
}

G1Model::G1Model(std::shared_ptr<const TriangleMesh> mesh) : SurfaceModel(std::move(mesh)) {
  const TriangleMesh& m = this->mesh();
  const EdgeEnds ends = edgeEnds(m);
  resizeLarge(pieces_, 3 * m.triangleCount());
  std::vector<uint8_t> fallbacks(m.triangleCount(), 0);
  parallelForRange(tbb::blocked_range<size_t>(0, m.triangleCount(), 1024),
                   [&](const tbb::blocked_range<size_t>& range) {
                     for (size_t t = range.begin(); t != range.end(); ++t) {
                       const LocalTriangle tri = localTriangle(m, t);
                       bool gaveUp = false;
                       const auto pieces = g1Pieces(tri.p, tri.n, &ends[t], &gaveUp);
                       const double orientation = patchOrientation(m, t);
                       for (int k = 0; k < 3; ++k) {
                         BezierTriangle& s = pieces_[3 * t + size_t(k)];
                         s = pieces[size_t(k)];
                         s.orientation = orientation;
                         s.triangle = uint32_t(t);
                       }
                       fallbacks[t] = gaveUp;
                     }
                   });
  setFallbacks(std::move(fallbacks));
}

SurfacePoint G1Model::evaluate(size_t t, double u, double v) const {
  const G1PieceCoords c = g1PieceCoords(u, v);
  const BezierTriangle& s = piece(t, c.piece);
  Vec3 du, dv;
  s.derivatives(c.u, c.v, du, dv);
  // Each piece's map from the triangle's (u, v) keeps orientation (Jacobian determinant 3), so
  // the piece's du × dv points the way the triangle's would.
  return {s.position(c.u, c.v), orientedPatchNormal(mesh(), t, u, v, du, dv)};
}

void G1Model::patchRecord(size_t t, PatchRecord& out) const {
  addVertices(mesh(), t, out);
  // pieces[k][i]: control point i of piece k (BezierTriangle::index order).
  const PatchRecord::Ref pieces = out.setArray(PatchRecord::kRoot, "pieces");
  for (int k = 0; k < 3; ++k) {
    const PatchRecord::Ref points = out.pushArray(pieces);
    for (const Vec3& b : piece(t, k).b) out.push(points, b);
  }
}

}  // namespace quadtri
