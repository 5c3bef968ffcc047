#include "quadtri/surface/robust_implicit_model.h"

#include <tbb/parallel_for.h>

#include <nlohmann/json.hpp>

#include "quadtri/mesh/topology.h"
#include "quadtri/surface/robust_pencil.h"
#include "quadtri/surface/robust_quadric_fit.h"

namespace quadtri {
namespace {

// Samples per edge of the lattice that sizes the slab and the box.
constexpr int kBoundSamples = 12;

/// Data of one mesh edge that both of its patches use: the edge plane (canonical sign), the arc
/// midpoint, and the unit direction in the plane perpendicular to the chord (normals' side).
struct SharedEdge {
  Vec4 plane = Vec4::Zero();
  Vec3 arcMidpoint = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();
};

// Unit shading normal at vertex `which` of the edge, from what both sides share: the corner
// normal itself, or the normalised mean where a crease splits it.
Vec3 sharedNormal(const TriangleMesh& mesh, const Edge& edge, uint32_t which) {
  const auto cornerOf = [&](uint32_t t, uint8_t k) {
    return mesh.triangles[t][k] == which ? int(k) : (k + 1) % 3;
  };
  const auto [t0, k0] = edge.sides.front();
  const Vec3 first = mesh.cornerNormal(t0, cornerOf(t0, k0));
  Vec3 sum = Vec3::Zero();
  bool split = false;
  for (auto [t, k] : edge.sides) {
    const Vec3 n = mesh.cornerNormal(t, cornerOf(t, k));
    split |= n != first;
    sum += n;
  }
  return split ? safeNormalized(sum, first) : first;
}

SharedEdge sharedEdge(const TriangleMesh& mesh, const Edge& edge) {
  const Vec3& va = mesh.positions[edge.a];
  const Vec3& vb = mesh.positions[edge.b];
  const Vec3 na = sharedNormal(mesh, edge, edge.a);
  const Vec3 nb = sharedNormal(mesh, edge, edge.b);
  SharedEdge out;
  out.arcMidpoint = edgeArcMidpoint(va, na, vb, nb);
  const Vec3 e = vb - va;
  const double len = e.norm();
  if (!(len > 0.0)) return out;
  const Vec3 ehat = e / len;
  // The plane must contain the chord and a direction off the surface: ni+nj (thesis eq. 4.5),
  // or where that is (anti)parallel to the chord, the sides' oriented face normals.
  Vec3 up = na + nb;
  if (!(ehat.cross(up).norm() > 1e-6 * up.norm()) || !(up.norm() > 1e-6)) {
    up = Vec3::Zero();
    for (auto [t, k] : edge.sides) up += patchOrientation(mesh, t) * mesh.faceNormal(t);
  }
  Vec3 normal = ehat.cross(up);
  if (!(normal.norm() > 1e-6 * up.norm()) || !(up.norm() > 1e-6)) {
    Vec3 s, t;
    orthonormalBasis(ehat, s, t);
    normal = s;
    up = t;
  }
  normal.normalize();
  out.plane << normal, -normal.dot(va);
  out.direction = normal.cross(ehat);
  if (out.direction.dot(up) < 0.0) out.direction = -out.direction;
  return out;
}

// Largest angle between an edge plane and the bisector of its sides' faces, about the chord.
constexpr double kMaxPlaneTiltDeg = 45.0;

// Normals far from their faces (folds) can tilt the plane of ni+nj towards a side's face, which
// leaves that side a sliver of a wedge: its patch is clipped away. Turns the plane about the
// chord back to kMaxPlaneTiltDeg from the faces' bisector (a no-op on smooth data).
void keepAwayFromFaces(const TriangleMesh& mesh, const Edge& edge, SharedEdge& shared) {
  const Vec3& va = mesh.positions[edge.a];
  const Vec3 e = mesh.positions[edge.b] - va;
  if (!(e.norm() > 0.0)) return;
  const Vec3 ehat = e.normalized();
  Vec3 bisector = Vec3::Zero();
  for (auto [t, k] : edge.sides) bisector += patchOrientation(mesh, t) * mesh.faceNormal(t);
  bisector -= bisector.dot(ehat) * ehat;
  if (!(bisector.norm() > 1e-6)) return;  // a knife edge or degenerate faces: leave it
  bisector.normalize();
  Vec3 up = shared.direction - shared.direction.dot(ehat) * ehat;
  if (!(up.norm() > 0.0)) return;
  up.normalize();
  const double maxTilt = kMaxPlaneTiltDeg * kPi / 180.0;
  if (angleDegrees(up, bisector) <= kMaxPlaneTiltDeg) return;
  Vec3 across = up - up.dot(bisector) * bisector;
  across = across.norm() > 0.0 ? Vec3(across.normalized()) : ehat.cross(bisector);
  up = std::cos(maxTilt) * bisector + std::sin(maxTilt) * across;
  const Vec3 normal = ehat.cross(up).normalized();
  shared.plane << normal, -normal.dot(va);
  shared.direction = up;
}

}  // namespace

RobustImplicitModel::RobustImplicitModel(std::shared_ptr<const TriangleMesh> meshIn)
    : SurfaceModel(std::move(meshIn)) {
  const TriangleMesh& m = mesh();
  const MeshTopology topo(m);
  std::vector<SharedEdge> edges(topo.edges.size());
  tbb::parallel_for(size_t(0), edges.size(),
                    [&](size_t i) { edges[i] = sharedEdge(m, topo.edges[i]); });
  const std::vector<std::array<Vec3, 3>> controlPoints = edgeControlPoints(m);

  patches_.resize(m.triangleCount());
  frames_.resize(m.triangleCount());
  std::vector<QuadricCoeffs> pencils(m.triangleCount());
  std::vector<uint8_t> fallbacks(m.triangleCount(), 0);
  tbb::parallel_for(size_t(0), m.triangleCount(), [&](size_t t) {
    CornerData data;
    for (int k = 0; k < 3; ++k) {
      data.position[k] = m.corner(t, k);
      data.normal[k] = m.cornerNormal(t, k);
      data.arcMidpoint[k] = edges[topo.edgeOf[t][k]].arcMidpoint;
    }
    const QuadricFit fit = fitQuadric(data);
    fallbacks[t] = fit.pointFallback;
    QuadricPatch& patch = patches_[t];
    patch.q = fit.q;
    pencils[t] = fit.pencil;
    frames_[t].cornerNormalErrorDeg = fit.cornerNormalErrorDeg;
    double facing = 0.0;
    for (int k = 0; k < 3; ++k)
      facing += quadricGradient(fit.q, data.position[k]).dot(data.normal[k]);
    patch.orientation = facing < 0.0 ? -1.0 : 1.0;
    coverTriangle(quadraticPatch(m, controlPoints, t),
                  patch.orientation * m.faceNormal(t) * patchOrientation(m, t), pencils[t],
                  patch.q);
  });
  std::vector<Vec3> arcMidpoints(edges.size());
  for (size_t i = 0; i < edges.size(); ++i) arcMidpoints[i] = edges[i].arcMidpoint;
  std::vector<double> cornerErrors(m.triangleCount());
  for (size_t t = 0; t < m.triangleCount(); ++t) cornerErrors[t] = frames_[t].cornerNormalErrorDeg;
  agreeAcrossEdges(m, topo, arcMidpoints, controlPoints, pencils, cornerErrors, patches_);
  tbb::parallel_for(size_t(0), edges.size(), [&](size_t i) {
    const Edge& edge = topo.edges[i];
    if (edge.sides.size() == 2)
      alignWithCrossing(patches_[edge.sides[0].first].q, patches_[edge.sides[1].first].q,
                        m.positions[edge.a], m.positions[edge.b], edges[i].plane,
                        edges[i].direction);
    keepAwayFromFaces(m, edge, edges[i]);
  });
  tbb::parallel_for(size_t(0), m.triangleCount(), [&](size_t t) {
    Frame& frame = frames_[t];
    QuadricPatch& patch = patches_[t];
    frame.parametric = quadraticPatch(m, controlPoints, t);
    frame.faceNormal = patchOrientation(m, t) * m.faceNormal(t);
    for (int k = 0; k < 3; ++k) {
      const SharedEdge& edge = edges[topo.edgeOf[t][k]];
      frame.edgeDirection[k] = edge.direction;
      frame.edgePlane[k] = edge.plane;
      // Inside is the side of the opposite corner; the neighbour across the edge gets the
      // same plane negated (exactly), so the two partition space along the edge.
      const Vec3& opposite = m.corner(t, (k + 2) % 3);
      const double side = edge.plane.head<3>().dot(opposite) + edge.plane[3];
      patch.planes[k] = side < 0.0 ? Vec4(-edge.plane) : edge.plane;
    }
    patch.planeCount = 3;
    patch.facing = frame.faceNormal;
    clipToPatch(t);
    // Normals no quadric of the pencil follows (a fold, the teapot's knob): the quadric leaves
    // the wedge or misses the projection lines, so its patch would leave a hole. The triangle's
    // own plane, clipped by the same edge planes, is the triangle; the bridges join it to its
    // neighbours.
    if (!coversItself(t) && frame.faceNormal.squaredNorm() > 0.5) {
      patch.q.fill(0.0);
      patch.q[6] = frame.faceNormal.x();
      patch.q[7] = frame.faceNormal.y();
      patch.q[8] = frame.faceNormal.z();
      patch.q[9] = -frame.faceNormal.dot(m.corner(t, 0));
      patch.orientation = 1.0;
      frame.flat = true;
      frame.cornerNormalErrorDeg = 0.0;
      for (int k = 0; k < 3; ++k)
        frame.cornerNormalErrorDeg = std::max(frame.cornerNormalErrorDeg,
                                              angleDegrees(frame.faceNormal, m.cornerNormal(t, k)));
      clipToPatch(t);
    }
  });
  addBridges(topo);
  for (size_t t = 0; t < m.triangleCount(); ++t) fallbacks[t] |= frames_[t].flat;
  setFallbacks(std::move(fallbacks));
}

bool RobustImplicitModel::coversItself(size_t t) const {
  const TriangleMesh& m = mesh();
  const QuadricPatch& patch = patches_[t];
  const Vec3& n = frames_[t].faceNormal;
  const double scale = m.meanEdgeLength(t);
  // Lines along the face normal through the triangle's inner lattice points: each must meet
  // the clipped patch within a mean edge length of the triangle.
  constexpr int level = 6;
  for (int j = 1; j < level; ++j)
    for (int i = 1; i + j < level; ++i) {
      const double u = double(i) / level, v = double(j) / level;
      const Vec3 x = (1.0 - u - v) * m.corner(t, 0) + u * m.corner(t, 1) + v * m.corner(t, 2);
      double hit;
      if (!intersectQuadricPatch(patch, x - scale * n, n, 0.0, 2.0 * scale, hit)) return false;
    }
  return true;
}

size_t RobustImplicitModel::flatCount() const {
  size_t count = 0;
  for (const Frame& frame : frames_) count += frame.flat;
  return count;
}

void RobustImplicitModel::addBridges(const MeshTopology& topo) {
  const TriangleMesh& m = mesh();
  const Vec2 cornerUv[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  const int n = kBoundSamples;
  std::vector<QuadricPatch> bridges(topo.edges.size());
  std::vector<char> needed(topo.edges.size(), 0);
  tbb::parallel_for(size_t(0), topo.edges.size(), [&](size_t i) {
    const Edge& edge = topo.edges[i];
    if (edge.sides.size() != 2) return;
    const auto [ta, ka] = edge.sides[0];
    const auto [tb, kb] = edge.sides[1];
    const QuadricPatch& a = patches_[ta];
    const QuadricPatch& b = patches_[tb];
    const Vec3& va = m.positions[edge.a];
    const Vec3& vb = m.positions[edge.b];
    const double length = (vb - va).norm();
    if (!(length > 0.0)) return;
    // Both boundaries, sampled at the same points of the edge: evaluate starts them from the
    // shared parametric edge, in the shared plane, along the shared direction.
    const bool sameWay = m.triangles[ta][ka] == m.triangles[tb][kb];
    QuadricPatch bridge;
    double gap = 0.0;
    for (int j = 0; j <= n; ++j) {
      const double s = double(j) / n;
      const Vec2 ua = cornerUv[ka] + s * (cornerUv[(ka + 1) % 3] - cornerUv[ka]);
      const double sb = sameWay ? s : 1.0 - s;
      const Vec2 ub = cornerUv[kb] + sb * (cornerUv[(kb + 1) % 3] - cornerUv[kb]);
      const Vec3 pa = evaluate(ta, ua.x(), ua.y()).position;
      const Vec3 pb = evaluate(tb, ub.x(), ub.y()).position;
      bridge.bounds.extend(pa);
      bridge.bounds.extend(pb);
      gap = std::max(gap, (pa - pb).norm());
    }
    // Sides that meet to round-off (data from a quadric) need no bridge.
    if (!(gap > 1e-9 * length)) return;
    bridge.bounds.inflate(std::max(frames_[ta].boundsMargin, frames_[tb].boundsMargin));
    const Vec4& plane = a.planes[ka];  // its gradient points into a's side
    bridge.q.fill(0.0);
    bridge.q[6] = plane[0];
    bridge.q[7] = plane[1];
    bridge.q[8] = plane[2];
    bridge.q[9] = plane[3];
    // Near both sheets (the two slabs) and between the edge's ends, where the lens pinches.
    bridge.planes[0] = a.planes[3];
    bridge.planes[1] = a.planes[4];
    bridge.planes[2] = b.planes[3];
    bridge.planes[3] = b.planes[4];
    const Vec3 along = (vb - va) / length;
    bridge.planes[4] << along, -along.dot(va);
    bridge.planes[5] << -along, along.dot(vb);
    bridge.planeCount = 6;
    bridge.joins = {int32_t(ta), int32_t(tb)};
    bridges[i] = bridge;
    needed[i] = 1;
  });
  primitives_ = patches_;
  for (size_t i = 0; i < bridges.size(); ++i)
    if (needed[i]) primitives_.push_back(bridges[i]);
}

SurfacePoint RobustImplicitModel::evaluate(size_t t, double u, double v) const {
  const Frame& frame = frames_[t];
  const QuadricPatch& patch = patches_[t];
  const QuadricCoeffs& q = patch.q;
  // Blend the edge planes and directions with weights that are 1 on their edge and 0 on the
  // others, so boundary points start in their edge plane, move inside it and land on the
  // clipped boundary. (Corners lie on all their planes: nothing moves there.)
  const double l[3] = {1.0 - u - v, u, v};
  const double wsum = l[0] * l[1] + l[1] * l[2] + l[2] * l[0];
  Vec3 start = frame.parametric.position(u, v);
  Vec3 dir = Vec3::Zero();
  if (wsum > 0.0) {
    const Vec3 base = start;
    for (int k = 0; k < 3; ++k) {
      const double wk = l[k] * l[(k + 1) % 3] / wsum;
      const Vec4& plane = frame.edgePlane[k];
      start -= wk * (plane.head<3>().dot(base) + plane[3]) * plane.head<3>();
      dir += wk * frame.edgeDirection[k];
    }
  }
  dir = safeNormalized(dir, frame.faceNormal);
  const double a = q[0] * dir.x() * dir.x() + q[1] * dir.y() * dir.y() + q[2] * dir.z() * dir.z() +
                   q[3] * dir.x() * dir.y() + q[4] * dir.x() * dir.z() + q[5] * dir.y() * dir.z();
  const double b = quadricGradient(q, start).dot(dir);
  const double c = evalQuadric(q, start);
  // Nearest root of a s² + b s + c along the line; where the line misses the quadric, the
  // point of least |q| (the parabola's vertex).
  double s = 0.0;
  const double disc = b * b - 4.0 * a * c;
  if (std::abs(a) <= 1e-14 * std::abs(b)) {
    s = b != 0.0 ? -c / b : 0.0;
  } else if (disc < 0.0) {
    s = -b / (2.0 * a);
  } else {
    const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    const double r1 = h / a, r2 = h != 0.0 ? c / h : 0.0;
    s = std::abs(r1) < std::abs(r2) ? r1 : r2;
  }
  if (!std::isfinite(s)) {
    s = 0.0;
  }
  const Vec3 p = start + s * dir;
  return {p, safeNormalized(patch.orientation * quadricGradient(q, p), frame.faceNormal)};
}

void RobustImplicitModel::clipToPatch(size_t t) {
  const TriangleMesh& m = mesh();
  const Frame& frame = frames_[t];
  QuadricPatch& patch = patches_[t];
  const Vec3 centre = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0;
  const double scale = m.meanEdgeLength(t);
  const int n = kBoundSamples;
  std::vector<Vec3> grid;
  grid.reserve((n + 1) * (n + 2) / 2);
  const auto index = [n](int i, int j) { return size_t(j * (n + 1) - j * (j - 1) / 2 + i); };
  // The quadric's Hessian is constant (2M), so |Hessian|/|∇q| bounds the curvature.
  const QuadricCoeffs& q = patch.q;
  Mat3 hessian;
  hessian << 2 * q[0], q[3], q[4], q[3], 2 * q[1], q[5], q[4], q[5], 2 * q[2];
  const double hessianNorm = hessian.norm();
  double curvature = 0.0, hmin = kInfinity, hmax = -kInfinity;
  patch.bounds = Bounds3();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i + j <= n; ++i) {
      const SurfacePoint sp = evaluate(t, double(i) / n, double(j) / n);
      grid.push_back(sp.position);
      patch.bounds.extend(sp.position);
      const double h = frame.faceNormal.dot(sp.position - centre);
      hmin = std::min(hmin, h);
      hmax = std::max(hmax, h);
      const double g = quadricGradient(q, sp.position).norm();
      curvature = std::max(curvature, g > 0.0 ? hessianNorm / g : kInfinity);
    }
  double spacing = 0.0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i + j < n; ++i) {
      spacing = std::max(spacing, (grid[index(i + 1, j)] - grid[index(i, j)]).norm());
      spacing = std::max(spacing, (grid[index(i, j + 1)] - grid[index(i, j)]).norm());
    }
  // Between samples the patch leaves their hull by at most the sagitta κδ²/8; twice that plus
  // a round-off floor, capped where the curvature bound is meaningless (near-singular points).
  const double margin = std::min(0.25 * curvature * spacing * spacing, 0.1 * scale) + 1e-4 * scale;
  patch.bounds.inflate(margin);
  frames_[t].boundsMargin = margin;
  // The slab keeps the sheet through the corners: generous on the patch's own height range,
  // far tighter than the distance to any other sheet of a sane fit.
  // A plane has one sheet: its slab only has to hold the bridges' lenses to its neighbours.
  const double slab = frame.flat ? 0.5 * scale : 0.25 * (hmax - hmin) + margin + 0.01 * scale;
  const Vec3& nf = frame.faceNormal;
  patch.planes[3] << nf, -nf.dot(centre) - (hmin - slab);
  patch.planes[4] << -nf, nf.dot(centre) + (hmax + slab);
  patch.planeCount = 5;
}

nlohmann::json RobustImplicitModel::patchJson(size_t t) const {
  const QuadricPatch& patch = patches_[t];
  nlohmann::json j;
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = mesh().corner(t, k);
    j["vertices"].push_back({p.x(), p.y(), p.z()});
  }
  j["quadric"] = patch.q;
  j["planes"] = nlohmann::json::array();
  for (int i = 0; i < patch.planeCount; ++i) {
    const Vec4& p = patch.planes[i];
    j["planes"].push_back({p[0], p[1], p[2], p[3]});
  }
  j["bounds"] = {{"min", {patch.bounds.lo.x(), patch.bounds.lo.y(), patch.bounds.lo.z()}},
                 {"max", {patch.bounds.hi.x(), patch.bounds.hi.y(), patch.bounds.hi.z()}}};
  j["orientation"] = patch.orientation;
  j["corner_normal_error_deg"] = frames_[t].cornerNormalErrorDeg;
  j["flat"] = frames_[t].flat;
  return j;
}

}  // namespace quadtri
