#include "quadtri/surface/edge_curves.h"

#include "quadtri/math/large_array.h"
#include "quadtri/math/least_squares.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/creases.h"

namespace quadtri {
namespace {

// Damping of the pseudo-inverse relative to the (unit) row scale: negligible where the planes
// meet at a real angle (relative effect ~1e-14/σ²), decisive where they are parallel.
constexpr double kDamping = 1e-7;
// The control point may sit at most this many edge lengths from the chord midpoint.
constexpr double kMaxOffset = 1.0;
// Distance from a tangent plane, relative to the edge length, beyond which the control point
// counts as having given up that plane (far above the damping's bias on real data, ~1e-14/σ).
constexpr double kTangentTolerance = 1e-6;

// The control point of one mesh edge, from the normals its triangles share (see the header).
Vec3 sharedEdgeControlPoint(const TriangleMesh& mesh, const Edge& edge,
                            const std::array<EdgeEnd, 2>& ends, bool& gaveUp) {
  gaveUp = false;
  const Vec3& va = mesh.positions[edge.a];
  const Vec3& vb = mesh.positions[edge.b];
  const auto [t0, k0] = edge.sides.front();
  const bool f0 = mesh.triangles[t0][k0] == edge.a;
  const Vec3 na0 = mesh.cornerNormal(t0, f0 ? k0 : (k0 + 1) % 3);
  const Vec3 nb0 = mesh.cornerNormal(t0, f0 ? (k0 + 1) % 3 : k0);
  // At a crease the tangent follows the crease line, which both sides share (creases.h).
  if (ends[0].crease() || ends[1].crease())
    return creaseControlPoint(va, ends[0], na0, vb, ends[1], nb0);
  // With a single side (or no split) the mean is the corner normal itself: keep it exact.
  if (ends[0].kind == EdgeEnd::Kind::Shared && ends[1].kind == EdgeEnd::Kind::Shared)
    return edgeControlPoint(va, na0, vb, nb0, &gaveUp);
  Vec3 na = Vec3::Zero(), nb = Vec3::Zero();
  for (auto [t, k] : edge.sides) {
    const bool forward = mesh.triangles[t][k] == edge.a;
    na += mesh.cornerNormal(t, forward ? k : (k + 1) % 3);
    nb += mesh.cornerNormal(t, forward ? (k + 1) % 3 : k);
  }
  return edgeControlPoint(va, safeNormalized(na, na0), vb, safeNormalized(nb, nb0), &gaveUp);
}

}  // namespace

Vec3 dampedLeastSquares(const Mat3& M, const Vec3& r, double mu) {
  // The damped pseudo-inverse solution Σ_k σ_k/(σ_k² + μ²) (u_k·r) v_k is the Tikhonov
  // minimiser of |Mδ − r|² + μ²|δ|², i.e. the least-squares solution of [M; μI] δ = [r; 0].
  // A QR factorisation of that 6×3 matrix computes it as accurately as an SVD of M (no normal
  // equations, so the condition number is not squared). Every column holds μ, so the columns are
  // independent; only non-finite input makes the solve refuse, and then the answer is NaN.
  Eigen::Matrix<double, 6, 3> A;
  A.topRows<3>() = M;
  A.bottomRows<3>() = mu * Mat3::Identity();
  Eigen::Matrix<double, 6, 1> rhs;
  rhs << r, 0.0, 0.0, 0.0;
  Vec3 x;
  if (!householderLeastSquares(A, rhs, x, 0.0)) x.setConstant(std::nan(""));
  return x;
}

bool edgeEndsSwapped(const Vec3& vi, const Vec3& ni, const Vec3& vj, const Vec3& nj) {
  auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  return less(vj, vi) || (vj == vi && less(nj, ni));
}

Vec3 edgeControlPoint(const Vec3& viIn, const Vec3& niIn, const Vec3& vjIn, const Vec3& njIn,
                      bool* gaveUp) {
  if (gaveUp) *gaveUp = false;
  // Canonical order makes the result independent of which side asks.
  const bool swap = edgeEndsSwapped(viIn, niIn, vjIn, njIn);
  const Vec3& vi = swap ? vjIn : viIn;
  const Vec3& vj = swap ? viIn : vjIn;
  const Vec3& ni = swap ? njIn : niIn;
  const Vec3& nj = swap ? niIn : njIn;
  const Vec3 e = vj - vi;
  const double len = e.norm();
  const Vec3 mid = 0.5 * (vi + vj);
  if (!(len > 0.0)) return mid;
  // b = mid + δ. Tangent planes: ni·(b - vi) = 0 and nj·(b - vj) = 0. The edge plane (eq. 4.5)
  // has normal np = e × (e/2 + nm) = e × nm, so np·(b - vi) = 0 reduces to np·δ = 0.
  const Vec3 nm = 0.5 * (ni + nj);
  Vec3 np = e.cross(nm);
  const double npLen = np.norm();
  np = npLen > 1e-9 * len ? Vec3(np / npLen) : Vec3::Zero();
  Mat3 M;
  M.row(0) = ni.transpose();
  M.row(1) = nj.transpose();
  M.row(2) = np.transpose();
  const Vec3 r(-0.5 * ni.dot(e), 0.5 * nj.dot(e), 0.0);
  Vec3 delta = dampedLeastSquares(M, r, kDamping);
  const double dl = delta.norm();
  if (!std::isfinite(dl)) {
    if (gaveUp) *gaveUp = true;
    return mid;
  }
  if (dl > kMaxOffset * len) {
    delta *= kMaxOffset * len / dl;
    if (gaveUp) *gaveUp = true;
  }
  // Residuals of the two tangent planes: ni·δ = r0 and nj·δ = r1.
  if (gaveUp && std::max(std::abs(ni.dot(delta) - r[0]), std::abs(nj.dot(delta) - r[1])) >
                    kTangentTolerance * len)
    *gaveUp = true;
  return mid + delta;
}

std::vector<std::array<Vec3, 3>> edgeControlPoints(const TriangleMesh& mesh,
                                                   std::vector<uint8_t>* gaveUpPatches) {
  return edgeControlPoints(mesh, mesh.topology(), gaveUpPatches);
}

std::vector<std::array<Vec3, 3>> edgeControlPoints(const TriangleMesh& mesh,
                                                   const MeshTopology& topo,
                                                   std::vector<uint8_t>* gaveUpPatches) {
  const EdgeEnds ends = edgeEnds(mesh, topo);
  std::vector<std::array<Vec3, 3>> out = largeVector<std::array<Vec3, 3>>(mesh.triangleCount());
  std::vector<uint8_t> gaveUpEdges(gaveUpPatches ? topo.edges.size() : 0, 0);
  // Each edge writes only its own sides' slots, so edges are independent and the result does
  // not depend on the thread count.
  parallelForRange(tbb::blocked_range<size_t>(0, topo.edges.size(), 4096), [&](const tbb::
                                                                                   blocked_range<
                                                                                       size_t>&
                                                                                       range) {
    for (size_t e = range.begin(); e != range.end(); ++e) {
      const Edge& edge = topo.edges[e];
      const auto [t0, k0] = edge.sides.front();
      const bool forward = mesh.triangles[t0][k0] == edge.a;
      const auto& side = ends[t0][k0];
      const std::array<EdgeEnd, 2> ab = forward ? side : std::array<EdgeEnd, 2>{side[1], side[0]};
      bool gaveUp = false;
      const Vec3 b = sharedEdgeControlPoint(mesh, edge, ab, gaveUp);
      for (auto [t, k] : edge.sides) out[t][k] = b;
      if (gaveUpPatches) gaveUpEdges[e] = gaveUp;
    }
  });
  if (gaveUpPatches) {
    gaveUpPatches->assign(mesh.triangleCount(), 0);
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k) (*gaveUpPatches)[t] |= gaveUpEdges[topo.edgeOf[t][k]];
  }
  return out;
}

std::array<Vec3, 6> QuadraticPatch::coefficients() const {
  // f = Σ λi² vi + 2 Σ λiλj bij with λ = (1-u-v, u, v), expanded in monomials.
  const Vec3 &b01 = b[0], &b12 = b[1], &b20 = b[2];
  return {v[0],                            // c0
          2.0 * (b20 - v[0]),              // c1 (v)
          2.0 * (b01 - v[0]),              // c2 (u)
          2.0 * (v[0] - b01 - b20 + b12),  // c3 (uv)
          v[0] + v[2] - 2.0 * b20,         // c4 (v²)
          v[0] + v[1] - 2.0 * b01};        // c5 (u²)
}

Vec3 QuadraticPatch::edgePoint(int k, double t) const {
  const Vec3& a = v[k];
  const Vec3& c = v[(k + 1) % 3];
  return (1 - t) * (1 - t) * a + 2 * t * (1 - t) * b[k] + t * t * c;
}

bool edgeControlPointsAreLocal(const TriangleMesh& mesh) {
  return mesh.hasNormals() && !edgeEndsNeedTopology(mesh);
}

std::array<Vec3, 3> localEdgeControlPoints(const TriangleMesh& mesh, size_t t, bool* gaveUp) {
  std::array<Vec3, 3> b;
  bool any = false;
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    bool edgeGaveUp = false;
    b[size_t(k)] = edgeControlPoint(mesh.corner(t, k), mesh.cornerNormal(t, k), mesh.corner(t, l),
                                    mesh.cornerNormal(t, l), &edgeGaveUp);
    any = any || edgeGaveUp;
  }
  if (gaveUp) *gaveUp = any;
  return b;
}

QuadraticPatch quadraticPatch(const TriangleMesh& mesh,
                              const std::vector<std::array<Vec3, 3>>& controlPoints, size_t t) {
  return QuadraticPatch{{mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)},
                        controlPoints[t]};
}

double patchOrientation(const TriangleMesh& mesh, size_t t) {
  const Vec3 ns = mesh.cornerNormal(t, 0) + mesh.cornerNormal(t, 1) + mesh.cornerNormal(t, 2);
  return mesh.faceCross(t).dot(ns) < 0.0 ? -1.0 : 1.0;
}

}  // namespace quadtri
