// Small dense least squares at fixed size, without Eigen's general (blocked, dynamically sized)
// Householder code, which costs more than the arithmetic at these sizes.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace quadtri {

/// The least-squares solution x of A x = b for R ≥ C by Householder QR (unpivoted), in place on
/// copies of A and b. Returns false, leaving x unset, when the columns are not independent
/// enough: the smallest |R_jj| is at most `rankTolerance` times the largest (the caller then
/// needs a rank-revealing method).
template <int R, int C>
bool householderLeastSquares(Eigen::Matrix<double, R, C> A, Eigen::Matrix<double, R, 1> b,
                             Eigen::Matrix<double, C, 1>& x, double rankTolerance) {
  static_assert(R >= C, "an overdetermined or square system");
  double diagonal[C];
  for (int j = 0; j < C; ++j) {
    double norm2 = 0.0;
    for (int i = j; i < R; ++i) norm2 += A(i, j) * A(i, j);
    const double norm = std::sqrt(norm2);
    if (!(norm > 0.0)) {
      diagonal[j] = 0.0;
      continue;
    }
    // Reflect column j onto alpha e_j, alpha of the sign opposite to A(j, j) (no cancellation):
    // v = A(j.., j) − alpha e_j, H = I − 2 v vᵀ / vᵀv, vᵀv = 2 norm (norm + |A(j, j)|).
    const double alpha = A(j, j) > 0.0 ? -norm : norm;
    A(j, j) -= alpha;
    const double vv = 2.0 * norm * (norm + std::abs(A(j, j) + alpha));
    const double twoOverVv = 2.0 / vv;  // one division per column, not one per column it reflects
    for (int k = j + 1; k < C; ++k) {
      double s = 0.0;
      for (int i = j; i < R; ++i) s += A(i, j) * A(i, k);
      const double f = s * twoOverVv;
      for (int i = j; i < R; ++i) A(i, k) -= f * A(i, j);
    }
    double s = 0.0;
    for (int i = j; i < R; ++i) s += A(i, j) * b[i];
    const double f = s * twoOverVv;
    for (int i = j; i < R; ++i) b[i] -= f * A(i, j);
    diagonal[j] = alpha;
  }
  double largest = 0.0, smallest = INFINITY;
  for (double d : diagonal) {
    largest = std::max(largest, std::abs(d));
    smallest = std::min(smallest, std::abs(d));
  }
  if (!(smallest > rankTolerance * largest)) return false;
  for (int j = C - 1; j >= 0; --j) {
    double sum = b[j];
    for (int k = j + 1; k < C; ++k) sum -= A(j, k) * x[k];
    x[j] = sum / diagonal[j];
  }
  return true;
}

}  // namespace quadtri
