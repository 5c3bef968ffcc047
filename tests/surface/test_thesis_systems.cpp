// The closed-form edge control points solve the thesis' own linear systems: the 18×18 system of
// §4.2 (eq. 4.7-4.9) and the 27×27 system of §4.1 (eq. 4.3-4.5), assembled as printed and
// solved by dense LU.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <random>

#include "quadtri/math/least_squares.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/edges_model.h"
#include "surface_fixtures.h"

namespace quadtri {
namespace {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

using test::edgePlaneNormal;

// The fixed-size Householder least squares of the implicit fit (13 rows, 10 unknowns) against
// Eigen's HouseholderQR on random systems, and its refusal of a rank-deficient one.
TEST(ThesisSystems, FixedSizeHouseholderMatchesEigensQr) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix<double, 13, 10> A;
    Eigen::Matrix<double, 13, 1> b;
    for (int i = 0; i < 13; ++i) {
      for (int j = 0; j < 10; ++j) A(i, j) = g(rng) * std::pow(10.0, trial % 7 - 3);
      b[i] = g(rng);
    }
    if (trial % 4 == 0) A(3, 3) = 0.0;  // a zero on the diagonal
    const Eigen::Matrix<double, 10, 1> reference = A.householderQr().solve(b);
    Eigen::Matrix<double, 10, 1> x;
    ASSERT_TRUE(householderLeastSquares(A, b, x, 1e-10)) << trial;
    EXPECT_LE((x - reference).norm(), 1e-10 * reference.norm()) << trial;
  }
  Eigen::Matrix<double, 13, 10> A = Eigen::Matrix<double, 13, 10>::Random();
  A.col(7) = 2.0 * A.col(2);
  Eigen::Matrix<double, 10, 1> x;
  EXPECT_FALSE(householderLeastSquares(A, Eigen::Matrix<double, 13, 1>::Ones().eval(), x, 1e-10));
}

// The edge control points' damped solve against the SVD formula Σ σ/(σ² + μ²) (u·r) v, on
// random systems (equal to 1e-9 relative) and rank-deficient ones (parallel tangent planes, a
// missing edge plane: as small a damped residual).
TEST(ThesisSystems, TheDampedSolveIsTheSvdsTikhonovSolution) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  const auto unit = [&] { return Vec3(g(rng), g(rng), g(rng)).normalized(); };
  const double mu = 1e-7;
  for (int trial = 0; trial < 300; ++trial) {
    Mat3 M;
    const Vec3 n0 = unit();
    const Vec3 n1 = trial % 3 == 1 ? n0 : unit();            // parallel planes
    const Vec3 np = trial % 5 == 2 ? Vec3::Zero() : unit();  // no edge plane
    M.row(0) = n0.transpose();
    M.row(1) = n1.transpose();
    M.row(2) = np.transpose();
    const Vec3 r(g(rng), g(rng), trial % 5 == 2 ? 0.0 : g(rng));
    Eigen::JacobiSVD<Mat3> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Vec3 reference = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const double s = svd.singularValues()[k];
      reference += (s / (s * s + mu * mu)) * svd.matrixU().col(k).dot(r) * svd.matrixV().col(k);
    }
    const Vec3 x = dampedLeastSquares(M, r, mu);
    const auto objective = [&](const Vec3& d) {
      return (M * d - r).squaredNorm() + mu * mu * d.squaredNorm();
    };
    // Where M is singular the answer along its null space is σ/(σ² + μ²) for a σ that is
    // round-off (1e-16/μ² = 1e-2 of |r|) in either method: compare what both minimise there.
    const bool singular = trial % 3 == 1 || trial % 5 == 2;
    if (!singular) {
      EXPECT_LE((x - reference).norm(), 1e-9 * std::max(1.0, reference.norm()))
          << trial << ": " << x.transpose() << " against " << reference.transpose();
    }
    EXPECT_LE(objective(x), objective(reference) * (1.0 + 1e-9) + 1e-24) << trial;
  }
  // Entries whose squares underflow (a column of 0 and 1e-170) still solve, without 0/0.
  Mat3 tiny;
  tiny << 0, 1, 0,   //
      1e-170, 0, 1,  //
      0, 0, 0;
  const Vec3 x = dampedLeastSquares(tiny, Vec3(0.5, -0.25, 0), mu);
  EXPECT_TRUE(x.allFinite()) << x.transpose();
  EXPECT_NEAR(x.y(), 0.5, 1e-12);
  EXPECT_NEAR(x.z(), -0.25, 1e-12);
}

// Eq. 4.6: f(u,v) = Σ_k φ_k(u,v) c_k with φ = (1, v, u, uv, v², u²) for c0..c5.
std::array<double, 6> monomials(double u, double v) {
  return {1, v, u, u * v, v * v, u * u};
}
std::array<double, 6> monomialsDu(double u, double v) {
  return {0, 0, 1, v, 0, 2 * u};
}
std::array<double, 6> monomialsDv(double u, double v) {
  return {0, 1, 0, u, 2 * v, 0};
}

// The 18×18 system of eq. 4.7-4.9; unknowns x[3k + d] = component d of c_k.
std::array<Vec3, 6> solveThesis18(const test::TriangleData& d) {
  Matrix A = Matrix::Zero(18, 18);
  Vector b = Vector::Zero(18);
  int row = 0;
  const Vec2 corners[3] = {{0, 0}, {1, 0}, {0, 1}};
  for (int c = 0; c < 3; ++c) {  // eq. 4.7: f(corner) = v_c
    const auto phi = monomials(corners[c].x(), corners[c].y());
    for (int dim = 0; dim < 3; ++dim, ++row) {
      for (int k = 0; k < 6; ++k) A(row, 3 * k + dim) = phi[k];
      b(row) = d.v[c][dim];
    }
  }
  for (int c = 0; c < 3; ++c) {  // eq. 4.8: f_u·n_c = 0 and f_v·n_c = 0 at each corner
    for (const auto& dphi : {monomialsDu(corners[c].x(), corners[c].y()),
                             monomialsDv(corners[c].x(), corners[c].y())}) {
      for (int k = 0; k < 6; ++k)
        for (int dim = 0; dim < 3; ++dim) A(row, 3 * k + dim) = dphi[k] * d.n[c][dim];
      ++row;
    }
  }
  // eq. 4.9: (i, j) = (0,1), (0,2), (1,2) at (½,0), (0,½), (½,½).
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  const Vec2 mids[3] = {{0.5, 0}, {0, 0.5}, {0.5, 0.5}};
  for (int p = 0; p < 3; ++p, ++row) {
    const int i = pairs[p][0], j = pairs[p][1];
    const Vec3 np = edgePlaneNormal(d.v[i], d.n[i], d.v[j], d.n[j]);
    const auto phi = monomials(mids[p].x(), mids[p].y());
    for (int k = 0; k < 6; ++k)
      for (int dim = 0; dim < 3; ++dim) A(row, 3 * k + dim) = phi[k] * np[dim];
    b(row) = d.v[i].dot(np);
  }
  const Vector x = A.fullPivLu().solve(b);
  std::array<Vec3, 6> c;
  for (int k = 0; k < 6; ++k) c[k] = x.segment<3>(3 * k);
  return c;
}

// The 27×27 system of eq. 4.3-4.5; curve q (f_u, f_v, f_w) has unknowns x[9q + 3m + d] =
// component d of its c_m in f(s) = s² c2 + s c1 + c0.
std::array<std::array<Vec3, 3>, 3> solveThesis27(const test::TriangleData& d) {
  Matrix A = Matrix::Zero(27, 27);
  Vector b = Vector::Zero(27);
  // eq. 4.3: f_u from v0 to v1, f_v from v2 to v0, f_w from v1 to v2.
  const int ends[3][2] = {{0, 1}, {2, 0}, {1, 2}};
  int row = 0;
  for (int q = 0; q < 3; ++q) {
    const int start = ends[q][0], end = ends[q][1];
    for (int dim = 0; dim < 3; ++dim) {  // f(0) = c0 = v_start; f(1) = c0 + c1 + c2 = v_end
      A(row, 9 * q + dim) = 1;
      b(row++) = d.v[start][dim];
      for (int m = 0; m < 3; ++m) A(row, 9 * q + 3 * m + dim) = 1;
      b(row++) = d.v[end][dim];
    }
    // eq. 4.4: f'(0)·n_start = 0 and f'(1)·n_end = 0, with f'(s) = c1 + 2s c2.
    for (int dim = 0; dim < 3; ++dim) A(row, 9 * q + 3 + dim) = d.n[start][dim];
    ++row;
    for (int dim = 0; dim < 3; ++dim) {
      A(row, 9 * q + 3 + dim) = d.n[end][dim];
      A(row, 9 * q + 6 + dim) = 2 * d.n[end][dim];
    }
    ++row;
    // eq. 4.5: f(½)·np = v_i·np with f(½) = c0 + c1/2 + c2/4.
    const Vec3 np = edgePlaneNormal(d.v[start], d.n[start], d.v[end], d.n[end]);
    const double w[3] = {1.0, 0.5, 0.25};
    for (int m = 0; m < 3; ++m)
      for (int dim = 0; dim < 3; ++dim) A(row, 9 * q + 3 * m + dim) = w[m] * np[dim];
    b(row++) = d.v[start].dot(np);
  }
  const Vector x = A.fullPivLu().solve(b);
  std::array<std::array<Vec3, 3>, 3> curves;
  for (int q = 0; q < 3; ++q)
    for (int m = 0; m < 3; ++m) curves[q][m] = x.segment<3>(9 * q + 3 * m);
  return curves;
}

QuadraticPatch closedForm(const test::TriangleData& d) {
  QuadraticPatch p;
  p.v = d.v;
  for (int k = 0; k < 3; ++k)
    p.b[k] = edgeControlPoint(d.v[k], d.n[k], d.v[(k + 1) % 3], d.n[(k + 1) % 3]);
  return p;
}

// Random non-degenerate triangles: normals within 60° of the face normal, edge systems whose
// smallest singular value keeps the damping below 1e-13 relative, and exact control points
// within the closed form's bound (otherwise the closed form clamps them on purpose).
std::vector<test::TriangleData> wellPosedTriangles(int count) {
  std::mt19937_64 rng(20201);
  std::vector<test::TriangleData> out;
  while (int(out.size()) < count) {
    const test::TriangleData d = test::randomTriangle(rng);
    if (test::edgeSystemSigmaMin(d) > 0.3 && test::edgeUnclamped(d, 0) &&
        test::edgeUnclamped(d, 1) && test::edgeUnclamped(d, 2))
      out.push_back(d);
  }
  return out;
}

TEST(ThesisSystems, ClosedFormSolvesTheParametric18x18System) {
  for (const test::TriangleData& d : wellPosedTriangles(300)) {
    const std::array<Vec3, 6> lu = solveThesis18(d);
    const std::array<Vec3, 6> closed = closedForm(d).coefficients();
    double scale = 0.0;
    for (const Vec3& c : lu) scale = std::max(scale, c.norm());
    for (int k = 0; k < 6; ++k) EXPECT_LE((lu[k] - closed[k]).norm(), 1e-12 * scale) << "c" << k;
  }
}

TEST(ThesisSystems, ClosedFormSolvesTheEdgeCurve27x27System) {
  for (const test::TriangleData& d : wellPosedTriangles(300)) {
    const auto lu = solveThesis27(d);
    const std::array<EdgeCurve, 3> closed = thesisEdgeCurves(closedForm(d));
    for (int q = 0; q < 3; ++q) {
      const std::array<Vec3, 3> c = closed[q].coefficients();
      const double scale = std::max({lu[q][0].norm(), lu[q][1].norm(), lu[q][2].norm()});
      for (int m = 0; m < 3; ++m)
        EXPECT_LE((lu[q][m] - c[m]).norm(), 1e-12 * scale) << "curve " << q << " c" << m;
    }
  }
}

TEST(ThesisSystems, IcosahedronFaceAgreesToRoundoff) {
  // docs/DESIGN.md measured 1e-15 between the 18×18 solution and the closed form on this face.
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  test::TriangleData d;
  d.v = {Vec3(0, 1, phi).normalized(), Vec3(-1, phi, 0).normalized(), Vec3(1, phi, 0).normalized()};
  for (int k = 0; k < 3; ++k) d.n[k] = d.v[k];
  const std::array<Vec3, 6> lu = solveThesis18(d);
  const std::array<Vec3, 6> closed = closedForm(d).coefficients();
  for (int k = 0; k < 6; ++k) EXPECT_LE((lu[k] - closed[k]).norm(), 1e-14) << "c" << k;
}

}  // namespace
}  // namespace quadtri
