// Whether a line meets a region of a Bézier piece whose projection along the line is one to one:
// the winding number of the projected region boundary around the line (bezier_intersect.h).
#include <algorithm>
#include <cmath>

#include "bezier_net.h"

namespace quadtri {

using namespace bezier_detail;

namespace {

struct P2 {
  double x, y;
};

// One de Casteljau step of a degree-N 2D net at barycentric w (in place allowed, as
// casteljauStep).
template <int N>
inline void step2(const P2* in, const Bary& w, P2* out) {
  for (int k = 0; k < N; ++k)
    for (int j = 0; j + k < N; ++j) {
      const P2& a = in[netIndex(N, j, k)];
      const P2& b = in[netIndex(N, j + 1, k)];
      const P2& c = in[netIndex(N, j, k + 1)];
      out[netIndex(N - 1, j, k)] = {w.w0 * a.x + w.w1 * b.x + w.w2 * c.x,
                                    w.w0 * a.y + w.w1 * b.y + w.w2 * c.y};
    }
}

// The first four control points of the quartic curve the net takes along the segment from
// domain point A to B: the blossom at (A^(4−k), B^k) for k = 0..3 (the fifth is the net at B).
void edgeCurve(const P2* net, const Bary& A, const Bary& B, P2* out) {
  // The nets after 1, 2, 3 and 4 steps at A (degrees 3, 2, 1, 0), then k steps at B from the
  // degree-k one.
  P2 a3[10], a2[6], a1[3], t2[3], t3[6], u3[3];
  step2<4>(net, A, a3);
  step2<3>(a3, A, a2);
  step2<2>(a2, A, a1);
  step2<1>(a1, A, out);
  step2<1>(a1, B, out + 1);
  step2<2>(a2, B, t2);
  step2<1>(t2, B, out + 2);
  step2<3>(a3, B, t3);
  step2<2>(t3, B, u3);
  step2<1>(u3, B, out + 3);
}

// Whether the convex hull of a quartic curve's five control points keeps away from the origin
// by more than `margin`: its box, or the band its chord's line and the chord's direction cut.
bool hullExcludesOrigin(const P2* c, double margin) {
  double xlo = c[0].x, xhi = c[0].x, ylo = c[0].y, yhi = c[0].y;
  for (int i = 1; i < 5; ++i) {
    xlo = std::min(xlo, c[i].x), xhi = std::max(xhi, c[i].x);
    ylo = std::min(ylo, c[i].y), yhi = std::max(yhi, c[i].y);
  }
  if (xlo > margin || xhi < -margin || ylo > margin || yhi < -margin) return true;
  const double wx = c[4].x - c[0].x, wy = c[4].y - c[0].y;
  const double length = std::sqrt(wx * wx + wy * wy);
  if (!(length > 0.0)) return false;
  // Across the chord (the origin at −n·c0) and along it (at −w·c0), in units of |w|.
  double alo = kInfinity, ahi = -kInfinity, blo = kInfinity, bhi = -kInfinity;
  for (int i = 0; i < 5; ++i) {
    const double rx = c[i].x - c[0].x, ry = c[i].y - c[0].y;
    const double across = wx * ry - wy * rx, along = wx * rx + wy * ry;
    alo = std::min(alo, across), ahi = std::max(ahi, across);
    blo = std::min(blo, along), bhi = std::max(bhi, along);
  }
  const double originAcross = wx * (-c[0].y) - wy * (-c[0].x);
  const double originAlong = wx * (-c[0].x) + wy * (-c[0].y);
  const double m = margin * length;
  return originAcross < alo - m || originAcross > ahi + m || originAlong < blo - m ||
         originAlong > bhi + m;
}

// The two halves of a quartic curve at its midpoint: left[4] == right[0].
void halve(const P2* c, P2* left, P2* right) {
  P2 t[5];
  std::copy(c, c + 5, t);
  left[0] = t[0];
  right[4] = t[4];
  for (int level = 1; level <= 4; ++level) {
    for (int i = 0; i + level <= 4; ++i)
      t[i] = {0.5 * (t[i].x + t[i + 1].x), 0.5 * (t[i].y + t[i + 1].y)};
    left[level] = t[0];
    right[4 - level] = t[4 - level];
  }
}

// The origin's winding number contribution of segment p → q (Sunday's crossing rule).
inline int crossing(const P2& p, const P2& q) {
  const double side = p.x * q.y - p.y * q.x;  // > 0: the origin lies left of p → q
  if (p.y <= 0.0) return q.y > 0.0 && side > 0.0 ? 1 : 0;
  return q.y <= 0.0 && side < 0.0 ? -1 : 0;
}

// Halvings of one edge curve before the query gives up: a hull 2^-12 of the edge's length.
constexpr int kMaxHalvings = 12;

// The winding number around the origin of the closed curve of three quartic edges (each edge's
// last point the next one's first), for a boundary that is a simple closed curve: 0, ±1, or
// Unknown where the curve passes within `margin` of the origin. Each edge's control polygon is
// refined until no hull of its pieces holds the origin: then the curve and the polygon wind
// around the origin alike (each piece and its polygon close a loop within a hull that misses it).
RegionWinding boundaryWinding(const P2 (&edges)[3][5], double margin) {
  int winding = 0;
  for (int e = 0; e < 3; ++e) {
    P2 stack[kMaxHalvings + 2][5];
    int depth[kMaxHalvings + 2];
    int top = 0;
    std::copy(edges[e], edges[e] + 5, stack[0]);
    depth[0] = 0;
    ++top;
    while (top > 0) {
      --top;
      const P2* c = stack[top];
      if (hullExcludesOrigin(c, margin)) {
        for (int i = 0; i < 4; ++i) winding += crossing(c[i], c[i + 1]);
        continue;
      }
      if (depth[top] >= kMaxHalvings) return RegionWinding::Unknown;  // the curve grazes it
      P2 left[5], right[5];
      halve(c, left, right);
      const int next = depth[top] + 1;
      // The right half first on the stack, so the left is walked first (the order of the
      // segments does not change the sum, but keeps the stack within one slot per level).
      std::copy(right, right + 5, stack[top]);
      depth[top] = next;
      std::copy(left, left + 5, stack[top + 1]);
      depth[top + 1] = next;
      top += 2;
    }
  }
  if (winding == 0) return RegionWinding::Outside;
  return winding == 1 || winding == -1 ? RegionWinding::Inside : RegionWinding::Unknown;
}

// The boundary rows of a 2D net: corner 0 → 1 (k = 0), 1 → 2 (i = 0) and 2 → 0 (j = 0).
template <typename P>
void boundaryRows(const P* net, P2 (&edges)[3][5]) {
  for (int m = 0; m <= 4; ++m) {
    const P& a = net[BezierTriangle::index(m, 0)];
    const P& b = net[BezierTriangle::index(4 - m, m)];
    const P& c = net[BezierTriangle::index(0, 4 - m)];
    edges[0][m] = {a.x, a.y};
    edges[1][m] = {b.x, b.y};
    edges[2][m] = {c.x, c.y};
  }
}

}  // namespace

RegionWinding bezierRegionWinding(const BezierTriangle& piece, const double* cu, const double* cv,
                                  const Vec3& o, const Vec3& d) {
  const double dd = d.squaredNorm();
  if (!(dd > 0.0) || !std::isfinite(dd)) return RegionWinding::Unknown;
  Vec3 s, t;
  orthonormalBasis(d / std::sqrt(dd), s, t);
  P2 net[15];
  double scale = 0.0;
  for (int i = 0; i < BezierTriangle::kPoints; ++i) {
    const Vec3 r = piece.b[size_t(i)] - o;
    net[i] = {r.dot(s), r.dot(t)};
    scale = std::max(scale, r.cwiseAbs().maxCoeff());
  }
  // As the subdivision search's: far above the rounding of the projection and of the halvings.
  const double margin = 1e-11 * scale;
  if (!std::isfinite(margin)) return RegionWinding::Unknown;
  const Bary corner[3] = {{1.0 - cu[0] - cv[0], cu[0], cv[0]},
                          {1.0 - cu[1] - cv[1], cu[1], cv[1]},
                          {1.0 - cu[2] - cv[2], cu[2], cv[2]}};
  P2 edges[3][5];
  const bool whole =
      cu[0] == 0.0 && cv[0] == 0.0 && cu[1] == 1.0 && cv[1] == 0.0 && cu[2] == 0.0 && cv[2] == 1.0;
  if (whole) {
    boundaryRows(net, edges);  // the piece's own boundary: no blossoms needed
  } else {
    for (int e = 0; e < 3; ++e) edgeCurve(net, corner[e], corner[(e + 1) % 3], edges[e]);
    for (int e = 0; e < 3; ++e) edges[e][4] = edges[(e + 1) % 3][0];
  }
  return boundaryWinding(edges, margin);
}

RegionWinding bezier_detail::netWinding(const Net& net, double margin) {
  P2 edges[3][5];
  boundaryRows(net.data(), edges);
  return boundaryWinding(edges, margin);
}

}  // namespace quadtri
