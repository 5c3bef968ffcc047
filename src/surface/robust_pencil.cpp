#include "quadtri/surface/robust_pencil.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

#include "quadtri/math/parallel.h"

namespace quadtri {
namespace {

// Weight of keeping each patch's arc-midpoint member against making neighbours agree, for
// data from a quadric; it grows with the corner-normal error (1 per kCompatibleDeg) so that
// fits of generic data stay where they are: there the agreement cannot be met (their conics
// differ through the corner normals), and chasing it with a large multiple of L² brings the
// quadric's second sheet next to the patch.
constexpr double kArcWeight = 1e-2;
constexpr double kCompatibleDeg = 1e-4;

// Σ a_i b_i in fixed blocks summed in order: the same bits for any thread count.
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  constexpr size_t kBlock = 16384;
  const size_t blocks = (a.size() + kBlock - 1) / kBlock;
  std::vector<double> partial(blocks, 0.0);
  parallelFor(size_t(0), blocks, [&](size_t i) {
    double sum = 0.0;
    for (size_t j = i * kBlock; j < std::min(a.size(), (i + 1) * kBlock); ++j) sum += a[j] * b[j];
    partial[i] = sum;
  });
  double sum = 0.0;
  for (double p : partial) sum += p;
  return sum;
}

// Iterations and relative residual of the conjugate-gradient solve (a 1,000,000-triangle torus
// takes about 300); a system that needs more goes to the direct solver.
constexpr int kMaxIterations = 2000;
constexpr double kResidual = 1e-14;

// Jacobi-preconditioned conjugate gradients for the symmetric positive definite N μ = rhs;
// false when it does not reach kResidual within kMaxIterations.
template <typename Multiply>
bool conjugateGradients(const Multiply& multiply, const std::vector<double>& rhs,
                        const std::vector<double>& diagonal, std::vector<double>& x) {
  const size_t n = rhs.size();
  x.assign(n, 0.0);
  const double bb = dot(rhs, rhs);
  if (!std::isfinite(bb)) return false;
  if (bb == 0.0) return true;
  for (double d : diagonal)
    if (!(d > 0.0) || !std::isfinite(d)) return false;
  std::vector<double> r = rhs, z(n), p(n), q(n);
  for (size_t i = 0; i < n; ++i) z[i] = r[i] / diagonal[i];
  p = z;
  double rz = dot(r, z);
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    multiply(p, q);
    const double pq = dot(p, q);
    if (!(pq > 0.0) || !std::isfinite(pq)) return false;
    const double alpha = rz / pq;
    parallelFor(size_t(0), n, [&](size_t i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      z[i] = r[i] / diagonal[i];
    });
    if (dot(r, r) <= kResidual * kResidual * bb) return true;
    const double rzNext = dot(r, z);
    const double beta = rzNext / rz;
    rz = rzNext;
    parallelFor(size_t(0), n, [&](size_t i) { p[i] = z[i] + beta * p[i]; });
  }
  return false;
}

// The same system by sparse LDLᵀ; empty when that fails.
std::vector<double> directSolve(const MeshTopology& topo,
                                const std::vector<std::array<double, 3>>& change,
                                const std::vector<std::array<double, 3>>& distance,
                                const std::vector<double>& held, size_t count) {
  const Eigen::Index n = Eigen::Index(count);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (size_t t = 0; t < count; ++t)
    entries.emplace_back(Eigen::Index(t), Eigen::Index(t), held[t]);
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    const Edge& edge = topo.edges[e];
    if (edge.sides.size() != 2) continue;
    const auto [a, ka] = edge.sides[0];
    const auto [b, kb] = edge.sides[1];
    const double ca = change[a][ka], cb = -change[b][kb], r = distance[b][kb] - distance[a][ka];
    entries.emplace_back(a, a, ca * ca);
    entries.emplace_back(b, b, cb * cb);
    entries.emplace_back(a, b, ca * cb);
    entries.emplace_back(b, a, ca * cb);
    rhs[a] += ca * r;
    rhs[b] += cb * r;
  }
  Eigen::SparseMatrix<double> normal(n, n);
  normal.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success) return {};
  const Eigen::VectorXd mu = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !mu.allFinite()) return {};
  return std::vector<double>(mu.data(), mu.data() + n);
}

}  // namespace

// Moves every patch along its pencil, q_t + μ_t p_t (corners and their normals do not change),
// so that neighbours pass at the same signed distance from each shared edge's arc midpoint:
// sparse least squares over all patches, rows s_a + c_a μ_a = s_b + c_b μ_b per interior edge
// (s the oriented distance q/|∇q| of the arc midpoint, c its change per unit μ) plus
// kArcWeight·|c|·μ_t per patch. Data sampled from a sphere give s = 0 everywhere and μ = 0;
// for other quadrics it keeps neighbouring multiples of L² alike, so a − κb splits into a
// real plane pair through each edge (see alignWithCrossing).
void agreeAcrossEdges(const TriangleMesh& mesh, const MeshTopology& topo,
                      const std::vector<Vec3>& arcMidpoints,
                      const std::vector<std::array<Vec3, 3>>& controlPoints,
                      const std::vector<QuadricCoeffs>& pencils,
                      const std::vector<double>& cornerNormalErrorDeg,
                      std::vector<QuadricPatch>& patches) {
  const size_t count = patches.size();
  // distance[t][k], change[t][k]: s and c of patch t at its edge k's arc midpoint; held[t]:
  // the regulariser's diagonal entry. Each triangle writes its own slots only.
  std::vector<std::array<double, 3>> distance(count), change(count);
  std::vector<double> held(count);
  // The regulariser measures μ by how far it moves the patch anywhere (sampled on f_p), not
  // only at the arc midpoints: where those lie near the triangle's plane (inflections,
  // saddles) a large μ would leave them in place and bend the rest of the patch.
  static constexpr double kSamples[7][2] = {{1. / 3, 1. / 3}, {0.5, 0},         {0.5, 0.5},
                                            {0, 0.5},         {1. / 6, 1. / 6}, {2. / 3, 1. / 6},
                                            {1. / 6, 2. / 3}};
  parallelFor(size_t(0), count, [&](size_t t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& m = arcMidpoints[topo.edgeOf[t][k]];
      const double g = quadricGradient(patches[t].q, m).norm();
      const double o = patches[t].orientation / (g > 0.0 ? g : 1.0);
      distance[t][k] = o * evalQuadric(patches[t].q, m);
      change[t][k] = o * evalQuadric(pencils[t], m);
    }
    const QuadraticPatch fp = quadraticPatch(mesh, controlPoints, t);
    double effect = 0.0;
    for (const auto& uv : kSamples) {
      const Vec3 x = fp.position(uv[0], uv[1]);
      const double g = quadricGradient(patches[t].q, x).norm();
      effect = std::max(effect, std::abs(evalQuadric(pencils[t], x)) / (g > 0.0 ? g : 1.0));
    }
    for (int k = 0; k < 3; ++k) effect = std::max(effect, std::abs(change[t][k]));
    // Flat patches (L² vanishes on them): no row sees μ, so hold it at 0 explicitly.
    const double size = (mesh.corner(t, 1) - mesh.corner(t, 0)).norm() +
                        (mesh.corner(t, 2) - mesh.corner(t, 1)).norm();
    effect = std::max(effect, 1e-6 * size);
    const double weight = std::max(kArcWeight, cornerNormalErrorDeg[t] / kCompatibleDeg);
    held[t] = weight * weight * effect * effect;
  });
  // The normal equations N μ = rhs: N = diag(held) + Σ over interior edges of c cᵀ with c the
  // edge's row (c_a at a, −c_b at b), rhs = Σ c r. Products with N and rhs are formed per
  // triangle from its own edges (no matrix), so they do not depend on the thread count.
  const auto rowOf = [&](size_t e, double& ca, double& cb, double& r) {
    const Edge& edge = topo.edges[e];
    const auto [a, ka] = edge.sides[0];
    const auto [b, kb] = edge.sides[1];
    ca = change[a][ka];
    cb = -change[b][kb];
    r = distance[b][kb] - distance[a][ka];
  };
  // Per triangle: N's diagonal, rhs, and its off-diagonal entries (one per interior edge: the
  // neighbour across it and c_a c_b; zero for an edge whose two sides are both this triangle's,
  // whose cross terms go to the diagonal).
  std::vector<double> rhs(count, 0.0), diagonal(count, 0.0);
  std::vector<std::array<double, 3>> offDiagonal(count);
  std::vector<std::array<uint32_t, 3>> neighbour(count);
  parallelFor(size_t(0), count, [&](size_t t) {
    double b = 0.0, d = held[t];
    for (int k = 0; k < 3; ++k) {
      offDiagonal[t][k] = 0.0;
      neighbour[t][k] = uint32_t(t);
      const Edge& edge = topo.edges[topo.edgeOf[t][k]];
      if (edge.sides.size() != 2) continue;
      double ca, cb, r;
      rowOf(topo.edgeOf[t][k], ca, cb, r);
      const bool first = edge.sides[0] == EdgeSide(uint32_t(t), uint8_t(k));
      const double c = first ? ca : cb;
      b += c * r;
      d += c * c;
      if (edge.sides[0].first == edge.sides[1].first) {
        d += ca * cb;
      } else {
        offDiagonal[t][k] = ca * cb;
        neighbour[t][k] = first ? edge.sides[1].first : edge.sides[0].first;
      }
    }
    rhs[t] = b;
    diagonal[t] = d;
  });
  // y = N x, row by row.
  const auto multiply = [&](const std::vector<double>& x, std::vector<double>& y) {
    parallelFor(size_t(0), count, [&](size_t t) {
      double sum = diagonal[t] * x[t];
      for (int k = 0; k < 3; ++k) sum += offDiagonal[t][k] * x[neighbour[t][k]];
      y[t] = sum;
    });
  };
  std::vector<double> mu;
  if (!conjugateGradients(multiply, rhs, diagonal, mu))
    mu = directSolve(topo, change, distance, held, count);
  if (mu.empty()) return;
  parallelFor(size_t(0), count, [&](size_t t) {
    QuadricCoeffs& q = patches[t].q;
    double norm2 = 0.0;
    for (int i = 0; i < 10; ++i) {
      q[i] += mu[t] * pencils[t][i];
      norm2 += q[i] * q[i];
    }
    for (double& c : q) c /= std::sqrt(norm2);
  });
}

// Where the fitted member leaves part of the triangle uncovered (some line along the face
// normal n through f_p misses it, or meets it facing away), replaces it by the member of the
// pencil whose quadratic form vanishes along n: a graph over the triangle's plane, which every
// such line meets exactly once. Only fits of normals that no quadric comes near need this
// (coarse, strongly curved or inconsistent data, as on the teapot); it keeps (1) and (2).
void coverTriangle(const QuadraticPatch& parametric, const Vec3& n, const QuadricCoeffs& pencil,
                   QuadricCoeffs& q) {
  const auto alongNormal = [&n](const QuadricCoeffs& c) {
    return c[0] * n.x() * n.x() + c[1] * n.y() * n.y() + c[2] * n.z() * n.z() +
           c[3] * n.x() * n.y() + c[4] * n.x() * n.z() + c[5] * n.y() * n.z();
  };
  constexpr int kSteps = 6;
  bool covered = true;
  for (int j = 0; j <= kSteps && covered; ++j)
    for (int i = 0; i + j <= kSteps && covered; ++i) {
      const Vec3 x = parametric.position(double(i) / kSteps, double(j) / kSteps);
      const double a = alongNormal(q), b = quadricGradient(q, x).dot(n), c = evalQuadric(q, x);
      const double disc = b * b - 4.0 * a * c;
      if (disc < 0.0) {
        covered = false;
        break;
      }
      // The root nearest to f_p and the orientation of the surface there.
      const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      double s = std::abs(a) > 1e-14 * std::abs(b) ? h / a : 0.0;
      if (h != 0.0 && std::abs(c / h) < std::abs(s)) s = c / h;
      covered = quadricGradient(q, x + s * n).dot(n) > 0.0;
    }
  const double ap = alongNormal(pencil);
  if (covered || !(std::abs(ap) > 0.0)) return;
  const double lambda = -alongNormal(q) / ap;
  double norm2 = 0.0;
  for (int i = 0; i < 10; ++i) {
    q[i] += lambda * pencil[i];
    norm2 += q[i] * q[i];
  }
  for (double& c : q) c /= std::sqrt(norm2);
}

// Replaces the edge plane by a plane through the chord that contains the curve where the two
// neighbours' quadrics a and b meet, so both patches end on the same curve. Both contain the
// chord's endpoints with (nearly) the same tangent planes, so a − κb (κ matching their
// gradients at the chord's midpoint c) vanishes to second order at c; in the plane through c
// perpendicular to the chord its zero set is a line pair through c, and the separator is the
// line closer to the edge plane's direction d. For data from any quadric the fits are that
// quadric plus multiples of L_A² and L_B², a − b is exactly a plane pair through the edge, and
// the neighbours meet exactly on the separator; otherwise they meet on it to second order.
void alignWithCrossing(const QuadricCoeffs& a, const QuadricCoeffs& b, const Vec3& va,
                       const Vec3& vb, Vec4& plane, Vec3& direction) {
  const Vec3 c = 0.5 * (va + vb);
  const Vec3 ga = quadricGradient(a, c), gb = quadricGradient(b, c);
  if (!(gb.squaredNorm() > 0.0)) return;
  const double kappa = ga.dot(gb) / gb.squaredNorm();
  const Mat3 ma = quadraticPart(a);
  const Mat3 md = ma - kappa * quadraticPart(b);
  // The same quadric on both sides (sphere data), or two planes (a crease between flat
  // faces): any plane through the edge is exact; keep P.
  const double len = (vb - va).norm();
  if (!(md.norm() > 1e-9 * ma.norm()) || !(md.norm() * len > 1e-9 * ga.norm())) return;
  const Vec3 ehat = (vb - va) / len;
  const Vec3 d = direction, w = ehat.cross(d);
  const double a20 = d.dot(md * d), a11 = 2.0 * d.dot(md * w), a02 = w.dot(md * w);
  const double disc = a11 * a11 - 4.0 * a02 * a20;
  if (disc < 0.0) return;  // a − κb is definite there: the quadrics touch only along the chord
  // The root of a02 t² + a11 t + a20 = 0 of least |t| (stable form); direction d + t w.
  const double den = a11 + std::copysign(std::sqrt(disc), a11);
  const double t = den != 0.0 ? -2.0 * a20 / den : 0.0;
  if (!std::isfinite(t)) return;
  Vec3 normal = ehat.cross(d + t * w).normalized();
  if (normal.dot(plane.head<3>()) < 0.0) normal = -normal;
  // Tilting the separator far from the edge plane would reorder the wedges around a vertex.
  if (normal.dot(plane.head<3>()) < std::cos(kPi / 6)) return;
  plane << normal, -normal.dot(va);
  const Vec3 up = direction;
  direction = normal.cross(ehat);
  if (direction.dot(up) < 0.0) direction = -direction;
}

}  // namespace quadtri
