#include "surface/robust_implicit_model.h"

#include <tbb/parallel_for.h>

#include <Eigen/SparseCholesky>
#include <nlohmann/json.hpp>

#include "mesh/topology.h"
#include "surface/robust_quadric_fit.h"

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

// Weight of keeping each patch's arc-midpoint member against making neighbours agree, for
// data from a quadric; it grows with the corner-normal error (1 per kCompatibleDeg) so that
// fits of generic data stay where they are: there the agreement cannot be met (their conics
// differ through the corner normals), and chasing it with a large multiple of L² brings the
// quadric's second sheet next to the patch.
constexpr double kArcWeight = 1e-2;
constexpr double kCompatibleDeg = 1e-4;

// Moves every patch along its pencil, q_t + μ_t p_t (corners and their normals do not change),
// so that neighbours pass at the same signed distance from each shared edge's arc midpoint:
// sparse least squares over all patches, rows s_a + c_a μ_a = s_b + c_b μ_b per interior edge
// (s the oriented distance q/|∇q| of the arc midpoint, c its change per unit μ) plus
// kArcWeight·|c|·μ_t per patch. Data sampled from a sphere give s = 0 everywhere and μ = 0;
// for other quadrics it keeps neighbouring multiples of L² alike, so a − κb splits into a
// real plane pair through each edge (see alignWithCrossing).
void agreeAcrossEdges(const TriangleMesh& mesh, const MeshTopology& topo,
                      const std::vector<Vec3>& arcMidpoints,
                      const std::vector<std::array<Vec3, 3>>& controlPoints,
                      const std::vector<QuadricCoeffs>& pencils,
                      const std::vector<double>& cornerNormalErrorDeg,
                      std::vector<QuadricPatch>& patches) {
  const size_t count = patches.size();
  const Eigen::Index n = Eigen::Index(count);
  // distance[t][k], change[t][k]: s and c of patch t at its edge k's arc midpoint.
  std::vector<std::array<double, 3>> distance(count), change(count);
  for (size_t t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3& m = arcMidpoints[topo.edgeOf[t][k]];
      const double g = quadricGradient(patches[t].q, m).norm();
      const double o = patches[t].orientation / (g > 0.0 ? g : 1.0);
      distance[t][k] = o * evalQuadric(patches[t].q, m);
      change[t][k] = o * evalQuadric(pencils[t], m);
    }
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  // The regulariser measures μ by how far it moves the patch anywhere (sampled on f_p), not
  // only at the arc midpoints: where those lie near the triangle's plane (inflections,
  // saddles) a large μ would leave them in place and bend the rest of the patch.
  const double samples[7][2] = {{1. / 3, 1. / 3}, {0.5, 0},         {0.5, 0.5},      {0, 0.5},
                                {1. / 6, 1. / 6}, {2. / 3, 1. / 6}, {1. / 6, 2. / 3}};
  for (size_t t = 0; t < count; ++t) {
    const QuadraticPatch fp = quadraticPatch(mesh, controlPoints, t);
    double effect = 0.0;
    for (const auto& uv : samples) {
      const Vec3 x = fp.position(uv[0], uv[1]);
      const double g = quadricGradient(patches[t].q, x).norm();
      effect = std::max(effect, std::abs(evalQuadric(pencils[t], x)) / (g > 0.0 ? g : 1.0));
    }
    for (int k = 0; k < 3; ++k) effect = std::max(effect, std::abs(change[t][k]));
    // Flat patches (L² vanishes on them): no row sees μ, so hold it at 0 explicitly.
    const double size = (mesh.corner(t, 1) - mesh.corner(t, 0)).norm() +
                        (mesh.corner(t, 2) - mesh.corner(t, 1)).norm();
    effect = std::max(effect, 1e-6 * size);
    const double weight = std::max(kArcWeight, cornerNormalErrorDeg[t] / kCompatibleDeg);
    entries.emplace_back(Eigen::Index(t), Eigen::Index(t), weight * weight * effect * effect);
  }
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    const Edge& edge = topo.edges[e];
    if (edge.sides.size() != 2) continue;
    const auto [a, ka] = edge.sides[0];
    const auto [b, kb] = edge.sides[1];
    const double ca = change[a][ka], cb = -change[b][kb], r = distance[b][kb] - distance[a][ka];
    entries.emplace_back(a, a, ca * ca);
    entries.emplace_back(b, b, cb * cb);
    entries.emplace_back(a, b, ca * cb);
    entries.emplace_back(b, a, ca * cb);
    rhs[a] += ca * r;
    rhs[b] += cb * r;
  }
  Eigen::SparseMatrix<double> normal(n, n);
  normal.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success) return;
  const Eigen::VectorXd mu = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !mu.allFinite()) return;
  for (size_t t = 0; t < count; ++t) {
    QuadricCoeffs& q = patches[t].q;
    double norm2 = 0.0;
    for (int i = 0; i < 10; ++i) {
      q[i] += mu[Eigen::Index(t)] * pencils[t][i];
      norm2 += q[i] * q[i];
    }
    for (double& c : q) c /= std::sqrt(norm2);
  }
}

// Where the fitted member leaves part of the triangle uncovered (some line along the face
// normal n through f_p misses it, or meets it facing away), replaces it by the member of the
// pencil whose quadratic form vanishes along n: a graph over the triangle's plane, which every
// such line meets exactly once. Only fits of normals that no quadric comes near need this
// (coarse, strongly curved or inconsistent data, as on the teapot); it keeps (1) and (2).
void coverTriangle(const QuadraticPatch& parametric, const Vec3& n, const QuadricCoeffs& pencil,
                   QuadricCoeffs& q) {
  const auto alongNormal = [&n](const QuadricCoeffs& c) {
    return c[0] * n.x() * n.x() + c[1] * n.y() * n.y() + c[2] * n.z() * n.z() +
           c[3] * n.x() * n.y() + c[4] * n.x() * n.z() + c[5] * n.y() * n.z();
  };
  constexpr int kSteps = 6;
  bool covered = true;
  for (int j = 0; j <= kSteps && covered; ++j)
    for (int i = 0; i + j <= kSteps && covered; ++i) {
      const Vec3 x = parametric.position(double(i) / kSteps, double(j) / kSteps);
      const double a = alongNormal(q), b = quadricGradient(q, x).dot(n), c = evalQuadric(q, x);
      const double disc = b * b - 4.0 * a * c;
      if (disc < 0.0) {
        covered = false;
        break;
      }
      // The root nearest to f_p and the orientation of the surface there.
      const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      double s = std::abs(a) > 1e-14 * std::abs(b) ? h / a : 0.0;
      if (h != 0.0 && std::abs(c / h) < std::abs(s)) s = c / h;
      covered = quadricGradient(q, x + s * n).dot(n) > 0.0;
    }
  const double ap = alongNormal(pencil);
  if (covered || !(std::abs(ap) > 0.0)) return;
  const double lambda = -alongNormal(q) / ap;
  double norm2 = 0.0;
  for (int i = 0; i < 10; ++i) {
    q[i] += lambda * pencil[i];
    norm2 += q[i] * q[i];
  }
  for (double& c : q) c /= std::sqrt(norm2);
}

Mat3 quadraticPart(const QuadricCoeffs& q) {
  Mat3 m;
  m << q[0], 0.5 * q[3], 0.5 * q[4], 0.5 * q[3], q[1], 0.5 * q[5], 0.5 * q[4], 0.5 * q[5], q[2];
  return m;
}

// Replaces the edge plane by a plane through the chord that contains the curve where the two
// neighbours' quadrics a and b meet, so both patches end on the same curve. Both contain the
// chord's endpoints with (nearly) the same tangent planes, so a − κb (κ matching their
// gradients at the chord's midpoint c) vanishes to second order at c; in the plane through c
// perpendicular to the chord its zero set is a line pair through c, and the separator is the
// line closer to the edge plane's direction d. For data from any quadric the fits are that
// quadric plus multiples of L_A² and L_B², a − b is exactly a plane pair through the edge, and
// the neighbours meet exactly on the separator; otherwise they meet on it to second order.
void alignWithCrossing(const QuadricCoeffs& a, const QuadricCoeffs& b, const Vec3& va,
                       const Vec3& vb, SharedEdge& edge) {
  const Vec3 c = 0.5 * (va + vb);
  const Vec3 ga = quadricGradient(a, c), gb = quadricGradient(b, c);
  if (!(gb.squaredNorm() > 0.0)) return;
  const double kappa = ga.dot(gb) / gb.squaredNorm();
  const Mat3 ma = quadraticPart(a);
  const Mat3 md = ma - kappa * quadraticPart(b);
  // The same quadric on both sides (sphere data), or two planes (a crease between flat
  // faces): any plane through the edge is exact; keep P.
  const double len = (vb - va).norm();
  if (!(md.norm() > 1e-9 * ma.norm()) || !(md.norm() * len > 1e-9 * ga.norm())) return;
  const Vec3 ehat = (vb - va) / len;
  const Vec3 d = edge.direction, w = ehat.cross(d);
  const double a20 = d.dot(md * d), a11 = 2.0 * d.dot(md * w), a02 = w.dot(md * w);
  const double disc = a11 * a11 - 4.0 * a02 * a20;
  if (disc < 0.0) return;  // a − κb is definite there: the quadrics touch only along the chord
  // The root of a02 t² + a11 t + a20 = 0 of least |t| (stable form); direction d + t w.
  const double den = a11 + std::copysign(std::sqrt(disc), a11);
  const double t = den != 0.0 ? -2.0 * a20 / den : 0.0;
  if (!std::isfinite(t)) return;
  Vec3 normal = ehat.cross(d + t * w).normalized();
  if (normal.dot(edge.plane.head<3>()) < 0.0) normal = -normal;
  // Tilting the separator far from the edge plane would reorder the wedges around a vertex.
  if (normal.dot(edge.plane.head<3>()) < std::cos(kPi / 6)) return;
  edge.plane << normal, -normal.dot(va);
  const Vec3 up = edge.direction;
  edge.direction = normal.cross(ehat);
  if (edge.direction.dot(up) < 0.0) edge.direction = -edge.direction;
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
  tbb::parallel_for(size_t(0), m.triangleCount(), [&](size_t t) {
    CornerData data;
    for (int k = 0; k < 3; ++k) {
      data.position[k] = m.corner(t, k);
      data.normal[k] = m.cornerNormal(t, k);
      data.arcMidpoint[k] = edges[topo.edgeOf[t][k]].arcMidpoint;
    }
    const QuadricFit fit = fitQuadric(data);
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
                        m.positions[edge.a], m.positions[edge.b], edges[i]);
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
    clipToPatch(t);
  });
}

SurfacePoint RobustImplicitModel::project(size_t t, double u, double v, bool& onQuadric) const {
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
  onQuadric = true;
  const double disc = b * b - 4.0 * a * c;
  if (std::abs(a) <= 1e-14 * std::abs(b)) {
    s = b != 0.0 ? -c / b : 0.0;
  } else if (disc < 0.0) {
    onQuadric = false;
    s = -b / (2.0 * a);
  } else {
    const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    const double r1 = h / a, r2 = h != 0.0 ? c / h : 0.0;
    s = std::abs(r1) < std::abs(r2) ? r1 : r2;
  }
  if (!std::isfinite(s)) {
    onQuadric = false;
    s = 0.0;
  }
  const Vec3 p = start + s * dir;
  return {p, safeNormalized(patch.orientation * quadricGradient(q, p), frame.faceNormal)};
}

SurfacePoint RobustImplicitModel::evaluate(size_t t, double u, double v) const {
  bool onQuadric = true;
  return project(t, u, v, onQuadric);
}

void RobustImplicitModel::clipToPatch(size_t t) {
  const TriangleMesh& m = mesh();
  const Frame& frame = frames_[t];
  QuadricPatch& patch = patches_[t];
  const Vec3 centre = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0;
  const double scale =
      ((m.corner(t, 1) - m.corner(t, 0)).norm() + (m.corner(t, 2) - m.corner(t, 1)).norm() +
       (m.corner(t, 0) - m.corner(t, 2)).norm()) /
      3.0;
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
      bool onQuadric = true;
      const SurfacePoint sp = project(t, double(i) / n, double(j) / n, onQuadric);
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
  const double margin = std::min(0.25 * curvature * spacing * spacing, scale) + 1e-4 * scale;
  patch.bounds.inflate(margin);
  // The slab keeps the sheet through the corners: generous on the patch's own height range,
  // far tighter than the distance to any other sheet of a sane fit.
  const double slab = 0.25 * (hmax - hmin) + margin + 0.01 * scale;
  const Vec3& nf = frame.faceNormal;
  patch.planes[3] << nf, -nf.dot(centre) - (hmin - slab);
  patch.planes[4] << -nf, nf.dot(centre) + (hmax + slab);
  patch.planeCount = 5;
}

nlohmann::json RobustImplicitModel::patchJson(size_t t) const {
  const QuadricPatch& patch = patches_[t];
  nlohmann::json j;
  j["quadric"] = patch.q;
  for (int i = 0; i < patch.planeCount; ++i) {
    const Vec4& p = patch.planes[i];
    j["planes"].push_back({p[0], p[1], p[2], p[3]});
  }
  j["bounds"] = {{"lo", {patch.bounds.lo.x(), patch.bounds.lo.y(), patch.bounds.lo.z()}},
                 {"hi", {patch.bounds.hi.x(), patch.bounds.hi.y(), patch.bounds.hi.z()}}};
  j["orientation"] = patch.orientation;
  j["corner_normal_error_deg"] = frames_[t].cornerNormalErrorDeg;
  return j;
}

}  // namespace quadtri
