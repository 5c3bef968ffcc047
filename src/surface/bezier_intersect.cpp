#include "quadtri/surface/bezier_intersect.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bezier_net.h"

namespace quadtri {

using namespace bezier_detail;

namespace {
// Position and first derivatives of a degree-4 net at (u, v).
inline void evaluate(const Net& net, double u, double v, P3& p, P3& du, P3& dv) {
  P3 a[10];
  casteljauStep(net.data(), 4, Bary{1.0 - u - v, u, v}, a);
  evaluateFromCubic(a, u, v, p, du, dv);
}

// Newton on (x, y)(u, v) = 0 over the whole piece's projected net, from (u, v). On success
// (u, v) is the root (|x|, |y| at most `residual` there) and z its ray parameter.
bool newton(const Net& net, double residual, double& u, double& v, double& z) {
  P3 p, pu, pv;
  for (int it = 0; it < 24; ++it) {
    evaluate(net, u, v, p, pu, pv);
    const double det = pu.x * pv.y - pu.y * pv.x;
    if (!(std::abs(det) > 0.0)) return false;
    const double su = (pv.x * p.y - pv.y * p.x) / det;
    const double sv = (pu.y * p.x - pu.x * p.y) / det;
    if (!std::isfinite(su) || !std::isfinite(sv)) return false;
    u += su;
    v += sv;
    if (std::abs(u) > 4.0 || std::abs(v) > 4.0) return false;
    if (std::max(std::abs(su), std::abs(sv)) < 1e-12) {
      evaluate(net, u, v, p, pu, pv);
      z = p.z;
      // A tiny step with a large residual: a singular Jacobian, not a root.
      return std::abs(p.x) <= residual && std::abs(p.y) <= residual;
    }
  }
  return false;
}

// What a node's derivative nets tell: whether (x, y) is injective on it, and the ranges of
// the (x, y) partial derivatives (in the node's own (u, v)).
struct Slopes {
  double uxlo, uxhi, uylo, uyhi, vxlo, vxhi, vylo, vyhi;
  bool injective;
};

// Injective: every ∂/∂u control vector crosses every ∂/∂v one with the same sign, so the mean
// Jacobian between two points of the node is never singular and there is at most one root.
Slopes slopes(const Net& net) {
  double dux[10], duy[10], dvx[10], dvy[10];
  int at = 0;
  for (int k = 0; k <= 3; ++k)
    for (int j = 0; j + k <= 3; ++j, ++at) {
      const P3& base = net[size_t(BezierTriangle::index(j, k))];
      const P3& pu = net[size_t(BezierTriangle::index(j + 1, k))];
      const P3& pv = net[size_t(BezierTriangle::index(j, k + 1))];
      dux[at] = 4.0 * (pu.x - base.x);
      duy[at] = 4.0 * (pu.y - base.y);
      dvx[at] = 4.0 * (pv.x - base.x);
      dvy[at] = 4.0 * (pv.y - base.y);
    }
  Slopes s{dux[0], dux[0], duy[0], duy[0], dvx[0], dvx[0], dvy[0], dvy[0], false};
  for (int a = 1; a < 10; ++a) {
    s.uxlo = std::min(s.uxlo, dux[a]);
    s.uxhi = std::max(s.uxhi, dux[a]);
    s.uylo = std::min(s.uylo, duy[a]);
    s.uyhi = std::max(s.uyhi, duy[a]);
    s.vxlo = std::min(s.vxlo, dvx[a]);
    s.vxhi = std::max(s.vxhi, dvx[a]);
    s.vylo = std::min(s.vylo, dvy[a]);
    s.vyhi = std::max(s.vyhi, dvy[a]);
  }
  // The interval of det[∂u, ∂v] over the boxes first (cheap, enough where the node is flat
  // enough), then every pair.
  const double lo = std::min({s.uxlo * s.vylo, s.uxlo * s.vyhi, s.uxhi * s.vylo, s.uxhi * s.vyhi}) -
                    std::max({s.uylo * s.vxlo, s.uylo * s.vxhi, s.uyhi * s.vxlo, s.uyhi * s.vxhi});
  const double hi = std::max({s.uxlo * s.vylo, s.uxlo * s.vyhi, s.uxhi * s.vylo, s.uxhi * s.vyhi}) -
                    std::min({s.uylo * s.vxlo, s.uylo * s.vxhi, s.uyhi * s.vxlo, s.uyhi * s.vxhi});
  if (lo > 0.0 || hi < 0.0) {
    s.injective = true;
    return s;
  }
  bool allPositive = true, allNegative = true;
  for (int a = 0; a < 10; ++a)
    for (int b = 0; b < 10; ++b) {
      const double c = dux[a] * dvy[b] - duy[a] * dvx[b];
      allPositive &= c > 0.0;
      allNegative &= c < 0.0;
      if (!allPositive && !allNegative) return s;  // both signs: not injective
    }
  s.injective = allPositive || allNegative;
  return s;
}

// The range of w·[lo, hi] for w in [−1/3, 2/3] (a node coordinate less the centroid's).
inline void offsetRange(double lo, double hi, double& outLo, double& outHi) {
  const double a = -lo / 3.0, b = 2.0 * lo / 3.0, c = -hi / 3.0, d = 2.0 * hi / 3.0;
  outLo = std::min(std::min(a, b), std::min(c, d));
  outHi = std::max(std::max(a, b), std::max(c, d));
}

struct Node {
  Net net;
  double cu[3], cv[3];  // the sub-triangle's corners in the piece's (u, v)
  double zmin;
  double extent;  // the larger side of the net's 2D box
  int depth;
  // An injective ancestor's Newton converged outside it: Newton from inside this node would most
  // likely go there again, so the node is only split (and solved at the last level).
  bool newtonWentOutside;
};

struct Box {
  double xlo, xhi, ylo, yhi, zlo, zhi;
};

Box netBox(const Net& net) {
  Box b{kInfinity, -kInfinity, kInfinity, -kInfinity, kInfinity, -kInfinity};
  for (const P3& p : net) {
    b.xlo = std::min(b.xlo, p.x);
    b.xhi = std::max(b.xhi, p.x);
    b.ylo = std::min(b.ylo, p.y);
    b.yhi = std::max(b.yhi, p.y);
    b.zlo = std::min(b.zlo, p.z);
    b.zhi = std::max(b.zhi, p.z);
  }
  return b;
}

class Tracer {
 public:
  // `up`, when given, sets the frame: t is its part perpendicular to d. A region's normal there
  // makes a ray that grazes it see a thin sliver whose 2D boxes stay thin.
  // `region`, when given, restricts the search to a sub-patch's region.
  Tracer(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double tmin, double tmax,
         Mode mode, const Vec3* up = nullptr, const BezierSubPatch* region = nullptr)
      : tmin_(tmin), tmax_(tmax), mode_(mode), region_(region) {
    const double dd = d.squaredNorm();
    const Vec3 unit = d / std::sqrt(dd);
    Vec3 s, t;
    orthonormalBasis(unit, s, t);
    if (up) {
      const Vec3 perpendicular = *up - up->dot(unit) * unit;
      const double length = perpendicular.norm();
      if (length > 1e-3 * up->norm()) {
        t = perpendicular / length;
        s = t.cross(unit);
      }
    }
    double scale = 0.0, zscale = 0.0;
    for (int i = 0; i < BezierTriangle::kPoints; ++i) {
      const Vec3 r = piece.b[size_t(i)] - o;
      root_[size_t(i)] = {r.dot(s), r.dot(t), r.dot(d) / dd};
      scale = std::max(scale, r.cwiseAbs().maxCoeff());
      zscale = std::max(zscale, std::abs(root_[size_t(i)].z));
    }
    // Rounding of the projection and of ten levels of splitting stays far below these.
    marginXY_ = 1e-11 * scale;
    residual_ = 1e-9 * scale;
    marginZ_ = 1e-11 * (zscale + scale / std::sqrt(dd));
  }

  bool valid() const { return std::isfinite(marginXY_) && std::isfinite(marginZ_); }

  // Searches the whole piece, or the region given to the constructor.
  void run(Found& found) {
    Node* stack = stack_;
    stack[0].cu[0] = 0, stack[0].cv[0] = 0;
    stack[0].cu[1] = 1, stack[0].cv[1] = 0;
    stack[0].cu[2] = 0, stack[0].cv[2] = 1;
    const int depth = region_ ? region_->depth : 0;
    if (depth > 0) {
      region_->corners(stack[0].cu, stack[0].cv);
      regionNet(root_, stack[0].cu, stack[0].cv, stack[0].net);
    } else {
      stack[0].net = root_;
    }
    // Rendering's last level is 1/1024 of the piece, whatever region the search starts from.
    const int maxDepth = mode_ == Mode::All ? kMaxDepthAll : std::max(kMaxDepthRender - depth, 4);
    const Box rootBox = netBox(stack[0].net);
    if (culled(rootBox, found) || separated(stack[0].net)) return;
    stack[0].depth = 0;
    stack[0].newtonWentOutside = false;
    stack[0].zmin = rootBox.zlo;
    stack[0].extent = std::max(rootBox.xhi - rootBox.xlo, rootBox.yhi - rootBox.ylo);
    int top = 1, visited = 0;
    while (top > 0) {
      const Node node = stack[--top];  // a copy: its children take its place on the stack
      if (node.zmin > limit(found) + marginZ_) continue;
      if (++visited > (mode_ == Mode::All ? kMaxNodesAll : kMaxNodesRender)) return;
      // A leaf at the last level, or once the net is as small as the rounding margin.
      const bool last =
          node.depth >= maxDepth || top + 2 > kStackSize || node.extent <= 4.0 * marginXY_;
      const Slopes sl = slopes(node.net);
      // F at the centre, then the mean value form: F over the node lies in
      // F(c) + [∂F/∂u]·[−1/3, 2/3] + [∂F/∂v]·[−1/3, 2/3]; no root where that excludes 0.
      double u = (node.cu[0] + node.cu[1] + node.cu[2]) / 3.0;
      double v = (node.cv[0] + node.cv[1] + node.cv[2]) / 3.0;
      P3 f, fu, fv;
      evaluate(root_, u, v, f, fu, fv);
      if (excluded(sl, f)) continue;
      bool wentOutside = node.newtonWentOutside;
      if (last || (sl.injective && !wentOutside)) {
        planarStart(node, u, v);
        if (solve(node, sl.injective, last, u, v, wentOutside, found)) {
          if (mode_ == Mode::Any && found.any) return;
          continue;
        }
        if (last) continue;
      }
      // An injective node Newton found no root in: the winding number of its boundary tells
      // whether it holds one (rendering queries; all-hits ones split as before).
      if (sl.injective && mode_ != Mode::All) {
        const RegionWinding w = netWinding(node.net, marginXY_);
        if (w == RegionWinding::Outside) continue;
        if (w == RegionWinding::Inside) wentOutside = false;  // its children try Newton again
      }
      // Bisect: the children that survive culling, the nearer pushed last (popped first).
      Node& a = stack[top];
      Node& b = stack[top + 1];
      bisect(node.net, a.net, b.net);
      const double mu = 0.5 * (node.cu[1] + node.cu[2]), mv = 0.5 * (node.cv[1] + node.cv[2]);
      a.cu[0] = b.cu[0] = mu;
      a.cv[0] = b.cv[0] = mv;
      a.cu[1] = b.cu[2] = node.cu[0];
      a.cv[1] = b.cv[2] = node.cv[0];
      a.cu[2] = node.cu[1];
      a.cv[2] = node.cv[1];
      b.cu[1] = node.cu[2];
      b.cv[1] = node.cv[2];
      a.depth = b.depth = node.depth + 1;
      a.newtonWentOutside = b.newtonWentOutside = wentOutside;
      const Box boxA = netBox(a.net), boxB = netBox(b.net);
      a.zmin = boxA.zlo;
      b.zmin = boxB.zlo;
      a.extent = std::max(boxA.xhi - boxA.xlo, boxA.yhi - boxA.ylo);
      b.extent = std::max(boxB.xhi - boxB.xlo, boxB.yhi - boxB.ylo);
      const bool keepA = !culled(boxA, found) && !separated(a.net);
      const bool keepB = !culled(boxB, found) && !separated(b.net);
      int pushed = 0;
      if (keepA && keepB) {
        if (a.zmin < b.zmin) std::swap(a, b);
        pushed = 2;
      } else if (keepA) {
        pushed = 1;
      } else if (keepB) {
        a = b;
        pushed = 1;
      }
      top += pushed;
    }
  }

 private:
  double limit(const Found& found) const {
    return mode_ == Mode::Nearest && found.any ? found.nearest.t : tmax_;
  }

  // Rendering queries: whether a line through the origin, across an edge of the net's corner
  // triangle that the origin lies beyond, has every control point on the far side (then the
  // net's convex hull excludes the origin). It culls the nodes along a region's edge that a ray
  // just outside it crosses, which the frame's boxes keep. All-hits queries stay as they were.
  bool separated(const Net& net) const {
    if (mode_ == Mode::All) return false;
    const P3* corner[3] = {&net[size_t(BezierTriangle::index(0, 0))],
                           &net[size_t(BezierTriangle::index(4, 0))],
                           &net[size_t(BezierTriangle::index(0, 4))]};
    const double area = (corner[1]->x - corner[0]->x) * (corner[2]->y - corner[0]->y) -
                        (corner[1]->y - corner[0]->y) * (corner[2]->x - corner[0]->x);
    if (!(area != 0.0)) return false;
    for (int e = 0; e < 3; ++e) {
      const P3& p = *corner[e];
      const P3& q = *corner[(e + 1) % 3];
      // The outward normal of edge p → q.
      const double nx = area > 0.0 ? q.y - p.y : p.y - q.y;
      const double ny = area > 0.0 ? p.x - q.x : q.x - p.x;
      if (!(nx * p.x + ny * p.y < 0.0)) continue;  // the origin is not beyond this edge
      const double margin = marginXY_ * (std::abs(nx) + std::abs(ny));
      bool all = true;
      for (const P3& b : net)
        if (!(nx * b.x + ny * b.y < -margin)) {
          all = false;
          break;
        }
      if (all) return true;
    }
    return false;
  }

  bool culled(const Box& b, const Found& found) const {
    return b.xlo > marginXY_ || b.xhi < -marginXY_ || b.ylo > marginXY_ || b.yhi < -marginXY_ ||
           b.zhi < tmin_ - marginZ_ || b.zlo > limit(found) + marginZ_;
  }

  bool excluded(const Slopes& s, const P3& f) const {
    double ulo, uhi, vlo, vhi;
    offsetRange(s.uxlo, s.uxhi, ulo, uhi);
    offsetRange(s.vxlo, s.vxhi, vlo, vhi);
    if (f.x + ulo + vlo > marginXY_ || f.x + uhi + vhi < -marginXY_) return true;
    offsetRange(s.uylo, s.uyhi, ulo, uhi);
    offsetRange(s.vylo, s.vyhi, vlo, vhi);
    return f.y + ulo + vlo > marginXY_ || f.y + uhi + vhi < -marginXY_;
  }

  // Barycentric coordinates of the ray (the 2D origin) in the node's corner triangle, whose
  // corners lie on the surface; false when the triangle is degenerate (its area below 1e-9 of
  // its longest side squared).
  static bool planarCoordinates(const Node& node, double& l0, double& l1, double& l2) {
    const P3& A = node.net[size_t(BezierTriangle::index(0, 0))];
    const P3& B = node.net[size_t(BezierTriangle::index(4, 0))];
    const P3& C = node.net[size_t(BezierTriangle::index(0, 4))];
    const double area = (B.x - A.x) * (C.y - A.y) - (B.y - A.y) * (C.x - A.x);
    const double side2 = std::max({(B.x - A.x) * (B.x - A.x) + (B.y - A.y) * (B.y - A.y),
                                   (C.x - A.x) * (C.x - A.x) + (C.y - A.y) * (C.y - A.y),
                                   (C.x - B.x) * (C.x - B.x) + (C.y - B.y) * (C.y - B.y)});
    if (!(std::abs(area) > 1e-9 * side2)) return false;
    l1 = ((-A.x) * (C.y - A.y) - (-A.y) * (C.x - A.x)) / area;
    l2 = ((B.x - A.x) * (-A.y) - (B.y - A.y) * (-A.x)) / area;
    l0 = 1.0 - l1 - l2;
    return std::isfinite(l1) && std::isfinite(l2);
  }

  // Newton's start in the node: where the ray crosses its corner triangle, clamped into it
  // (the centre (u, v) stays when the triangle is degenerate).
  static void planarStart(const Node& node, double& u, double& v) {
    double l0, l1, l2;
    if (!planarCoordinates(node, l0, l1, l2)) return;
    l0 = std::max(l0, 0.0), l1 = std::max(l1, 0.0), l2 = std::max(l2, 0.0);
    const double sum = l0 + l1 + l2;
    l0 /= sum, l1 /= sum, l2 /= sum;
    u = l0 * node.cu[0] + l1 * node.cu[1] + l2 * node.cu[2];
    v = l0 * node.cv[0] + l1 * node.cv[1] + l2 * node.cv[2];
  }

  // The node's barycentric coordinates of the piece's (u, v).
  static void nodeCoordinates(const Node& node, double u, double v, double& a, double& b) {
    const double e1u = node.cu[1] - node.cu[0], e1v = node.cv[1] - node.cv[0];
    const double e2u = node.cu[2] - node.cu[0], e2v = node.cv[2] - node.cv[0];
    const double ru = u - node.cu[0], rv = v - node.cv[0];
    const double det = e1u * e2v - e1v * e2u;
    a = (ru * e2v - rv * e2u) / det;
    b = (e1u * rv - e1v * ru) / det;
  }

  static bool inNode(const Node& node, double u, double v) {
    double a, b;
    nodeCoordinates(node, u, v, a, b);
    return a >= -kNodeSlack && b >= -kNodeSlack && a + b <= 1.0 + kNodeSlack;
  }

  static bool inDomain(double u, double v) {
    return u >= -kDomainSlack && v >= -kDomainSlack && u + v <= 1.0 + kDomainSlack;
  }

  // Records a root (when it is in range).
  void record(double u, double v, double t, Found& found) const {
    if (!(t > tmin_ && t < tmax_) || !inDomain(u, v)) return;
    if (mode_ == Mode::All) {
      for (int i = 0; i < found.count; ++i)
        if (std::abs(found.all[i].u - u) < kSameRoot && std::abs(found.all[i].v - v) < kSameRoot)
          return;
      if (found.count < kMaxHits) found.all[found.count++] = {t, u, v};
      found.any = true;
      return;
    }
    if (!found.any || t < found.nearest.t) found.nearest = {t, u, v};
    found.any = true;
  }

  // Newton from (u, v) in the node (`wentOutside` set when it converges outside an injective
  // one). True when the node is done: its root recorded (or
  // out of range), or, at the last level, whatever could be found. At the last level a node
  // that may fold also tries its corners, and the planar corner triangle stands in when Newton
  // finds nothing in the node.
  bool solve(const Node& node, bool injective, bool last, double u, double v, bool& wentOutside,
             Found& found) const {
    double z;
    bool inside = false;  // a root of this node was recorded
    bool convergedOutside = false;
    if (newton(root_, residual_, u, v, z)) {
      convergedOutside = !inNode(node, u, v);
      if (!convergedOutside) {
        record(u, v, z, found);
        inside = true;
        if (injective) return true;  // the node's only root
      } else {
        wentOutside = injective;
      }
    }
    if (!last) return false;
    if (!injective) {
      for (int k = 0; k < 3; ++k) {
        double cu = node.cu[k], cv = node.cv[k];
        if (newton(root_, residual_, cu, cv, z)) {
          if (inNode(node, cu, cv)) {
            record(cu, cv, z, found);
            inside = true;
          } else {
            convergedOutside = true;
          }
        }
      }
    }
    if (inside) return true;
    // Rendering queries keep a root Newton found outside the node for the node that holds it;
    // all-hits queries (crack rates) cannot risk losing one, so they take the stand-in below.
    if (convergedOutside && mode_ != Mode::All) return true;
    // Planar stand-in where Newton found no root in the node (it failed, or it went to another
    // root, as near a silhouette where the Jacobian nearly vanishes and two roots lie close): the
    // corners of the net lie on the surface, and the node is 1/1024 of the piece or less.
    double l0, l1, l2;
    if (!planarCoordinates(node, l0, l1, l2) || l0 < 0.0 || l1 < 0.0 || l2 < 0.0) return true;
    u = l0 * node.cu[0] + l1 * node.cu[1] + l2 * node.cu[2];
    v = l0 * node.cv[0] + l1 * node.cv[1] + l2 * node.cv[2];
    const P3& A = node.net[size_t(BezierTriangle::index(0, 0))];
    const P3& B = node.net[size_t(BezierTriangle::index(4, 0))];
    const P3& C = node.net[size_t(BezierTriangle::index(0, 4))];
    // Newton from the stand-in's point polishes it when it stays in the node.
    double nu = u, nv = v;
    if (newton(root_, residual_, nu, nv, z) && inNode(node, nu, nv)) {
      record(nu, nv, z, found);
      return true;
    }
    record(u, v, l0 * A.z + l1 * B.z + l2 * C.z, found);
    return true;
  }

  Net root_;
  double tmin_, tmax_;
  Mode mode_;
  const BezierSubPatch* region_;
  double marginXY_ = 0.0, marginZ_ = 0.0, residual_ = 0.0;
  Node stack_[kStackSize];
};

}  // namespace

bool bezier_detail::traceBezier(const BezierTriangle& piece, const Vec3& o, const Vec3& d,
                                double tmin, double tmax, Mode mode, Found& found, const Vec3* up,
                                const BezierSubPatch* region) {
  Tracer tracer(piece, o, d, tmin, tmax, mode, up, region);
  if (!tracer.valid()) return false;
  tracer.run(found);
  return true;
}

bool intersectBezierTriangle(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double tmin,
                             double tmax, BezierHit& hit) {
  if (!(tmin < tmax)) return false;
  Found found;
  if (!traceBezier(piece, o, d, tmin, tmax, Mode::Nearest, found) || !found.any) return false;
  hit = found.nearest;
  return true;
}

bool occludesBezierTriangle(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double tmin,
                            double tmax) {
  if (!(tmin < tmax)) return false;
  Found found;
  return traceBezier(piece, o, d, tmin, tmax, Mode::Any, found) && found.any;
}

size_t intersectBezierTriangleAll(const BezierTriangle& piece, const Vec3& o, const Vec3& d,
                                  double tmin, double tmax, std::vector<BezierHit>& hits) {
  if (!(tmin < tmax)) return 0;
  Found found;
  if (!traceBezier(piece, o, d, tmin, tmax, Mode::All, found)) return 0;
  hits.insert(hits.end(), found.all, found.all + found.count);
  return size_t(found.count);
}

}  // namespace quadtri
