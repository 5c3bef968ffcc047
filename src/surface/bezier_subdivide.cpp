// Subdividing the degree-4 nets of Bézier pieces (bezier_net.h: bisect, child, regionNet) and
// the pieces' halves and quarters (bezier_intersect.h: bisectBezierTriangle,
// subdivideBezierTriangle), by de Casteljau steps. Shared by the subdivision search
// (bezier_intersect.cpp) and the region budget (bezier_regions.cpp).
#include <algorithm>

#include "bezier_net.h"
#include "quadtri/surface/bezier_intersect.h"

namespace quadtri {

using namespace bezier_detail;

namespace {

// The corners of the midpoint sub-triangles: a parent corner or the midpoint of an edge.
enum Corner { kE0, kE1, kE2, kM01, kM02, kM12 };

inline P3 mid(const P3& a, const P3& b) {
  return {0.5 * (a.x + b.x), 0.5 * (a.y + b.y), 0.5 * (a.z + b.z)};
}

// casteljauStep at a corner or edge midpoint: a shift or an average (exact and symmetric, so
// the points of a shared edge come out the same from either side).
template <Corner S>
inline void cornerStep(const P3* in, int n, P3* out) {
  for (int k = 0; k < n; ++k)
    for (int j = 0; j + k < n; ++j) {
      const P3& a = in[netIndex(n, j, k)];
      const P3& b = in[netIndex(n, j + 1, k)];
      const P3& c = in[netIndex(n, j, k + 1)];
      P3& o = out[netIndex(n - 1, j, k)];
      if constexpr (S == kE0) o = a;
      if constexpr (S == kE1) o = b;
      if constexpr (S == kE2) o = c;
      if constexpr (S == kM01) o = mid(a, b);
      if constexpr (S == kM02) o = mid(a, c);
      if constexpr (S == kM12) o = mid(b, c);
    }
}

// The net of the sub-triangle with corners A, B, C: point (i, j, k) is the blossom
// b(A^i, B^j, C^k), evaluated by de Casteljau steps at A, then B, then C, sharing the steps.
template <Corner A, Corner B, Corner C>
void subNet(const Net& in, Net& out) {
  P3 byA[BezierTriangle::kPoints], byB[BezierTriangle::kPoints], byC[BezierTriangle::kPoints];
  std::copy(in.begin(), in.end(), byA);
  for (int i = 0; i <= 4; ++i) {
    if (i > 0) cornerStep<A>(byA, 5 - i, byA);
    const int m = 4 - i;
    std::copy(byA, byA + (m + 1) * (m + 2) / 2, byB);
    for (int j = 0; j <= m; ++j) {
      if (j > 0) cornerStep<B>(byB, m - j + 1, byB);
      const int c = m - j;
      if (c == 0) {
        out[size_t(BezierTriangle::index(j, 0))] = byB[0];
        continue;
      }
      std::copy(byB, byB + (c + 1) * (c + 2) / 2, byC);
      for (int e = c; e > 0; --e) cornerStep<C>(byC, e, byC);
      out[size_t(BezierTriangle::index(j, c))] = byC[0];
    }
  }
}

}  // namespace

// Newest-vertex bisection: the edge opposite corner 0 is split at its midpoint m12 into
// (m12, e0, e1) and (m12, e2, e0), the new vertex first, so that repeated bisection keeps
// the sub-triangles' shapes (4 similarity classes). Both children come from one chain of
// de Casteljau steps at m12: child a at (i, j, k) is point (k, 0) of the net after i steps,
// child b point (0, j).
void bezier_detail::bisect(const Net& in, Net& a, Net& b) {
  P3 net[BezierTriangle::kPoints];
  std::copy(in.begin(), in.end(), net);
  for (int i = 0; i <= 4; ++i) {
    const int n = 4 - i;  // degree of the current net
    if (i > 0) cornerStep<kM12>(net, n + 1, net);
    for (int j = 0; j <= n; ++j) {
      a[size_t(BezierTriangle::index(j, n - j))] = net[netIndex(n, n - j, 0)];
      b[size_t(BezierTriangle::index(j, n - j))] = net[netIndex(n, 0, j)];
    }
  }
}

void bezier_detail::child(const Net& in, int m, Net& out) {
  switch (m) {
    case 0:
      return subNet<kE0, kM01, kM02>(in, out);
    case 1:
      return subNet<kM01, kE1, kM12>(in, out);
    case 2:
      return subNet<kM02, kM12, kE2>(in, out);
    default:
      return subNet<kM12, kM02, kM01>(in, out);
  }
}

// The net of the sub-triangle with corners (cu[m], cv[m]) in the net's (u, v): subNet's steps at
// arbitrary points.
void bezier_detail::regionNet(const Net& in, const double* cu, const double* cv, Net& out) {
  const Bary A{1.0 - cu[0] - cv[0], cu[0], cv[0]}, B{1.0 - cu[1] - cv[1], cu[1], cv[1]},
      C{1.0 - cu[2] - cv[2], cu[2], cv[2]};
  P3 byA[BezierTriangle::kPoints], byB[BezierTriangle::kPoints], byC[BezierTriangle::kPoints];
  std::copy(in.begin(), in.end(), byA);
  for (int i = 0; i <= 4; ++i) {
    if (i > 0) casteljauStep(byA, 5 - i, A, byA);
    const int m = 4 - i;
    std::copy(byA, byA + (m + 1) * (m + 2) / 2, byB);
    for (int j = 0; j <= m; ++j) {
      if (j > 0) casteljauStep(byB, m - j + 1, B, byB);
      const int c = m - j;
      if (c == 0) {
        out[size_t(BezierTriangle::index(j, 0))] = byB[0];
        continue;
      }
      std::copy(byB, byB + (c + 1) * (c + 2) / 2, byC);
      for (int e = c; e > 0; --e) casteljauStep(byC, e, C, byC);
      out[size_t(BezierTriangle::index(j, c))] = byC[0];
    }
  }
}

namespace {

// The piece over `net`, with `like`'s orientation, triangle and piece number.
BezierTriangle pieceOfNet(const Net& net, const BezierTriangle& like) {
  BezierTriangle out;
  for (int i = 0; i < BezierTriangle::kPoints; ++i) {
    const P3& p = net[size_t(i)];
    out.b[size_t(i)] = Vec3(p.x, p.y, p.z);
  }
  out.orientation = like.orientation;
  out.triangle = like.triangle;
  out.piece = like.piece;
  return out;
}

}  // namespace

std::array<BezierTriangle, 2> bisectBezierTriangle(const BezierTriangle& piece, int corner) {
  // Rotated so that `corner` comes first (a cyclic turn keeps the orientation): the new point
  // with exponents (e0, e1, e2) on the new corners is the old one with exponent e_m on old
  // corner (corner + m) mod 3.
  Net net;
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j + k <= 4; ++j) {
      const int e[3] = {4 - j - k, j, k};
      int old[3];
      for (int m = 0; m < 3; ++m) old[(corner + m) % 3] = e[m];
      const Vec3& p = piece.b[size_t(BezierTriangle::index(old[1], old[2]))];
      net[size_t(BezierTriangle::index(j, k))] = {p.x(), p.y(), p.z()};
    }
  Net halves[2];
  bisect(net, halves[0], halves[1]);
  return {pieceOfNet(halves[0], piece), pieceOfNet(halves[1], piece)};
}

std::array<BezierTriangle, 4> subdivideBezierTriangle(const BezierTriangle& piece) {
  Net net;
  for (int i = 0; i < BezierTriangle::kPoints; ++i) {
    const Vec3& p = piece.b[size_t(i)];
    net[size_t(i)] = {p.x(), p.y(), p.z()};
  }
  std::array<BezierTriangle, 4> out;
  for (size_t m = 0; m < 4; ++m) {
    Net sub;
    child(net, int(m), sub);
    out[m] = pieceOfNet(sub, piece);
  }
  return out;
}

}  // namespace quadtri
