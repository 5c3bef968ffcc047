// Internals shared by bezier_intersect.cpp (the subdivision search of one piece),
// bezier_subpatch.cpp (the sub-patches that rendering traces) and bezier_regions.cpp (their
// records and budget): the nets' arithmetic, the search's limits and its entry point. Private to
// the surface layer.
#pragma once

#include <array>

#include "quadtri/surface/bezier_intersect.h"

namespace quadtri::bezier_detail {

// Bisections: two make one midpoint 4-split, so 30 reach sub-triangles of 1/32768 the size
// (20, 1/1024, lost two roots 1e-5 apart on a line grazing the torus at n·d = 2e-4).
constexpr int kMaxDepthAll = 30;
// Rendering queries stop at 20 (1/1024): deeper levels spend the smaller node budget below
// before the nearest root is found.
constexpr int kMaxDepthRender = 20;
constexpr int kStackSize = kMaxDepthAll + 8;  // depth first: at most 1 pending per level
// Past this many nodes (a degenerate piece, say one collapsed onto a segment the ray crosses)
// the search stops, so no ray costs more than about this. A ray that grazes a piece near its
// silhouette, where two roots lie on either side of the fold of its projection, needs many:
// the nodes that straddle the fold cannot be solved and are split down to the last level. At
// 2,000, 53 of the corpus' 85 closed meshes lost such roots (crack rates 1e-5 to 5e-4 at 100,000
// lines); at 20,000, 15 (pinion, pipe, joint: 2e-5 to 6e-5).
constexpr int kMaxNodesAll = 200000;
// Nearest and any-hit queries (rendering) keep the first version's budget: a grazing ray's lost
// second root changes a silhouette pixel's sample at most, and 200,000 nodes made a close-up of
// an 80-triangle icosphere 60 times slower than `shading`.
constexpr int kMaxNodesRender = 2000;
constexpr int kMaxHits = 16;
// Newton's root lies in a sub-triangle when its barycentric coordinates there are above −this.
constexpr double kNodeSlack = 1e-6;
// ... and in the piece when u, v and 1 − u − v are above −this.
constexpr double kDomainSlack = 1e-9;
// Roots of one piece closer than this in (u, v) are one hit.
constexpr double kSameRoot = 1e-9;

struct P3 {
  double x, y, z;
};

// A degree-n net laid out like BezierTriangle::index: rows of constant k, j increasing.
constexpr int netIndex(int n, int j, int k) {
  return k * (n + 1) - k * (k - 1) / 2 + j;
}

using Net = std::array<P3, BezierTriangle::kPoints>;

// Barycentric weights (over the parent's corners 0, 1, 2) of a sub-triangle corner.
struct Bary {
  double w0, w1, w2;
};

// One de Casteljau step of a degree-n net at barycentric w: a degree n − 1 net. In place
// (out == in) is allowed: each output precedes the inputs still to be read.
inline void casteljauStep(const P3* in, int n, const Bary& w, P3* out) {
  for (int k = 0; k < n; ++k)
    for (int j = 0; j + k < n; ++j) {
      const P3& a = in[netIndex(n, j, k)];
      const P3& b = in[netIndex(n, j + 1, k)];
      const P3& c = in[netIndex(n, j, k + 1)];
      out[netIndex(n - 1, j, k)] = {w.w0 * a.x + w.w1 * b.x + w.w2 * c.x,
                                    w.w0 * a.y + w.w1 * b.y + w.w2 * c.y,
                                    w.w0 * a.z + w.w1 * b.z + w.w2 * c.z};
    }
}

// The corners of child m (as child()) of the sub-triangle with corners (cu, cv), in place.
inline void childCorners(int m, double* cu, double* cv) {
  // Child m's corners in its parent's own (u, v).
  static constexpr double kCorner[4][3][2] = {{{0, 0}, {0.5, 0}, {0, 0.5}},
                                              {{0.5, 0}, {1, 0}, {0.5, 0.5}},
                                              {{0, 0.5}, {0.5, 0.5}, {0, 1}},
                                              {{0.5, 0.5}, {0, 0.5}, {0.5, 0}}};
  const double u0 = cu[0], v0 = cv[0];
  const double e1u = cu[1] - u0, e1v = cv[1] - v0, e2u = cu[2] - u0, e2v = cv[2] - v0;
  for (int c = 0; c < 3; ++c) {
    const double a = kCorner[m][c][0], b = kCorner[m][c][1];
    cu[c] = u0 + a * e1u + b * e2u;
    cv[c] = v0 + a * e1v + b * e2v;
  }
}

// The last de Casteljau step at (u, v) from a degree-2 net `b`: the point and the first
// derivatives of the degree-4 net it came from.
inline void evaluateFromQuadratic(const P3* b, double u, double v, P3& p, P3& du, P3& dv) {
  const Bary w{1.0 - u - v, u, v};
  P3 c[3];
  casteljauStep(b, 2, w, c);
  p = {w.w0 * c[0].x + u * c[1].x + v * c[2].x, w.w0 * c[0].y + u * c[1].y + v * c[2].y,
       w.w0 * c[0].z + u * c[1].z + v * c[2].z};
  du = {4 * (c[1].x - c[0].x), 4 * (c[1].y - c[0].y), 4 * (c[1].z - c[0].z)};
  dv = {4 * (c[2].x - c[0].x), 4 * (c[2].y - c[0].y), 4 * (c[2].z - c[0].z)};
}

// The last two de Casteljau steps at (u, v) from a degree-3 net `a` (as above).
inline void evaluateFromCubic(const P3* a, double u, double v, P3& p, P3& du, P3& dv) {
  P3 b[6];
  casteljauStep(a, 3, Bary{1.0 - u - v, u, v}, b);
  evaluateFromQuadratic(b, u, v, p, du, dv);
}

// Newest-vertex bisection of a net: the edge opposite corner 0 split at its midpoint into
// (m12, e0, e1) and (m12, e2, e0), the new vertex first (bezier_subdivide.cpp).
void bisect(const Net& in, Net& a, Net& b);
// Midpoint child m (0–2 at corners 0–2, 3 the middle) of a net, as childCorners places it.
void child(const Net& in, int m, Net& out);
// The net of the sub-triangle with corners (cu[m], cv[m]) in the net's (u, v).
void regionNet(const Net& in, const double* cu, const double* cv, Net& out);

// a · b for a direction stored in float (a BezierSubPatch's), in double.
inline double dotf(const Vec3& a, const float* b) {
  return a.x() * double(b[0]) + a.y() * double(b[1]) + a.z() * double(b[2]);
}

enum class Mode { Nearest, Any, All };

// Hits found so far: the nearest (Nearest, Any) or every distinct one (All).
struct Found {
  BezierHit nearest;
  bool any = false;
  BezierHit all[kMaxHits];
  int count = 0;
};

// The subdivision search of bezier_intersect.h on `piece` along o + t·d in (tmin, tmax): `up`,
// when given, sets the frame (t is its part perpendicular to d), and `region` restricts it to a
// sub-patch. Fills `found` as the mode asks; false when the ray cannot be searched (d zero).
bool traceBezier(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double tmin,
                 double tmax, Mode mode, Found& found, const Vec3* up = nullptr,
                 const BezierSubPatch* region = nullptr);

// bezierRegionWinding for a net already in the line's frame (the line the z axis through the
// origin, as the search's nets): the winding number of the net's boundary, in x and y, around
// the origin, with `margin` as the search's rounding margin.
RegionWinding netWinding(const Net& net, double margin);

}  // namespace quadtri::bezier_detail
