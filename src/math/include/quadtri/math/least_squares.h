// Small dense least squares at fixed size, without Eigen's general (blocked, dynamically sized)
// Householder code, which costs more than the arithmetic at these sizes.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace quadtri {

namespace least_squares_detail {

// Column J's reflection (householderLeastSquares), J a constant so that every loop below has
// fixed bounds and unrolls: the same operations in the same order as a loop over J would do.
template <int J, int R, int C>
inline void reflectColumn(Eigen::Matrix<double, R, C>& A, Eigen::Matrix<double, R, 1>& b,
                          double* diagonal) {
  if constexpr (J < C) {
    double norm2 = 0.0;
    for (int i = J; i < R; ++i) norm2 += A(i, J) * A(i, J);
    const double norm = std::sqrt(norm2);
    if (!(norm > 0.0)) {
      diagonal[J] = 0.0;
    } else {
      // Reflect column J onto alpha e_J, alpha of the sign opposite to A(J, J) (no
      // cancellation): v = A(J.., J) − alpha e_J, H = I − 2 v vᵀ / vᵀv,
      // vᵀv = 2 norm (norm + |A(J, J)|).
      const double alpha = A(J, J) > 0.0 ? -norm : norm;
      A(J, J) -= alpha;
      const double vv = 2.0 * norm * (norm + std::abs(A(J, J) + alpha));
      const double twoOverVv = 2.0 / vv;  // one division per column, not one per column reflected
      for (int k = J + 1; k < C; ++k) {
        double s = 0.0;
        for (int i = J; i < R; ++i) s += A(i, J) * A(i, k);
        const double f = s * twoOverVv;
        for (int i = J; i < R; ++i) A(i, k) -= f * A(i, J);
      }
      double s = 0.0;
      for (int i = J; i < R; ++i) s += A(i, J) * b[i];
      const double f = s * twoOverVv;
      for (int i = J; i < R; ++i) b[i] -= f * A(i, J);
      diagonal[J] = alpha;
    }
    reflectColumn<J + 1>(A, b, diagonal);
  }
}

}  // namespace least_squares_detail

/// The least-squares solution x of A x = b for R ≥ C by Householder QR (unpivoted), in place on
/// copies of A and b. Returns false, leaving x unset, when the columns are not independent
/// enough: the smallest |R_jj| is at most `rankTolerance` times the largest (the caller then
/// needs a rank-revealing method).
template <int R, int C>
bool householderLeastSquares(Eigen::Matrix<double, R, C> A, Eigen::Matrix<double, R, 1> b,
                             Eigen::Matrix<double, C, 1>& x, double rankTolerance) {
  static_assert(R >= C, "an overdetermined or square system");
  double diagonal[C];
  least_squares_detail::reflectColumn<0>(A, b, diagonal);
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
