// The sub-patches that rendering traces (bezier_intersect.h: BezierSubPatch): their fast path
// (prism, cone-certified Newton) and the search on a region. Their construction and the region
// budget are in bezier_regions.cpp.
#include <tbb/blocked_range.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <mutex>
#include <utility>

#include "bezier_net.h"
#include "quadtri/math/float_round.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/bezier_intersect.h"

namespace quadtri {

using namespace bezier_detail;

namespace {

// The first de Casteljau step of the piece's own (3D) net at (u, v): a cubic net.
inline void cubicNet(const BezierTriangle& piece, double u, double v, P3* a) {
  const double w0 = 1.0 - u - v;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j + k < 4; ++j) {
      const Vec3& A = piece.b[size_t(netIndex(4, j, k))];
      const Vec3& B = piece.b[size_t(netIndex(4, j + 1, k))];
      const Vec3& C = piece.b[size_t(netIndex(4, j, k + 1))];
      a[netIndex(3, j, k)] = {w0 * A.x() + u * B.x() + v * C.x(),
                              w0 * A.y() + u * B.y() + v * C.y(),
                              w0 * A.z() + u * B.z() + v * C.z()};
    }
}

// Position and first derivatives of the piece at (u, v).
inline void evaluatePiece(const BezierTriangle& piece, double u, double v, P3& p, P3& du, P3& dv) {
  P3 a[10];
  cubicNet(piece, u, v, a);
  evaluateFromCubic(a, u, v, p, du, dv);
}

// evaluatePiece with the second derivatives too, from the same de Casteljau steps: the quadratic
// net b after two steps gives ∂²/∂u² = 12 (b_020 − 2 b_110 + b_200) and its kin.
inline void evaluatePiece2(const BezierTriangle& piece, double u, double v, P3& p, P3& du, P3& dv,
                           P3& duu, P3& duv, P3& dvv) {
  const Bary w{1.0 - u - v, u, v};
  P3 a[10], b[6];
  cubicNet(piece, u, v, a);
  casteljauStep(a, 3, w, b);
  const P3& b200 = b[netIndex(2, 0, 0)];
  const P3& b110 = b[netIndex(2, 1, 0)];
  const P3& b101 = b[netIndex(2, 0, 1)];
  const P3& b020 = b[netIndex(2, 2, 0)];
  const P3& b011 = b[netIndex(2, 1, 1)];
  const P3& b002 = b[netIndex(2, 0, 2)];
  duu = {12 * (b020.x - 2 * b110.x + b200.x), 12 * (b020.y - 2 * b110.y + b200.y),
         12 * (b020.z - 2 * b110.z + b200.z)};
  duv = {12 * (b011.x - b110.x - b101.x + b200.x), 12 * (b011.y - b110.y - b101.y + b200.y),
         12 * (b011.z - b110.z - b101.z + b200.z)};
  dvv = {12 * (b002.x - 2 * b101.x + b200.x), 12 * (b002.y - 2 * b101.y + b200.y),
         12 * (b002.z - 2 * b101.z + b200.z)};
  evaluateFromQuadratic(b, u, v, p, du, dv);
}

inline double dot(const P3& a, const P3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline P3 cross(const P3& a, const P3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Newton on b(u, v) = o + t·d in (u, v, t), in 3D on the piece's own net, from (u, v, t). On
// success (u, v) is a root and t its ray parameter: the point b(u, v) lies on the line, within
// 1e-9 of the scale of the piece's control points seen from o (an upper bound of
// intersectBezierTriangle's) with a step below 1e-9, or within 1e-6 with a step below 1e-6 that
// squared the one before (the quadratic convergence that only a regular root gives); either way
// polished by that last step. A point near the line at a singular Jacobian is no root.
bool newton3(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double& u, double& v,
             double& t) {
  const P3 nd{-d.x(), -d.y(), -d.z()};
  const double dd = d.squaredNorm();
  double previous = kInfinity;
  P3 p, pu, pv, puu, puv, pvv;
  for (int it = 0; it < 24; ++it) {
    if (it == 0)
      evaluatePiece2(piece, u, v, p, pu, pv, puu, puv, pvv);
    else
      evaluatePiece(piece, u, v, p, pu, pv);
    // Solve [pu pv −d]·(su, sv, st) = o + t·d − p by Cramer's rule.
    const P3 f{o.x() + t * d.x() - p.x, o.y() + t * d.y() - p.y, o.z() + t * d.z() - p.z};
    const P3 bc = cross(pv, nd), ca = cross(nd, pu), ab = cross(pu, pv);
    const double det = dot(pu, bc);
    if (!(std::abs(det) > 0.0)) return false;
    double su = dot(f, bc) / det, sv = dot(f, ca) / det, st = dot(f, ab) / det;
    if (!std::isfinite(su) || !std::isfinite(sv) || !std::isfinite(st)) return false;
    if (it == 0) {
      // The first step from the start is Chebyshev's: the Newton step (su, sv, st) corrected by
      // the curvature it crosses, J⁻¹ · ½ H(s, s), when that correction is small. Its error is
      // cubic in the start's, so the next step usually settles (two evaluations, not three).
      const P3 h{0.5 * (puu.x * su * su + 2 * puv.x * su * sv + pvv.x * sv * sv),
                 0.5 * (puu.y * su * su + 2 * puv.y * su * sv + pvv.y * sv * sv),
                 0.5 * (puu.z * su * su + 2 * puv.z * su * sv + pvv.z * sv * sv)};
      const double cu = dot(h, bc) / det, cv = dot(h, ca) / det, ct = dot(h, ab) / det;
      if (std::isfinite(cu) && std::isfinite(cv) && std::isfinite(ct) &&
          std::max(std::abs(cu), std::abs(cv)) < 0.5 * std::max(std::abs(su), std::abs(sv)))
        su -= cu, sv -= cv, st -= ct;
    }
    const double step = std::max(std::abs(su), std::abs(sv));
    const bool settled = step < 1e-9;
    const bool quadratic = step < 1e-7 && step <= 10.0 * previous * previous;
    if (settled || quadratic) {
      const P3 r{p.x - o.x(), p.y - o.y(), p.z - o.z()};
      const double tp = (r.x * d.x() + r.y * d.y() + r.z * d.z()) / dd;
      const double tolerance = settled ? 1e-9 : 1e-6;
      const double farthest = std::max({std::abs(r.x), std::abs(r.y), std::abs(r.z)});
      const auto onLine = [&](double boxSize) {
        const double residual = tolerance * (farthest + boxSize);
        return std::abs(r.x - tp * d.x()) <= residual && std::abs(r.y - tp * d.y()) <= residual &&
               std::abs(r.z - tp * d.z()) <= residual;
      };
      // The box of the control points (the piece stores none) only widens the tolerance, so it
      // is computed only for a point that the distance from o alone does not accept: nearly
      // always the point is on the line far within that.
      const auto boxSize = [&] {
        const Bounds3 box = piece.bounds();
        return (box.hi - box.lo).maxCoeff();
      };
      if (onLine(0.0) || onLine(boxSize())) {
        u += su;
        v += sv;
        t += st;
        return std::isfinite(t) && std::abs(u) <= 4.0 && std::abs(v) <= 4.0;
      }
    }
    previous = step;
    u += su;
    v += sv;
    t += st;
    if (std::abs(u) > 4.0 || std::abs(v) > 4.0) return false;
  }
  return false;
}

enum class Solved { Hit, Candidate, None, Unknown };

// Whether (u, v) lies in the closed triangle with corners (cu, cv) (no slack).
bool inTriangle(const double* cu, const double* cv, double u, double v) {
  const double e1u = cu[1] - cu[0], e1v = cv[1] - cv[0];
  const double e2u = cu[2] - cu[0], e2v = cv[2] - cv[0];
  const double ru = u - cu[0], rv = v - cv[0];
  const double det = e1u * e2v - e1v * e2u;
  const double a = (ru * e2v - rv * e2u) / det, b = (e1u * rv - e1v * ru) / det;
  return a >= 0.0 && b >= 0.0 && a + b <= 1.0;
}

bool inParent(const BezierSubPatch& sub, double u, double v) {
  double pu[3], pv[3];
  sub.parentCorners(pu, pv);
  return inTriangle(pu, pv, u, v);
}

// The ray against a sub-patch's prism, in a few dot products: false when it misses. Otherwise
// `prism` holds the ray's height above the corner triangle's plane (ho + t·hd) and its
// barycentric coordinates 1 and 2 there (a + t·b) for the fast path. Small and inline, apart
// from the solve: most calls end here, and they keep to a little code.
struct PrismCrossing {
  double ho, hd, a1, b1, a2, b2;
};

inline bool crossesPrism(const BezierSubPatch& sub, const Vec3& o, const Vec3& d, double tmin,
                         double tmax, PrismCrossing& prism) {
  const Vec3 r = o - sub.p0;
  const double ho = dotf(r, sub.n), hd = dotf(d, sub.n);
  // Rounding of the projections from a far origin: far below this.
  const double far = 1e-12 * r.cwiseAbs().maxCoeff();
  double t0 = tmin, t1 = tmax;
  if (hd != 0.0) {
    double ta = (double(sub.hlo) - far - ho) / hd, tb = (double(sub.hhi) + far - ho) / hd;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (!(t0 <= t1)) return false;
  } else if (ho < double(sub.hlo) - far || ho > double(sub.hhi) + far) {
    return false;
  }
  // The corner triangle's barycentric coordinates 1 and 2 along the ray: a + t·b; the largest
  // over [t0, t1] must reach each control point's least.
  const double a1 = dotf(r, sub.g1), b1 = dotf(d, sub.g1);
  const double a2 = dotf(r, sub.g2), b2 = dotf(d, sub.g2);
  const double farL = far * double(sub.inverseSize);
  auto reach = [&](double a, double b) { return b > 0.0 ? a + t1 * b : b < 0.0 ? a + t0 * b : a; };
  if (reach(a1, b1) < double(sub.lmin[1]) - farL || reach(a2, b2) < double(sub.lmin[2]) - farL ||
      reach(1.0 - a1 - a2, -b1 - b2) < double(sub.lmin[0]) - farL)
    return false;
  prism = {ho, hd, a1, b1, a2, b2};
  return true;
}

// At most one root in the region when every projected cross of derivative control vectors has
// the sign of d·axis (the injectivity test of slopes(), from the precomputed cone).
inline bool certifies(const BezierSubPatch& sub, const Vec3& d) {
  const double da = dotf(d, sub.axis), sinCone = double(sub.sinCone);
  return da * da > sinCone * sinCone * d.squaredNorm();
}

// A ray that leaves the region (`from`: see intersectBezierSubPatch), where the region's cone
// certifies it, meets the region at most once: there, at its origin. About half the regions a
// bounce or shadow ray is tested against are the one it leaves; this spares them the prism.
inline bool leavesRegion(const BezierSubPatch& sub, const Vec3& d, const Vec2* from) {
  if (!from || !certifies(sub, d)) return false;
  double cu[3], cv[3];
  sub.corners(cu, cv);
  return inTriangle(cu, cv, from->x(), from->y());
}

// The fast path of a sub-patch the ray crosses the prism of: Newton from where the ray crosses
// the corner triangle's plane. Hit and None are final: the cone proves that the ray meets the
// region at most once. Candidate is a root of the region in range, but where the ray may meet
// the region twice; Unknown leaves the region to the subdivision search. (A ray that leaves the
// region never gets here: leavesRegion.)
[[gnu::noinline]] Solved solveSubPatch(const BezierTriangle& piece, const BezierSubPatch& sub,
                                       const Vec3& o, const Vec3& d, double tmin, double tmax,
                                       const PrismCrossing& prism, BezierHit& hit) {
  const auto [ho, hd, a1, b1, a2, b2] = prism;
  const bool injective = certifies(sub, d);
  double cu[3], cv[3];
  sub.corners(cu, cv);
  double t = -ho / hd;
  if (!std::isfinite(t)) return Solved::Unknown;
  double l1 = std::max(a1 + t * b1, 0.0), l2 = std::max(a2 + t * b2, 0.0);
  const double l0 = std::max(1.0 - (a1 + t * b1) - (a2 + t * b2), 0.0);
  const double sum = l0 + l1 + l2;
  l1 /= sum, l2 /= sum;
  double u = cu[0] + l1 * (cu[1] - cu[0]) + l2 * (cu[2] - cu[0]);
  double v = cv[0] + l1 * (cv[1] - cv[0]) + l2 * (cv[2] - cv[0]);
  // Where Newton finds no root in the region, the winding number of its boundary settles
  // whether the ray meets a region it meets at most once.
  const auto unsettled = [&] {
    return injective && bezierRegionWinding(piece, cu, cv, o, d) == RegionWinding::Outside
               ? Solved::None
               : Solved::Unknown;
  };
  if (!newton3(piece, o, d, u, v, t)) return unsettled();
  // The root in the region (its barycentric coordinates there) and in the piece's domain.
  const double e1u = cu[1] - cu[0], e1v = cv[1] - cv[0], e2u = cu[2] - cu[0], e2v = cv[2] - cv[0];
  const double ru = u - cu[0], rv = v - cv[0];
  const double det = e1u * e2v - e1v * e2u;
  const double ba = (ru * e2v - rv * e2u) / det, bb = (e1u * rv - e1v * ru) / det;
  if (!(ba >= -kNodeSlack && bb >= -kNodeSlack && ba + bb <= 1.0 + kNodeSlack)) {
    // A root outside the region: none in it when the parent holds that root and meets the ray
    // at most once.
    const double dp = dotf(d, sub.parentAxis), sinParent = double(sub.parentSinCone);
    if (injective && dp * dp > sinParent * sinParent * d.squaredNorm() && inParent(sub, u, v))
      return Solved::None;
    return unsettled();
  }
  if (!(u >= -kDomainSlack && v >= -kDomainSlack && u + v <= 1.0 + kDomainSlack))
    return unsettled();
  if (!(t > tmin && t < tmax)) return injective ? Solved::None : Solved::Unknown;
  hit = {t, u, v};
  return injective ? Solved::Hit : Solved::Candidate;
}

}  // namespace

bool intersectBezierSubPatch(const BezierTriangle& piece, const BezierSubPatch& sub, const Vec3& o,
                             const Vec3& d, double tmin, double tmax, BezierHit& hit,
                             const Vec2* from) {
  PrismCrossing prism;
  if (!(tmin < tmax) || leavesRegion(sub, d, from) || !crossesPrism(sub, o, d, tmin, tmax, prism))
    return false;
  BezierHit candidate;
  switch (solveSubPatch(piece, sub, o, d, tmin, tmax, prism, candidate)) {
    case Solved::Hit:
      hit = candidate;
      return true;
    case Solved::None:
      return false;
    case Solved::Candidate:
      tmax = candidate.t;  // the search is for a nearer root
      break;
    case Solved::Unknown:
      break;
  }
  const Vec3 up(sub.axis[0], sub.axis[1], sub.axis[2]);
  Found found;
  traceBezier(piece, o, d, tmin, tmax, Mode::Nearest, found, &up, &sub);
  if (found.any) {
    hit = found.nearest;
    return true;
  }
  if (candidate.t == kInfinity) return false;
  hit = candidate;
  return true;
}

bool occludesBezierSubPatch(const BezierTriangle& piece, const BezierSubPatch& sub, const Vec3& o,
                            const Vec3& d, double tmin, double tmax, const Vec2* from) {
  PrismCrossing prism;
  if (!(tmin < tmax) || leavesRegion(sub, d, from) || !crossesPrism(sub, o, d, tmin, tmax, prism))
    return false;
  BezierHit hit;
  switch (solveSubPatch(piece, sub, o, d, tmin, tmax, prism, hit)) {
    case Solved::Hit:
    case Solved::Candidate:
      return true;
    case Solved::None:
      return false;
    case Solved::Unknown:
      break;
  }
  const Vec3 up(sub.axis[0], sub.axis[1], sub.axis[2]);
  Found found;
  return traceBezier(piece, o, d, tmin, tmax, Mode::Any, found, &up, &sub) && found.any;
}

}  // namespace quadtri
