#include "quadtri/surface/implicit_fit.h"

#include <Eigen/QR>

#include "quadtri/math/least_squares.h"

namespace quadtri {
namespace {

using QuadricRow = Eigen::Matrix<double, 1, 10>;

// Monomials of f_i at p: f_i(p) = row(p)·(A..J).
QuadricRow valueRow(const Vec3& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  QuadricRow r;
  r << x * x, y * y, z * z, x * y, x * z, y * z, x, y, z, 1.0;
  return r;
}

// Directional derivative of the monomials at p along d: ∇f_i(p)·d = row(p, d)·(A..J).
QuadricRow directionalRow(const Vec3& p, const Vec3& d) {
  const double x = p.x(), y = p.y(), z = p.z();
  QuadricRow r;
  r << 2 * x * d.x(), 2 * y * d.y(), 2 * z * d.z(), x * d.y() + y * d.x(), x * d.z() + z * d.x(),
      y * d.z() + z * d.y(), d.x(), d.y(), d.z(), 0.0;
  return r;
}

double largestEdge(const QuadraticPatch& fp) {
  return std::max(
      {(fp.v[1] - fp.v[0]).norm(), (fp.v[2] - fp.v[1]).norm(), (fp.v[0] - fp.v[2]).norm()});
}

// Relative tolerance below which a patch counts as planar or three points as collinear.
constexpr double kFlatTolerance = 1e-9;

// The triangle's plane as a quadric when f_p lies in it, else nullopt.
std::optional<QuadricCoeffs> planarPatchQuadric(const QuadraticPatch& fp) {
  const Vec3 cross = (fp.v[1] - fp.v[0]).cross(fp.v[2] - fp.v[0]);
  const double size = largestEdge(fp);
  if (!(cross.norm() > kFlatTolerance * size * size)) return std::nullopt;
  const Vec3 n = cross.normalized();
  for (const Vec3& b : fp.b)
    if (std::abs(n.dot(b - fp.v[0])) > kFlatTolerance * size) return std::nullopt;
  QuadricCoeffs q{};
  q[6] = n.x();
  q[7] = n.y();
  q[8] = n.z();
  q[9] = -n.dot(fp.v[0]);
  const double sum = q[6] + q[7] + q[8] + q[9];
  const double norm = 1.0 + std::abs(q[9]);
  // Eq. 4.13 where it can hold; a unit normal where the coefficients sum to ~0.
  const double scale = std::abs(sum) > 1e-6 * norm ? 1.0 / sum : 1.0;
  for (double& c : q) c *= scale;
  return q;
}

}  // namespace

QuadricCoeffs fitThesisQuadric(const QuadraticPatch& fp) {
  if (auto plane = planarPatchQuadric(fp)) return *plane;
  // Fixed sizes keep the solve free of heap allocation (conversion of 1M triangles is timed).
  Eigen::Matrix<double, 13, 10> m;
  Eigen::Matrix<double, 13, 1> rhs = Eigen::Matrix<double, 13, 1>::Zero();
  const double corners[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  int row = 0;
  for (const auto& c : corners) m.row(row++) = valueRow(fp.position(c[0], c[1]));  // eq. 4.10
  for (const auto& c : corners) {                                                  // eq. 4.11
    const Vec3 p = fp.position(c[0], c[1]);
    Vec3 du, dv;
    fp.derivatives(c[0], c[1], du, dv);
    m.row(row++) = directionalRow(p, du);
    m.row(row++) = directionalRow(p, dv);
  }
  {  // eq. 4.12
    const double third = 1.0 / 3.0;
    const Vec3 p = fp.position(third, third);
    Vec3 du, dv;
    fp.derivatives(third, third, du, dv);
    m.row(row++) = valueRow(p);
    m.row(row++) = directionalRow(p, du);
    m.row(row++) = directionalRow(p, dv);
  }
  m.row(row).setOnes();  // eq. 4.13
  rhs[row] = 1.0;
  // Least squares by unpivoted Householder QR where the rows have full rank (the common case,
  // and the cheapest), else the minimum-norm solution of a complete orthogonal decomposition
  // (what the SVD's pseudo-inverse gives).
  Eigen::Matrix<double, 10, 1> x;
  if (!householderLeastSquares(m, rhs, x, 1e-10))
    x = Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix<double, 13, 10>>(m).solve(rhs);
  QuadricCoeffs q{};
  for (int i = 0; i < 10; ++i) q[i] = std::isfinite(x[i]) ? x[i] : 0.0;
  return q;
}

void setThesisClipPlanes(const QuadraticPatch& fp, QuadricPatch& patch) {
  struct PlaneDef {
    double uv[3][2];     // the three points of f_p, as printed (with "0, 0, 5" read as ½)
    int chordA, chordB;  // corners of the edge the plane cuts (-1: none, the corner plane)
  };
  static constexpr PlaneDef kDefs[4] = {{{{0, 0}, {1, 0}, {0, 1}}, -1, -1},
                                        {{{0, 0}, {0.5, 0}, {1, 0}}, 0, 1},
                                        {{{0, 0}, {0, 0.5}, {0, 1}}, 0, 2},
                                        {{{1, 0}, {0.5, 0.5}, {1, 1}}, 1, 2}};
  const double third = 1.0 / 3.0;
  const Vec3 barycentre = fp.position(third, third);
  const double size = largestEdge(fp);
  const Vec3 faceCross = (fp.v[1] - fp.v[0]).cross(fp.v[2] - fp.v[0]);
  patch.planeCount = 0;
  if (!(size > 0.0)) return;
  for (const PlaneDef& def : kDefs) {
    const Vec3 p1 = fp.position(def.uv[0][0], def.uv[0][1]);
    const Vec3 p2 = fp.position(def.uv[1][0], def.uv[1][1]);
    const Vec3 p3 = fp.position(def.uv[2][0], def.uv[2][1]);
    Vec3 n = (p2 - p1).cross(p3 - p1);
    Vec3 anchor = p1;
    const double nLen = n.norm();
    const bool collinear = !(nLen > kFlatTolerance * size * size);
    const bool throughBarycentre =
        !collinear && std::abs(n.dot(barycentre - p1)) <= kFlatTolerance * size * nLen;
    if (collinear || throughBarycentre) {
      if (def.chordA < 0) continue;  // the corner plane of a planar patch: it holds the patch
      // Fallback: the plane through the edge's chord that contains the triangle's normal.
      anchor = fp.v[def.chordA];
      n = (fp.v[def.chordB] - anchor).cross(faceCross);
      if (!(n.norm() > kFlatTolerance * size * faceCross.norm()) || !(faceCross.norm() > 0.0))
        continue;
    }
    n.normalize();
    // The thesis flips n towards the barycentre and then prints the test n·(p1 - p) >= 0, which
    // keeps the side away from it; its intent (figure 4.8: the normals point at the kept piece)
    // is the barycentre's side, n·(p - p1) >= 0.
    if (n.dot(barycentre - anchor) < 0.0) n = -n;
    if (!allFinite(n)) continue;
    patch.planes[patch.planeCount++] = Vec4(n.x(), n.y(), n.z(), -n.dot(anchor));
  }
}

int lineQuadricRoots(double a, double b, double c, double roots[2]) {
  int count = 0;
  if (a == 0.0) {
    if (b != 0.0) roots[count++] = -c / b;
    return count;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return 0;
  // h = -(b + sign(b)√disc)/2 avoids cancellation; the roots are h/a and c/h.
  const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  if (h != 0.0) {
    roots[count++] = h / a;
    roots[count++] = c / h;
  }
  return count;
}

std::optional<double> nearestRayRoot(const QuadricCoeffs& q, const Vec3& p, const Vec3& d,
                                     double maxDistance) {
  const double a = q[0] * d.x() * d.x() + q[1] * d.y() * d.y() + q[2] * d.z() * d.z() +
                   q[3] * d.x() * d.y() + q[4] * d.x() * d.z() + q[5] * d.y() * d.z();
  const double b = quadricGradient(q, p).dot(d);
  const double c = evalQuadric(q, p);
  if (c == 0.0) return 0.0;
  double roots[2];
  const int count = lineQuadricRoots(a, b, c, roots);
  const double dLen = d.norm();
  std::optional<double> best;
  for (int i = 0; i < count; ++i) {
    const double s = roots[i];
    if (!std::isfinite(s) || std::abs(s) * dLen > maxDistance) continue;
    if (!best || std::abs(s) < std::abs(*best)) best = s;
  }
  return best;
}

}  // namespace quadtri
