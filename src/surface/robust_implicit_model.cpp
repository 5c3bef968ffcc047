#include "quadtri/surface/robust_implicit_model.h"

#include <array>

#include "quadtri/math/frame_origin.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/mesh/winding.h"
#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"
#include "quadtri/surface/robust_pencil.h"
#include "quadtri/surface/robust_quadric_fit.h"
#include "robust_overlap.h"

namespace quadtri {
namespace {

/// Data of one mesh edge that both of its patches use: the edge plane (canonical sign), the arc
/// midpoint, and the unit direction in the plane perpendicular to the chord (normals' side).
struct SharedEdge {
  Vec4 plane = Vec4::Zero();
  Vec3 arcMidpoint = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();
  bool crease = false;  ///< the sides' corner normals differ at either end
};

// Unit shading normal at vertex `which` of the edge, from what both sides share: the corner
// normal itself, or the normalised mean where a crease splits it (`split` set then).
Vec3 sharedNormal(const TriangleMesh& mesh, const Edge& edge, uint32_t which, bool& split) {
  const auto cornerOf = [&](uint32_t t, uint8_t k) {
    return mesh.triangles[t][k] == which ? int(k) : (k + 1) % 3;
  };
  const auto [t0, k0] = edge.sides.front();
  const Vec3 first = mesh.cornerNormal(t0, cornerOf(t0, k0));
  Vec3 sum = Vec3::Zero();
  split = false;
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
  bool splitA = false, splitB = false;
  const Vec3 na = sharedNormal(mesh, edge, edge.a, splitA);
  const Vec3 nb = sharedNormal(mesh, edge, edge.b, splitB);
  SharedEdge out;
  out.crease = splitA || splitB;
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

// Largest angle between an edge plane and the bisector of its sides' faces, about the chord,
// and the least angle between the plane and either face.
constexpr double kMaxPlaneTiltDeg = 45.0;
constexpr double kLeastFaceAngleDeg = 10.0;

// The edge plane must separate its two triangles (each cell's section by its triangle's plane
// is then the triangle) and keep away from both: folds tilt the plane of ni+nj towards a face,
// or past it. About the chord, the planes that separate the two faces are those between the
// faces' half-planes (the dihedral angle δ); this turns the plane back into the part of that
// range at least min(kLeastFaceAngleDeg, δ/4) from both faces and within kMaxPlaneTiltDeg of
// its bisector (a no-op on smooth data). Uses the triangles' corners only, not their normals
// or winding. A boundary edge's plane keeps away from its one face.
void keepAwayFromFaces(const TriangleMesh& mesh, const Edge& edge, SharedEdge& shared) {
  if (edge.sides.empty() || edge.sides.size() > 2) return;
  const Vec3& va = mesh.positions[edge.a];
  const Vec3 e = mesh.positions[edge.b] - va;
  if (!(e.norm() > 0.0)) return;
  const Vec3 ehat = e.normalized();
  // Unit directions from the chord into each face, perpendicular to the chord.
  std::array<Vec3, 2> into;
  for (size_t i = 0; i < edge.sides.size(); ++i) {
    const auto [t, k] = edge.sides[i];
    const Vec3 r = mesh.corner(t, (k + 2) % 3) - va;
    const Vec3 perp = r - r.dot(ehat) * ehat;
    if (!(perp.norm() > 1e-12 * r.norm()) || !(perp.norm() > 0.0)) return;  // degenerate face
    into[i] = perp.normalized();
  }
  const Vec3 x = into[0];
  Vec3 y = ehat.cross(x);
  // The separating planes make angles ψ in (0, δ) with the first face, about the chord.
  double delta = 180.0;
  if (edge.sides.size() == 2) {
    delta = std::atan2(into[1].dot(y), into[1].dot(x)) * 180.0 / kPi;
    if (delta < 0.0) {
      y = -y;
      delta = -delta;
    }
    if (!(delta > 1e-9)) return;  // a knife edge: the faces coincide
  }
  const double margin = std::min(kLeastFaceAngleDeg, 0.25 * delta);
  const double lo = std::max(margin, 0.5 * delta - kMaxPlaneTiltDeg);
  const double hi = std::min(delta - margin, 0.5 * delta + kMaxPlaneTiltDeg);
  Vec3 up = shared.direction - shared.direction.dot(ehat) * ehat;
  if (!(up.norm() > 0.0))
    up = std::cos(0.5 * delta * kPi / 180.0) * x + std::sin(0.5 * delta * kPi / 180.0) * y;
  up.normalize();
  // The plane's angle ψ in [0, 180) (a plane through the chord is a line about it).
  double psi = std::atan2(up.dot(y), up.dot(x)) * 180.0 / kPi;
  if (psi < 0.0) psi += 180.0;
  if (psi >= 180.0) psi -= 180.0;
  if (psi >= lo && psi <= hi) return;
  // The nearer end of [lo, hi], measured around the 180° circle of planes.
  const auto gap = [](double a, double b) {
    const double d = std::fmod(std::abs(a - b), 180.0);
    return std::min(d, 180.0 - d);
  };
  const double target = gap(psi, lo) <= gap(psi, hi) ? lo : hi;
  Vec3 turned = std::cos(target * kPi / 180.0) * x + std::sin(target * kPi / 180.0) * y;
  if (turned.dot(shared.direction) < 0.0) turned = -turned;
  const Vec3 normal = ehat.cross(turned).normalized();
  shared.plane << normal, -normal.dot(va);
  shared.direction = turned;
}

// Per triangle, +1 or -1: the side of its face normal (v1−v0)×(v2−v0) its patch faces. Each
// connected part of the mesh (across edges with two sides) is oriented consistently from its
// topology, flipping triangles whose winding disagrees with their neighbours', and then as a
// whole to the side most shading normals point to: a closed part says where its inside is, and
// every triangle must agree about it, whatever its own normals say. A part that cannot be
// oriented (non-orientable, or edges with more sides) lets each triangle's own normals decide
// (patchOrientation).
std::vector<double> faceSides(const TriangleMesh& mesh, const MeshTopology& topo,
                              const WindingParts& w) {
  std::vector<char> manifold(mesh.triangleCount(), 1);
  for (const Edge& edge : topo.edges)
    if (edge.sides.size() > 2)
      for (auto [t, k] : edge.sides) manifold[t] = 0;
  std::vector<double> side(mesh.triangleCount(), 1.0);
  for (size_t p = 0; p < w.parts.size(); ++p) {
    const std::vector<uint32_t>& part = w.parts[p];
    bool ok = w.orientable[p] != 0;
    double vote = 0.0;
    for (uint32_t t : part) {
      ok &= manifold[t] != 0;
      const Vec3 ns = mesh.cornerNormal(t, 0) + mesh.cornerNormal(t, 1) + mesh.cornerNormal(t, 2);
      vote += w.relative[t] * mesh.faceCross(t).dot(ns);
    }
    const double sign = vote < 0.0 ? -1.0 : 1.0;
    for (uint32_t t : part) side[t] = ok ? sign * w.relative[t] : patchOrientation(mesh, t);
  }
  return side;
}

// Corner-normal error (degrees) under which a fit counts as exact (data from a quadric).
constexpr double kAlignBelowDeg = 1e-6;

// Rounds of shrinking overlapping cells (each halves their reach).
constexpr int kOverlapRounds = 8;

// The plane n·(x − o) + d ≥ 0 as n·x + d' ≥ 0 (a plane and its exact negation stay exact
// negations).
Vec4 translatedPlane(const Vec4& plane, const Vec3& o) {
  if (plane == Vec4::Zero()) return plane;
  return Vec4(plane[0], plane[1], plane[2], plane[3] - plane.head<3>().dot(o));
}

}  // namespace

RobustImplicitModel::RobustImplicitModel(std::shared_ptr<const TriangleMesh> meshIn)
    : SurfaceModel(std::move(meshIn)) {
  // Far from the world origin (frameOrigin) the construction runs on the mesh moved by
  // −origin, and its results are moved back once it is done (translateToWorld): there the
  // quadrics' terms grow with the square of the distance and cancel, and the construction's
  // checks, solves and moves along pencils lost what the patch's own size needs (a mesh a unit
  // across at 10^3: corners off by 9e-3 of an edge; at 10^5 a fifth of the patches planes).
  const Vec3 origin = frameOrigin(mesh().bounds());
  TriangleMesh moved;
  if (origin != Vec3::Zero()) {
    moved.positions.resize(mesh().positions.size());
    parallelFor(size_t(0), moved.positions.size(),
                [&](size_t i) { moved.positions[i] = mesh().positions[i] - origin; });
    moved.triangles = mesh().triangles;
    moved.normals = mesh().normals;
    moved.normalIndices = mesh().normalIndices;
    construction_ = &moved;
    worldOrigin_ = origin;
  }
  construct(mesh().topology());
  construction_ = nullptr;
  worldOrigin_ = Vec3::Zero();
  if (origin != Vec3::Zero()) translateToWorld(origin);
}

void RobustImplicitModel::translateToWorld(const Vec3& origin) {
  parallelFor(size_t(0), patches_.size(), [&](size_t i) {
    QuadricPatch& patch = patches_[i];
    patch.q = translatedQuadric(patch.q, origin);
    for (int k = 0; k < patch.planeCount; ++k)
      patch.planes[size_t(k)] = translatedPlane(patch.planes[size_t(k)], origin);
    patch.base = translatedPlane(patch.base, origin);
    if (patch.bounds.empty()) return;
    patch.bounds.lo += origin;
    patch.bounds.hi += origin;
    // The boxes clip the surface exactly (the ray test checks its roots against them), so they
    // take the margin of world coordinates that the construction gives a box (1e-10 of the
    // distance from the origin it saw, near 0 here), or a patch thin along an axis rejects its
    // own hits, rounded to world coordinates.
    patch.bounds.inflate(1e-10 * std::max(patch.bounds.lo.cwiseAbs().maxCoeff(),
                                          patch.bounds.hi.cwiseAbs().maxCoeff()));
  });
  parallelFor(size_t(0), frames_.size(), [&](size_t t) {
    for (Vec3& b : frames_[t].controlPoints) b += origin;
  });
}

void RobustImplicitModel::construct(const MeshTopology& topo) {
  const TriangleMesh& m = geometry();
  std::vector<SharedEdge> edges(topo.edges.size());
  parallelFor(size_t(0), edges.size(), [&](size_t i) { edges[i] = sharedEdge(m, topo.edges[i]); });
  std::vector<std::array<Vec3, 3>> controlPoints = edgeControlPoints(m, topo);

  // Room for a bridge per edge too (addBridges), so that appending them never moves the
  // patches; only the patches' part is mapped now, and addBridges maps what its bridges fill,
  // so the room of edges without a bridge (every edge, on data from a quadric) is never
  // resident.
  reserveLarge(patches_, m.triangleCount() + topo.edges.size(), m.triangleCount());
  patches_.resize(m.triangleCount());
  resizeLarge(frames_, m.triangleCount());
  std::vector<QuadricCoeffs> pencils = largeVector<QuadricCoeffs>(m.triangleCount());
  std::vector<uint8_t> fallbacks(m.triangleCount(), 0);
  parallelFor(size_t(0), m.triangleCount(), [&](size_t t) {
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
  parallelFor(size_t(0), edges.size(), [&](size_t i) {
    const Edge& edge = topo.edges[i];
    // Data from a quadric only (both fits corner-exact): there the plane through the crossing
    // makes the neighbours meet exactly. On generic data it would tilt planes by up to 30° for
    // a second-order agreement, and at a sliver's sharp corner two such tilts make its two long
    // edge planes cross close to the surface, where its neighbours' cells then overlap.
    if (edge.sides.size() == 2 &&
        frames_[edge.sides[0].first].cornerNormalErrorDeg < kAlignBelowDeg &&
        frames_[edge.sides[1].first].cornerNormalErrorDeg < kAlignBelowDeg)
      alignWithCrossing(patches_[edge.sides[0].first].q, patches_[edge.sides[1].first].q,
                        m.positions[edge.a], m.positions[edge.b], edges[i].plane,
                        edges[i].direction);
    keepAwayFromFaces(m, edge, edges[i]);
  });
  const WindingParts windings = windingParts(m, topo);
  const std::vector<double> sides = faceSides(m, topo, windings);
  std::vector<uint32_t> part(m.triangleCount(), 0);
  for (size_t p = 0; p < windings.parts.size(); ++p)
    for (uint32_t t : windings.parts[p]) part[t] = uint32_t(p);
  std::vector<CellSummary> cells = largeVector<CellSummary>(m.triangleCount());
  parallelFor(size_t(0), m.triangleCount(), [&](size_t t) {
    Frame& frame = frames_[t];
    QuadricPatch& patch = patches_[t];
    frame.controlPoints = controlPoints[t];
    frame.faceNormal = sides[t] * m.faceNormal(t);
    for (int k = 0; k < 3; ++k) {
      const SharedEdge& edge = edges[topo.edgeOf[t][k]];
      frame.edgeDirection[k] = edge.direction;
      frame.crease[k] = edge.crease;
      // Inside is the side of the opposite corner; the neighbour across the edge gets the
      // same plane negated (exactly).
      const Vec3& opposite = m.corner(t, (k + 2) % 3);
      const double side = edge.plane.head<3>().dot(opposite) + edge.plane[3];
      patch.planes[k] = side < 0.0 ? Vec4(-edge.plane) : edge.plane;
    }
    patch.planeCount = 3;
  });
  // What only the steps above read goes before the rounds, the conversion's peak (at a million
  // triangles: the shared edges 144 MB, the control points 72 MB, the arc midpoints 36 MB).
  std::vector<SharedEdge>().swap(edges);
  std::vector<std::array<Vec3, 3>>().swap(controlPoints);
  std::vector<Vec3>().swap(arcMidpoints);
  std::vector<double>().swap(cornerErrors);
  // The fits (moved along their pencils), kept for the rounds below.
  std::vector<QuadricCoeffs> fitted = largeVector<QuadricCoeffs>(m.triangleCount());
  for (size_t t = 0; t < m.triangleCount(); ++t) fitted[t] = patches_[t].q;
  std::vector<double> reach(m.triangleCount(), kInfinity);
  std::vector<char> redo(m.triangleCount(), 1);
  // A triangle's core: its cell cut down to the heights of its patch and of the region between
  // the patch and the triangle (what the patch and its bridges can reach). Only its box is kept
  // (coreBoxes); overlappingCells builds the core again for the rare pairs whose boxes meet.
  const auto core = [&](size_t t) {
    if (cells[t].empty()) return ConvexCell();
    const Frame& frame = frames_[t];
    const QuadricPatch& patch = patches_[t];
    const Vec3& n = frame.faceNormal;
    const double h = n.dot((m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0);
    FixedVector<Vec4, 5> planes(patch.planes.begin(), patch.planes.begin() + 3);
    planes.push_back(Vec4(n.x(), n.y(), n.z(), -h - frame.coreLo));
    planes.push_back(Vec4(-n.x(), -n.y(), -n.z(), h + frame.coreHi));
    return makeConvexCell(planes, cells[t].tolerance);
  };
  std::vector<Bounds3> coreBoxes = largeVector<Bounds3>(m.triangleCount());
  // A triangle's flat core: its cell cut down to a slab of 1e-6 of its size around it. Only
  // the rare pairs whose cores overlap need one, so it is built there, not kept for every
  // triangle.
  const auto flatCore = [&](size_t t) {
    if (cells[t].empty()) return ConvexCell();
    const QuadricPatch& patch = patches_[t];
    const Vec3& n = frames_[t].faceNormal;
    const double h = n.dot((m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0);
    const double thin = 1e-6 * m.meanEdgeLength(t);
    FixedVector<Vec4, 5> planes(patch.planes.begin(), patch.planes.begin() + 3);
    planes.push_back(Vec4(n.x(), n.y(), n.z(), -h + thin));
    planes.push_back(Vec4(-n.x(), -n.y(), -n.z(), h + thin));
    return makeConvexCell(planes, cells[t].tolerance);
  };
  // Cells of triangles that share no vertex must not overlap (thin parts, such as a plate
  // thinner than its triangles: a sheet of one side would otherwise reach through the other's):
  // each round halves the reach of the cells that do, and chooses their patches again.
  for (int round = 0; round < kOverlapRounds; ++round) {
    parallelFor(size_t(0), m.triangleCount(), [&](size_t t) {
      if (redo[t]) cells[t] = chooseAndSummarise(t, fitted[t], pencils[t], reach[t]);
    });
    // The cores' boxes: only those of the patches chosen again change.
    parallelFor(size_t(0), m.triangleCount(), [&](size_t t) {
      if (redo[t]) coreBoxes[t] = core(t).bounds();
    });
    // The first half of the rounds shrinks only the farther-reaching patch of each pair (often
    // enough to part them), the rest both, as before.
    std::vector<Vec3> faceNormals(m.triangleCount());
    std::vector<double> reaches(m.triangleCount());
    for (size_t t = 0; t < m.triangleCount(); ++t) {
      faceNormals[t] = frames_[t].faceNormal;
      reaches[t] = frames_[t].reach;
    }
    const std::vector<char> overlapping =
        robust_overlap::overlappingCells(m, coreBoxes, core, flatCore, faceNormals, part, reaches,
                                         redo, round >= kOverlapRounds / 2);
    bool any = false;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
      redo[t] = overlapping[t];
      if (overlapping[t]) reach[t] = 0.5 * frames_[t].reach;
      any |= overlapping[t];
    }
    if (!any) break;
  }
  // What only the rounds read goes before the bridges, the conversion's peak (at a million
  // triangles the fits and their pencils 160 MB, the cores' boxes 48 MB).
  std::vector<QuadricCoeffs>().swap(fitted);
  std::vector<QuadricCoeffs>().swap(pencils);
  std::vector<Bounds3>().swap(coreBoxes);
  std::vector<double>().swap(reach);
  std::vector<char>().swap(redo);
  addBridges(topo, cells);
  // Fell back: gave up the corner normals (blended, or the triangle's plane), or the triangle
  // has no extent.
  for (size_t t = 0; t < m.triangleCount(); ++t)
    fallbacks[t] |= frames_[t].flat || frames_[t].blend > 0.0;
  setFallbacks(std::move(fallbacks));
}

RobustImplicitModel::CellSummary RobustImplicitModel::chooseAndSummarise(
    size_t t, const QuadricCoeffs& fitted, const QuadricCoeffs& pencil, double reach) {
  ConvexCell cell;
  choosePatch(t, fitted, pencil, reach, cell);
  CellSummary summary;
  if (cell.empty()) return summary;
  summary.tolerance = cell.tolerance;
  summary.hasCell = true;
  const QuadricPatch& patch = patches_[t];
  if (patch.base != Vec4::Zero())
    for (int k = 0; k < 3; ++k)
      summary.faceBoxes[size_t(k)] =
          betweenBoundsOnFace(patch.q, patch.orientation, patch.base, cell, k);
  return summary;
}

void RobustImplicitModel::addBridges(const MeshTopology& topo,
                                     const std::vector<CellSummary>& cells) {
  const TriangleMesh& m = geometry();
  // Each edge's bridge box (empty: no bridge), found in parallel; the bridges are then
  // appended to the patches in edge order, into storage reserved for every edge at the start.
  std::vector<Bounds3> boxes = largeVector<Bounds3>(topo.edges.size());
  parallelFor(size_t(0), topo.edges.size(), [&](size_t i) {
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
    const Vec4& plane = a.planes[ka];  // its gradient points into a's side
    // Sides whose regions between sheet and base meet the plane identically (data from a
    // quadric: the same conic, the same base line and side) need no bridge.
    Vec3 u, w;
    orthonormalBasis(plane.head<3>(), u, w);
    const Vec3 o = 0.5 * (va + vb);
    const auto conic = [&](const QuadricPatch& p) {
      const QuadricCoeffs& q = p.q;
      const Mat3 M = quadraticPart(q);
      const Vec3 g = quadricGradient(q, o);
      Eigen::Matrix<double, 6, 1> c;
      c << u.dot(M * u) * length * length, 2.0 * u.dot(M * w) * length * length,
          w.dot(M * w) * length * length, g.dot(u) * length, g.dot(w) * length, evalQuadric(q, o);
      c *= p.orientation;
      return Eigen::Matrix<double, 6, 1>(c.normalized());
    };
    const Vec3 off = o + length * (plane.head<3>().cross(vb - va).normalized());
    const bool sameBaseSide = (a.base.head<3>().dot(off) + a.base[3] < 0.0) ==
                              (b.base.head<3>().dot(off) + b.base[3] < 0.0);
    if (a.base != Vec4::Zero() && b.base != Vec4::Zero() && sameBaseSide &&
        (conic(a) - conic(b)).norm() < 1e-9)
      return;
    Bounds3 box;
    box.extend(cells[ta].faceBoxes[ka]);
    box.extend(cells[tb].faceBoxes[kb]);
    if (box.empty()) return;  // both sheets lie on their bases along this face
    box.inflate(1e-7 * std::max(m.meanEdgeLength(ta), m.meanEdgeLength(tb)) +
                1e-10 * (length + o.norm()));
    boxes[i] = box;
  });
  size_t bridges = 0;
  for (const Bounds3& box : boxes) bridges += !box.empty();
  prefaultLarge(patches_.data() + patches_.size(), bridges * sizeof(QuadricPatch));
  for (size_t i = 0; i < boxes.size(); ++i) {
    if (boxes[i].empty()) continue;
    const auto [ta, ka] = topo.edges[i].sides[0];
    const auto [tb, kb] = topo.edges[i].sides[1];
    const Vec4& plane = patches_[ta].planes[ka];
    QuadricPatch bridge;
    bridge.q.fill(0.0);
    bridge.q[6] = plane[0];
    bridge.q[7] = plane[1];
    bridge.q[8] = plane[2];
    bridge.q[9] = plane[3];
    bridge.bounds = boxes[i];
    bridge.planeCount = 0;
    bridge.joins = {int32_t(ta), int32_t(tb)};
    bridge.joinPlanes = {int8_t(ka), int8_t(kb)};
    patches_.push_back(bridge);
  }
}

SurfacePoint RobustImplicitModel::evaluate(size_t t, double u, double v) const {
  const Vec3 p = position(t, u, v);
  return {p, safeNormalized(patches_[t].orientation * quadricGradient(patches_[t].q, p),
                            frames_[t].faceNormal)};
}

Vec3 RobustImplicitModel::position(size_t t, double u, double v) const {
  return liftOnto(patches_[t].q, liftLine(t, u, v));
}

RobustImplicitModel::LiftLine RobustImplicitModel::liftLine(size_t t, double u, double v) const {
  const TriangleMesh& m = mesh();
  const QuadraticPatch parametric{{m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)},
                                  frames_[t].controlPoints};
  return liftLineOn(parametric, patches_[t], frames_[t], u, v);
}

RobustImplicitModel::LiftLine RobustImplicitModel::liftLineOn(const QuadraticPatch& parametric,
                                                              const QuadricPatch& patch,
                                                              const Frame& frame, double u,
                                                              double v) {
  // Blend the edge planes and directions with weights that are 1 on their edge and 0 on the
  // others, so boundary points start in their edge plane, move inside it and land on the
  // clipped boundary. (Corners lie on all their planes: nothing moves there.)
  const double l[3] = {1.0 - u - v, u, v};
  const double wsum = l[0] * l[1] + l[1] * l[2] + l[2] * l[0];
  Vec3 start = parametric.position(u, v);
  Vec3 dir = Vec3::Zero();
  if (wsum > 0.0) {
    const Vec3 base = start;
    for (int k = 0; k < 3; ++k) {
      const double wk = l[k] * l[(k + 1) % 3] / wsum;
      // The edge's plane, either way round: the patch's clip plane k (only its sign differs
      // from the edge's, and the step below is the same, bit for bit, for either sign).
      const Vec4& plane = patch.planes[size_t(k)];
      start -= wk * (plane.head<3>().dot(base) + plane[3]) * plane.head<3>();
      dir += wk * frame.edgeDirection[k];
    }
  }
  return {start, safeNormalized(dir, frame.faceNormal)};
}

void RobustImplicitModel::heightLattice(size_t t, HeightLattice& lattice) const {
  const TriangleMesh& m = geometry();
  const QuadraticPatch parametric{{m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)},
                                  frames_[t].controlPoints};
  size_t at = 0;
  for (int j = 0; j <= kHeightSamples; ++j)
    for (int i = 0; i + j <= kHeightSamples; ++i)
      lattice[at++] = liftLineOn(parametric, patches_[t], frames_[t], double(i) / kHeightSamples,
                                 double(j) / kHeightSamples);
}

Vec3 RobustImplicitModel::liftOnto(const QuadricCoeffs& q, const LiftLine& line) {
  const Vec3& start = line.start;
  const Vec3& dir = line.dir;
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
  return start + s * dir;
}

void RobustImplicitModel::patchRecord(size_t t, PatchRecord& out) const {
  const QuadricPatch& patch = patches_[t];
  const PatchRecord::Ref root = PatchRecord::kRoot;
  addVertices(mesh(), t, out);
  addQuadricPatch(patch, out);
  out.set(root, "corner_normal_error_deg", frames_[t].cornerNormalErrorDeg);
  out.setBool(root, "flat", frames_[t].flat);
  out.set(root, "blend", frames_[t].blend);
  out.set(root, "base", patch.base.data(), 4);
}

}  // namespace quadtri
