#include "quadtri/surface/bezier_triangle.h"

namespace quadtri {
namespace {

// Bernstein basis of degree n at barycentric l, B[index] = n!/(i!j!k!) l0^i l1^j l2^k, laid out
// like BezierTriangle::index for n = 4 (rows of constant k, offset(k) = Σ_{m<k} (n + 1 − m)).
template <int N>
std::array<double, (N + 1) * (N + 2) / 2> bernstein(double l0, double l1, double l2) {
  double p0[N + 1], p1[N + 1], p2[N + 1];
  p0[0] = p1[0] = p2[0] = 1.0;
  for (int e = 1; e <= N; ++e) {
    p0[e] = p0[e - 1] * l0;
    p1[e] = p1[e - 1] * l1;
    p2[e] = p2[e - 1] * l2;
  }
  double fact[N + 1];
  fact[0] = 1.0;
  for (int e = 1; e <= N; ++e) fact[e] = fact[e - 1] * e;
  std::array<double, (N + 1) * (N + 2) / 2> out{};
  int at = 0;
  for (int k = 0; k <= N; ++k)
    for (int j = 0; j + k <= N; ++j) {
      const int i = N - j - k;
      out[size_t(at++)] = fact[N] / (fact[i] * fact[j] * fact[k]) * p0[i] * p1[j] * p2[k];
    }
  return out;
}

constexpr int index3(int j, int k) {
  return 4 * k - k * (k - 1) / 2 + j;
}

}  // namespace

bool BezierTriangle::isAffine(double relative) const {
  const Vec3& p0 = at(4, 0, 0);
  const Vec3& p1 = at(0, 4, 0);
  const Vec3& p2 = at(0, 0, 4);
  const Bounds3 box = bounds();
  const double tolerance = relative * (box.hi - box.lo).norm();
  if (!(tolerance >= 0.0)) return false;
  for (int k = 0; k <= kDegree; ++k)
    for (int j = 0; j + k <= kDegree; ++j) {
      const int i = kDegree - j - k;
      const Vec3 linear = (double(i) * p0 + double(j) * p1 + double(k) * p2) / double(kDegree);
      if (!((at(i, j, k) - linear).cwiseAbs().maxCoeff() <= tolerance)) return false;
    }
  return true;
}

Vec3 BezierTriangle::position(double u, double v) const {
  const auto basis = bernstein<4>(1.0 - u - v, u, v);
  Vec3 sum = Vec3::Zero();
  for (int p = 0; p < kPoints; ++p) sum += basis[size_t(p)] * b[size_t(p)];
  return sum;
}

void BezierTriangle::derivatives(double u, double v, Vec3& du, Vec3& dv) const {
  // ∂/∂u = 4 Σ_{i+j+k=3} B³_ijk (b_{i,j+1,k} − b_{i+1,j,k}), ∂/∂v likewise with k + 1.
  const auto basis = bernstein<3>(1.0 - u - v, u, v);
  du = Vec3::Zero();
  dv = Vec3::Zero();
  for (int k = 0; k <= 3; ++k)
    for (int j = 0; j + k <= 3; ++j) {
      const double w = basis[size_t(index3(j, k))];
      const Vec3& base = b[size_t(index(j, k))];  // b_{i+1,j,k}
      du += w * (b[size_t(index(j + 1, k))] - base);
      dv += w * (b[size_t(index(j, k + 1))] - base);
    }
  du *= 4.0;
  dv *= 4.0;
}

Vec3 BezierTriangle::normal(double u, double v) const {
  Vec3 du, dv;
  derivatives(u, v, du, dv);
  return safeNormalized(orientation * du.cross(dv), Vec3::Zero());
}

void BezierTriangle::positionAndNormal(double u, double v, Vec3& p, Vec3& n) const {
  // b(u, v) = Σ_{i+j+k=3} B³_ijk (b_{i+1,j,k} + u (b_{i,j+1,k} − b_{i+1,j,k}) + v (b_{i,j,k+1} −
  // b_{i+1,j,k})): the derivatives' sums (as derivatives()) and one more.
  const auto basis = bernstein<3>(1.0 - u - v, u, v);
  Vec3 a = Vec3::Zero(), du = Vec3::Zero(), dv = Vec3::Zero();
  for (int k = 0; k <= 3; ++k)
    for (int j = 0; j + k <= 3; ++j) {
      const double w = basis[size_t(index3(j, k))];
      const Vec3& base = b[size_t(index(j, k))];
      a += w * base;
      du += w * (b[size_t(index(j + 1, k))] - base);
      dv += w * (b[size_t(index(j, k + 1))] - base);
    }
  p = a + u * du + v * dv;
  n = safeNormalized(orientation * (4.0 * du).cross(4.0 * dv), Vec3::Zero());
}

Bounds3 BezierTriangle::bounds() const {
  Bounds3 box;
  for (const Vec3& p : b) box.extend(p);
  return box;
}

}  // namespace quadtri
