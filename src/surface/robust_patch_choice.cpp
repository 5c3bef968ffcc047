// quadric-implicit-robust, patch by patch (DESIGN §3.7): which quadric of a triangle's pencil
// becomes its patch (the fit, a graph member, or the flat fallback), and the checks a
// candidate must pass. The construction of the whole model, its bridges and its evaluation are
// in robust_implicit_model.cpp.
#include <algorithm>
#include <cmath>

#include "quadtri/surface/robust_implicit_model.h"
#include "quadtri/surface/robust_pencil.h"
#include "quadtri/surface/robust_quadric_fit.h"

namespace quadtri {
namespace {

// Blends of the corner normals towards the face normal tried before the flat plane.
constexpr double kBlends[] = {0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 0.95};

// The quadratic form of c along n.
double alongNormal(const QuadricCoeffs& c, const Vec3& n) {
  return c[0] * n.x() * n.x() + c[1] * n.y() * n.y() + c[2] * n.z() * n.z() + c[3] * n.x() * n.y() +
         c[4] * n.x() * n.z() + c[5] * n.y() * n.z();
}

// The member q + λ·pencil whose quadratic form vanishes along n (a graph over the triangle's
// plane); false where the pencil has no such member.
bool graphMember(const QuadricCoeffs& pencil, const Vec3& n, QuadricCoeffs& q) {
  const double ap = alongNormal(pencil, n), aq = alongNormal(q, n);
  if (!(std::abs(ap) > 0.0) || aq == 0.0) return false;
  double norm2 = 0.0;
  for (int i = 0; i < 10; ++i) {
    q[i] -= (aq / ap) * pencil[i];
    norm2 += q[i] * q[i];
  }
  if (!(norm2 > 0.0) || !std::isfinite(norm2)) return false;
  for (double& c : q) c /= std::sqrt(norm2);
  return true;
}

// Members q + μ·(G/ℓ)·L² of a candidate's pencil tried before blending its normals (G the mean
// length of ∇q at the corners, ℓ the mean edge length): a sheet h above the triangle's plane
// moves by about μ·h²/ℓ, both ways, near the candidate and near its graph member. L² and its
// gradient vanish on the triangle's plane, so the corners and their normals stay.
constexpr double kSquareSteps[] = {0.5, -0.5, 2.0, -2.0, 8.0, -8.0};
constexpr double kMaxSquareRise = 0.25;

// q + λ·pencil at unit coefficient norm; false where that vanishes or overflows.
bool addSquare(const QuadricCoeffs& q, const QuadricCoeffs& pencil, double lambda,
               QuadricCoeffs& out) {
  double norm2 = 0.0;
  for (int i = 0; i < 10; ++i) {
    out[i] = q[i] + lambda * pencil[i];
    norm2 += out[i] * out[i];
  }
  if (!(norm2 > 0.0) || !std::isfinite(norm2)) return false;
  for (double& c : out) c /= std::sqrt(norm2);
  return true;
}

// How far a patch may rise above or sink below its triangle, in units of the triangle's least
// altitude (twice its area over its longest edge), or of the largest sagitta of its edges' arcs.
constexpr double kMaxRise = 0.5;
constexpr double kMaxArcRise = 2.0;

// A mesh far from the world origin is built near it and its patches moved back
// (RobustImplicitModel::translateToWorld), where their coefficients are rounded in world
// coordinates: a quadric whose corners that rounding moves by more than this share of a mean
// edge is not kept (its triangle then falls back, to its plane at last, which moves exactly).
constexpr double kStoredCornerTolerance = 1e-3;

// A sliver's cell is capped at a corner sharper than kCapBelowDeg whose two edge planes meet in
// a line within asin(0.5) = 30° of the triangle's plane; the cap lies kCapOffset mean edges
// beyond the corner.
constexpr double kCapBelowDeg = 15.0;
constexpr double kCapBelowSine = 0.5;
constexpr double kCapOffset = 1e-3;

// Whether the segment o + s·d, s in [0, length], enters or leaves the cell through the plane
// of a crease edge at a point between the sheet and the triangle's plane: there the edge's
// bridge, not the sheet, is the surface the segment meets.
bool crossesCreaseBridge(const QuadricPatch& patch, const std::array<bool, 3>& crease,
                         const Vec3& o, const Vec3& d, double length) {
  double s0 = 0.0, s1 = length;
  int in = -1, out = -1;
  for (int k = 0; k < patch.planeCount; ++k) {
    const double slope = patch.planes[k].head<3>().dot(d);
    const double value = patch.planes[k].head<3>().dot(o) + patch.planes[k][3];
    if (slope == 0.0) {
      if (value < 0.0) return false;
      continue;
    }
    const double s = -value / slope;
    if (slope > 0.0 && s > s0) {
      s0 = s;
      in = k;
    } else if (slope < 0.0 && s < s1) {
      s1 = s;
      out = k;
    }
  }
  if (!(s0 < s1)) return false;
  const auto bridged = [&](int k, double s) {
    return k >= 0 && k < 3 && crease[size_t(k)] && betweenSheetAndBase(patch, o + s * d, k);
  };
  return bridged(in, s0) || bridged(out, s1);
}

}  // namespace

bool RobustImplicitModel::tryQuadric(size_t t, const QuadricCoeffs& q, const HeightLattice& lattice,
                                     double reach, ConvexCell& cell) {
  const TriangleMesh& m = geometry();
  Frame& frame = frames_[t];
  QuadricPatch& patch = patches_[t];
  const Vec3& n = frame.faceNormal;
  double facing = 0.0;
  for (int k = 0; k < 3; ++k) facing += quadricGradient(q, m.corner(t, k)).dot(n);
  if (!(std::abs(facing) > 0.0) || !std::isfinite(facing)) return false;
  if (worldOrigin_ != Vec3::Zero()) {
    const QuadricCoeffs stored = translatedQuadric(q, worldOrigin_);
    for (int k = 0; k < 3; ++k)
      if (!(quadricRootError(stored, m.corner(t, k) + worldOrigin_,
                             quadricGradient(q, m.corner(t, k)).norm()) <=
            kStoredCornerTolerance * m.meanEdgeLength(t)))
        return false;
  }
  patch.q = q;
  patch.orientation = facing < 0.0 ? -1.0 : 1.0;
  const Vec3 centre = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0;
  patch.base << n, -n.dot(centre);
  const double scale = m.meanEdgeLength(t);
  const double tolerance = 1e-10 * (scale + centre.norm());

  // Heights of the patch over its triangle, sampled.
  double hmin = 0.0, hmax = 0.0;
  for (const LiftLine& line : lattice) {
    const Vec3 p = liftOnto(q, line);
    hmin = std::min(hmin, n.dot(p - centre));
    hmax = std::max(hmax, n.dot(p - centre));
  }
  // No farther from the triangle than a share of its least altitude: fits to normals that no
  // surface near the triangle has (averaged across a sharp edge, on a sliver) bulge far out,
  // into other parts of the mesh.
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (m.corner(t, (k + 1) % 3) - m.corner(t, k)).norm());
  const double altitude = m.faceCross(t).norm() / longest;
  // Or no farther than twice the rise of its edges' arcs: what the corner normals themselves
  // say of the surface over a sliver, whose altitude is no measure of it (slivers along a
  // curved direction, such as the teapot's at its poles, rise more than half their altitude).
  // Normals averaged across a sharp edge are nearly perpendicular to the edge's chord, so that
  // arc stays low and the check still holds their bulges back.
  double sagitta = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Vec3& a = m.corner(t, k);
    const Vec3& b = m.corner(t, (k + 1) % 3);
    const Vec3 arc = edgeArcMidpoint(a, m.cornerNormal(t, k), b, m.cornerNormal(t, (k + 1) % 3));
    sagitta = std::max(sagitta, (arc - 0.5 * (a + b)).norm());
  }
  const double allowed = std::max(kMaxRise * altitude, kMaxArcRise * sagitta);
  if (!(std::max(hmax, -hmin) <= allowed)) return false;

  // A cap at a sharp corner whose two edge planes meet in a line close to the triangle's
  // plane: their wedge there runs on past the corner, nearly along the triangle, over the
  // cells of the triangles around that corner, where the surface the patch continues leaves
  // the slab. The cap (through the corner, across the corner's bisector) ends the cell there.
  int planeCount = 5;
  {
    int corner = -1;
    double shallowest = kCapBelowSine;
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = m.corner(t, k);
      if (!(angleDegrees(m.corner(t, (k + 1) % 3) - v, m.corner(t, (k + 2) % 3) - v) <
            kCapBelowDeg))
        continue;
      const Vec3 line = patch.planes[k].head<3>().cross(patch.planes[(k + 2) % 3].head<3>());
      const double sine = line.norm() > 1e-12 ? std::abs(line.normalized().dot(n)) : 0.0;
      if (sine < shallowest) {
        shallowest = sine;
        corner = k;
      }
    }
    if (corner >= 0) {
      const Vec3& v = m.corner(t, corner);
      const Vec3 inward = safeNormalized(safeNormalized(m.corner(t, (corner + 1) % 3) - v, n) +
                                             safeNormalized(m.corner(t, (corner + 2) % 3) - v, n),
                                         n);
      patch.planes[5] << inward, -inward.dot(v) + kCapOffset * scale;
      planeCount = 6;
    }
  }

  // The slab around the sampled heights, as tight as the exact checks below allow (a larger
  // cell only makes the gradient check harder): grown fourfold while the sheet leaves it.
  for (int attempt = 0; attempt < 5; ++attempt) {
    const double slab = (0.05 * (hmax - hmin) + 1e-3 * scale) * std::pow(4.0, attempt);
    const double lo = hmin - slab, hi = hmax + slab;
    patch.planes[3] << n, -n.dot(centre) - lo;
    patch.planes[4] << -n, n.dot(centre) + hi;
    patch.planeCount = planeCount;
    cell = makeConvexCell({patch.planes.begin(), patch.planes.begin() + planeCount}, tolerance);
    if (cell.vertices.size() < 4 || cell.overflowed) return false;
    // One sheet, a graph over the triangle's plane: orientation·∇q·n is positive wherever the
    // quadric vanishes in the cell. (Along a line parallel to n a quadric's two roots have
    // opposite slopes, so each such line then meets it at most once.) orientation·∇q·n is
    // linear in x: the part of the cell where it is at most a small margin is a convex cell,
    // in which the quadric must have no zero.
    double gmax = 0.0;
    for (const Vec3& v : cell.vertices) gmax = std::max(gmax, quadricGradient(q, v).norm());
    {
      // orientation·(2Mx + g)·n <= margin, as a plane m·x + d >= 0.
      const Mat3 M = quadraticPart(q);
      const Vec3 slope = -patch.orientation * 2.0 * (M * n);
      const double offset = -patch.orientation * Vec3(q[6], q[7], q[8]).dot(n) + 1e-3 * gmax;
      bool folded = false;
      if (slope.norm() > 1e-12 * gmax) {
        FixedVector<Vec4, ConvexCell::kMaxPlanes> planes(patch.planes.begin(),
                                                         patch.planes.begin() + planeCount);
        planes.push_back(Vec4(slope.x(), slope.y(), slope.z(), offset) / slope.norm());
        const ConvexCell turned = makeConvexCell(planes, tolerance);
        // A cell too degenerate to hold its vertices proves nothing: taken as folded.
        folded = turned.overflowed || (!turned.empty() && !quadricBoundsInCell(q, turned).empty());
      } else {
        folded = !(offset < 0.0);  // orientation·∇q·n is constant: it must exceed the margin
      }
      if (folded) return false;
    }
    // Inside the slab: orientation·q < 0 on all of its lower face, > 0 on all of its upper one.
    const double eps = 1e-9 * scale * gmax;
    const auto [lowLo, lowHi] = quadricRangeOnFace(q, cell, 3);
    const auto [upLo, upHi] = quadricRangeOnFace(q, cell, 4);
    const bool lowOk = patch.orientation > 0.0 ? lowHi < -eps : lowLo > eps;
    const bool upOk = patch.orientation > 0.0 ? upLo > eps : upHi < -eps;
    if (!lowOk || !upOk) continue;
    patch.bounds = quadricBoundsInCell(q, cell);
    if (patch.bounds.empty()) return false;
    // The core: the heights of the sheet and of the region between it and the triangle.
    const auto [sLo, sHi] = quadricRangeInCell(q, cell, n);
    frame.coreLo = std::min(0.0, sLo - n.dot(centre)) - 1e-6 * scale;
    frame.coreHi = std::max(0.0, sHi - n.dot(centre)) + 1e-6 * scale;
    frame.reach = std::max(-frame.coreLo, frame.coreHi);
    if (!(frame.reach <= reach)) return false;
    patch.bounds.inflate(1e-7 * scale + tolerance);
    // Covers its triangle: lines along the face normal through the triangle's inner lattice
    // points meet it within a mean edge length, or, next to a crease, meet the bridge on the
    // crease's edge plane (the two sides' arcs cross that plane: DESIGN §3.7 (h3)).
    constexpr int level = 6;
    for (int j = 1; j < level; ++j)
      for (int i = 1; i + j < level; ++i) {
        const double u = double(i) / level, v = double(j) / level;
        const Vec3 x = (1.0 - u - v) * m.corner(t, 0) + u * m.corner(t, 1) + v * m.corner(t, 2);
        double hit;
        if (!intersectQuadricPatch(patch, x - scale * n, n, 0.0, 2.0 * scale, hit) &&
            !crossesCreaseBridge(patch, frame.crease, x - scale * n, n, 2.0 * scale))
          return false;
      }
    return true;
  }
  return false;
}

void RobustImplicitModel::makeFlat(size_t t, double reach, ConvexCell& cell) {
  const TriangleMesh& m = geometry();
  Frame& frame = frames_[t];
  QuadricPatch& patch = patches_[t];
  const Vec3& n = frame.faceNormal;
  const Vec3 centre = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0;
  const double scale = m.meanEdgeLength(t);
  const double tolerance = 1e-10 * (scale + centre.norm());
  frame.flat = true;
  frame.blend = 1.0;
  patch.orientation = 1.0;
  patch.q.fill(0.0);
  // A triangle without area (or extent) has no plane: it stands for nothing (no base), and
  // its flat triangle has no area either.
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (m.corner(t, (k + 1) % 3) - m.corner(t, k)).norm());
  const bool degenerate = !(m.faceCross(t).norm() > 1e-10 * longest * longest);
  patch.base = Vec4::Zero();
  frame.reach = 1e-6 * scale;
  frame.coreLo = -frame.reach;
  frame.coreHi = frame.reach;
  const double slab = 0.01 * scale;
  patch.planes[3] << n, -n.dot(centre) + slab;
  patch.planes[4] << -n, n.dot(centre) + slab;
  patch.planeCount = 5;
  patch.bounds = Bounds3();
  for (int k = 0; k < 3; ++k) patch.bounds.extend(m.corner(t, k));
  patch.bounds.inflate(1e-7 * scale + tolerance);
  cell = ConvexCell();
  if (degenerate) return;
  // The plane and the base are the same numbers, so the region between them is empty.
  patch.q[6] = n.x();
  patch.q[7] = n.y();
  patch.q[8] = n.z();
  patch.q[9] = -n.dot(centre);
  patch.base << n, -n.dot(centre);
  cell = makeConvexCell({patch.planes.begin(), patch.planes.begin() + 5}, tolerance);
  const Bounds3 exact = quadricBoundsInCell(patch.q, cell);
  if (!exact.empty()) {
    patch.bounds = exact;
    patch.bounds.inflate(1e-7 * scale + tolerance);
  }
}

void RobustImplicitModel::choosePatch(size_t t, const QuadricCoeffs& fitted,
                                      const QuadricCoeffs& pencil, double reach, ConvexCell& cell) {
  const TriangleMesh& m = geometry();
  Frame& frame = frames_[t];
  const Vec3& n = frame.faceNormal;
  frame.flat = false;
  frame.blend = 0.0;
  const auto finish = [&](double blend) {
    frame.blend = blend;
    const QuadricPatch& patch = patches_[t];
    frame.cornerNormalErrorDeg = 0.0;
    for (int k = 0; k < 3; ++k)
      frame.cornerNormalErrorDeg =
          std::max(frame.cornerNormalErrorDeg,
                   angleDegrees(patch.orientation * quadricGradient(patch.q, m.corner(t, k)),
                                m.cornerNormal(t, k)));
  };
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (m.corner(t, (k + 1) % 3) - m.corner(t, k)).norm());
  if (m.faceCross(t).norm() > 1e-10 * longest * longest) {
    // The largest angle between a quadric's oriented gradient and the corner normals.
    const auto cornerError = [&](const QuadricCoeffs& q) {
      double facing = 0.0;
      for (int k = 0; k < 3; ++k) facing += quadricGradient(q, m.corner(t, k)).dot(n);
      const double orientation = facing < 0.0 ? -1.0 : 1.0;
      double error = 0.0;
      for (int k = 0; k < 3; ++k)
        error = std::max(error, angleDegrees(orientation * quadricGradient(q, m.corner(t, k)),
                                             m.cornerNormal(t, k)));
      return error;
    };
    const double scale = m.meanEdgeLength(t);
    HeightLattice lattice;
    heightLattice(t, lattice);
    // A candidate, then members of its pencil: its graph member, then, with `square` given,
    // q + μ·(G/ℓ)·L² around both, the one found left in `square`. L² keeps the corners and, in
    // exact arithmetic, their gradients; a member whose corner normals come out worse by more
    // than 1e-6° (the pencil's round-off on slivers, or a member dominated by it that turns a
    // corner's gradient over) is not kept.
    enum class Found { None, Candidate, Square };
    const auto tryPencil = [&](const QuadricCoeffs& q, const QuadricCoeffs& squareOfPlane,
                               QuadricCoeffs* square) {
      if (tryQuadric(t, q, lattice, reach, cell)) return Found::Candidate;
      const double error = cornerError(q) + 1e-6;
      const auto keep = [&](const QuadricCoeffs& member) {
        return cornerError(member) <= error && tryQuadric(t, member, lattice, reach, cell);
      };
      QuadricCoeffs graph = q;
      const bool hasGraph = graphMember(squareOfPlane, n, graph);
      if (hasGraph && keep(graph)) return Found::Candidate;
      const double ap = alongNormal(squareOfPlane, n);
      if (!square || !(std::abs(ap) > 0.0)) return Found::None;
      const auto unit = [&](const QuadricCoeffs& c) {
        double g = 0.0;
        for (int k = 0; k < 3; ++k) g += quadricGradient(c, m.corner(t, k)).norm();
        return g / (3.0 * scale * ap);
      };
      const double unitFit = unit(q), unitGraph = hasGraph ? unit(graph) : 0.0;
      // A member moved this way rises no farther than a quarter of a mean edge: the steps
      // lift sheets the fit's own checks let rise further (a stray-sheet bound of its own).
      const double squareReach = std::min(reach, kMaxSquareRise * scale);
      const auto keepSquare = [&](const QuadricCoeffs& member) {
        return cornerError(member) <= error && tryQuadric(t, member, lattice, squareReach, cell);
      };
      for (double step : kSquareSteps) {
        if (addSquare(q, squareOfPlane, step * unitFit, *square) && keepSquare(*square))
          return Found::Square;
        if (hasGraph && addSquare(graph, squareOfPlane, step * unitGraph, *square) &&
            keepSquare(*square))
          return Found::Square;
      }
      return Found::None;
    };
    // The fit (moved along its pencil by the mesh-wide steps) and its pencil.
    QuadricCoeffs square;
    const Found found = tryPencil(fitted, pencil, &square);
    if (found == Found::Candidate) return finish(0.0);
    const double squareError = found == Found::Square ? cornerError(square) : 0.0;
    // Corner normals blended towards the face normal: corners stay exact, the normals move
    // as little as the checks allow. Where a member q + μL² of the fit passed, the first blend
    // that passes replaces it only if its corner normals come closer to the shading normals
    // (normals no quadric comes near, whose blends agree with the data better than the fit).
    for (double blend : kBlends) {
      CornerData data;
      for (int k = 0; k < 3; ++k) {
        data.position[k] = m.corner(t, k);
        data.normal[k] = safeNormalized((1.0 - blend) * m.cornerNormal(t, k) + blend * n, n);
      }
      for (int k = 0; k < 3; ++k)
        data.arcMidpoint[k] = edgeArcMidpoint(data.position[k], data.normal[k],
                                              data.position[(k + 1) % 3], data.normal[(k + 1) % 3]);
      const QuadricFit fit = fitQuadric(data);
      if (tryPencil(fit.q, fit.pencil, nullptr) == Found::None) continue;
      if (found != Found::Square || cornerError(patches_[t].q) < squareError) return finish(blend);
      break;
    }
    if (found == Found::Square &&
        tryQuadric(t, square, lattice, std::min(reach, kMaxSquareRise * m.meanEdgeLength(t)), cell))
      return finish(0.0);
  }
  makeFlat(t, reach, cell);
  finish(1.0);
}

size_t RobustImplicitModel::flatCount() const {
  size_t count = 0;
  for (const Frame& frame : frames_) count += frame.flat;
  return count;
}

size_t RobustImplicitModel::blendedCount() const {
  size_t count = 0;
  for (const Frame& frame : frames_) count += !frame.flat && frame.blend > 0.0;
  return count;
}

}  // namespace quadtri
