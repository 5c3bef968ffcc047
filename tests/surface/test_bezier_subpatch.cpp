// The sub-patches rendering traces in place of whole Bézier pieces: they tile each piece, their
// boxes, prisms and derivative cones hold what they claim (checked by dense sampling), and their
// hits are the whole-piece intersector's.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "fixtures/bezier_pieces.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/surface/bezier_intersect.h"

namespace quadtri {
namespace {

using fixtures::bumpyPiece;
using fixtures::paraboloidPiece;

// Curved pieces: bumpy height fields (some strongly), paraboloids, and a piece of the unit sphere
// (the quartic interpolating it), as the G1 model's pieces of a coarse mesh.
std::vector<BezierTriangle> curvedPieces() {
  Pcg32 rng(41);
  std::vector<BezierTriangle> pieces;
  for (int i = 0; i < 12; ++i) {
    const double amplitude = i < 6 ? 0.1 : 0.5;
    BezierTriangle piece = bumpyPiece(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), amplitude, rng);
    for (Vec3& b : piece.b) b.head<2>() += 0.1 * Vec2(rng.nextDouble(), rng.nextDouble());
    pieces.push_back(piece);
  }
  pieces.push_back(paraboloidPiece(Vec2(-1, -1), Vec2(1.5, -1), Vec2(-1, 1.5)));
  pieces.push_back(paraboloidPiece(Vec2(0.2, 0.1), Vec2(2.5, 0.3), Vec2(0.5, 2.0)));
  // Slivers along a diagonal (as CAD meshes have), whose boxes only bisection shrinks.
  for (int i = 0; i < 2; ++i) {
    BezierTriangle sliver =
        bumpyPiece(Vec3(0, 0, 0), Vec3(2.0, 1.5, 1.0 + i), Vec3(0.05, 0.12, -0.03), 0.02, rng);
    pieces.push_back(sliver);
  }
  // A degenerate piece: corner 2 collapsed onto corner 0.
  BezierTriangle collapsed = bumpyPiece(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 0.2, rng);
  for (int k = 0; k <= 4; ++k)
    collapsed.b[size_t(BezierTriangle::index(0, k))] =
        collapsed.b[size_t(BezierTriangle::index(0, 0))];
  pieces.push_back(collapsed);
  for (size_t i = 0; i < pieces.size(); ++i) pieces[i].triangle = uint32_t(i);
  return pieces;
}

// The piece's (u, v) at the sub-patch's own barycentric (a, b).
Vec2 pieceUV(const BezierSubPatch& s, double a, double b) {
  double cu[3], cv[3];
  s.corners(cu, cv);
  return Vec2(cu[0] + a * (cu[1] - cu[0]) + b * (cu[2] - cu[0]),
              cv[0] + a * (cv[1] - cv[0]) + b * (cv[2] - cv[0]));
}

Vec3 vec(const float* f) {
  return Vec3(f[0], f[1], f[2]);
}

// The half-angle of a cone stored as its sine (2: no cone, 90°).
double coneAngle(float sinCone) {
  return std::asin(std::min(1.0, double(sinCone)));
}

// A random unit direction across the unit `axis`.
Vec3 sideways(const Vec3& axis, Pcg32& rng) {
  return safeNormalized(axis.cross(uniformDirection(rng)));
}

// The direction `angle` from the unit `axis` towards `side` (across it), times `sign`.
Vec3 tilted(const Vec3& axis, const Vec3& side, double angle, double sign) {
  return sign * (std::cos(angle) * axis + std::sin(angle) * side);
}

TEST(BezierSubPatch, RegionsTileEveryPiece) {
  const std::vector<BezierTriangle> pieces = curvedPieces();
  const std::vector<BezierSubPatch> subs = bezierSubPatches(pieces);
  std::vector<double> area(pieces.size(), 0.0);
  std::vector<int> count(pieces.size(), 0);
  for (const BezierSubPatch& s : subs) {
    ASSERT_LT(s.piece, pieces.size());
    EXPECT_LE(int(s.depth), BezierSubPatch::kMaxDepth);
    double cu[3], cv[3];
    s.corners(cu, cv);
    const double a = 0.5 * ((cu[1] - cu[0]) * (cv[2] - cv[0]) - (cv[1] - cv[0]) * (cu[2] - cu[0]));
    EXPECT_DOUBLE_EQ(a, 0.5 / double(1 << s.depth));  // positive: the piece's orientation
    area[s.piece] += a;
    ++count[s.piece];
  }
  for (size_t p = 0; p < pieces.size(); ++p) {
    EXPECT_NEAR(area[p], 0.5, 1e-15) << p;
    EXPECT_GE(count[p], 1) << p;
  }
  // The strongly curved pieces are split, the slivers bisected (an odd depth), and the
  // degenerate one to the last level.
  EXPECT_GT(subs.size(), 4 * pieces.size());
  int bisected = 0;
  for (const BezierSubPatch& s : subs) bisected += s.depth % 2;
  EXPECT_GT(bisected, 0);
  int deepest = 0;
  for (const BezierSubPatch& s : subs)
    if (s.piece == pieces.size() - 1) deepest = std::max(deepest, int(s.depth));
  EXPECT_GE(deepest, BezierSubPatch::kMaxDepth - 1);
  // A budget bounds the count: an even share each first (4: one 4-split or up to three
  // bisections), then what the pieces that needed less left over goes to those that needed
  // more. The regions still tile every piece.
  const size_t budget = 4 * pieces.size() + 3;
  const std::vector<BezierSubPatch> few = bezierSubPatches(pieces, 10.0, budget);
  EXPECT_LE(few.size(), budget);
  EXPECT_GT(few.size(), pieces.size());
  std::vector<double> fewArea(pieces.size(), 0.0);
  std::vector<int> fewCount(pieces.size(), 0);
  for (const BezierSubPatch& s : few) {
    fewArea[s.piece] += 0.5 / double(1 << s.depth);
    ++fewCount[s.piece];
  }
  for (size_t p = 0; p < pieces.size(); ++p) EXPECT_DOUBLE_EQ(fewArea[p], 0.5) << p;
  const int least = *std::min_element(fewCount.begin(), fewCount.end());
  const int most = *std::max_element(fewCount.begin(), fewCount.end());
  EXPECT_LT(least, 4);
  EXPECT_GT(most, 4);
  // A budget below the pieces (a mesh past the cap) leaves each piece one region, itself whole,
  // in piece order.
  // Each is the record the budgeted split gives a piece it leaves whole (with a cone so wide
  // that only the boxes split some).
  const std::vector<BezierSubPatch> whole = bezierSubPatches(pieces, 10.0, pieces.size() / 2);
  const std::vector<BezierSubPatch> wide = bezierSubPatches(pieces, 89.0, 8 * pieces.size());
  ASSERT_EQ(whole.size(), pieces.size());
  size_t compared = 0;
  for (size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(whole[i].piece, i);
    EXPECT_EQ(whole[i].depth, 0);
  }
  for (const BezierSubPatch& s : wide) {
    if (s.depth != 0) continue;
    ++compared;
    const BezierSubPatch& w = whole[s.piece];
    const auto same = [](const auto& a, const auto& b) {
      return std::memcmp(&a, &b, sizeof(a)) == 0;
    };
    EXPECT_TRUE(same(s.p0, w.p0) && same(s.n, w.n) && same(s.g1, w.g1) && same(s.g2, w.g2) &&
                same(s.hlo, w.hlo) && same(s.hhi, w.hhi) && same(s.lmin, w.lmin) &&
                same(s.inverseSize, w.inverseSize) && same(s.axis, w.axis) &&
                same(s.sinCone, w.sinCone) && same(s.parentAxis, w.parentAxis) &&
                same(s.parentSinCone, w.parentSinCone) && same(s.lo, w.lo) && same(s.hi, w.hi) &&
                same(s.cu, w.cu) && same(s.cv, w.cv) && same(s.parentU, w.parentU) &&
                same(s.parentV, w.parentV))
        << s.piece;
  }
  EXPECT_GT(compared, 0u);
  // The result is the same whatever the threads did, and on one thread.
  const std::vector<BezierSubPatch> again = [&] {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    return bezierSubPatches(pieces);
  }();
  ASSERT_EQ(again.size(), subs.size());
  for (size_t i = 0; i < subs.size(); ++i) {
    EXPECT_EQ(again[i].piece, subs[i].piece);
    EXPECT_EQ(again[i].depth, subs[i].depth);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(again[i].cu[c], subs[i].cu[c]);
      EXPECT_EQ(again[i].cv[c], subs[i].cv[c]);
    }
  }
  // Each region's corners are the piece's points: corner 0 is the prism's base.
  for (const BezierSubPatch& s : subs) {
    if (s.sinCone > 1.0) continue;
    const Vec2 uv = pieceUV(s, 0.0, 0.0);
    const Vec3 p0 = pieces[s.piece].position(uv.x(), uv.y());
    EXPECT_NEAR((p0 - s.p0).norm(), 0.0, 1e-12);
  }
}

TEST(BezierSubPatch, BoxAndPrismHoldEveryPointOfTheRegion) {
  const std::vector<BezierTriangle> pieces = curvedPieces();
  const std::vector<BezierSubPatch> subs = bezierSubPatches(pieces);
  constexpr int kSteps = 24;
  for (const BezierSubPatch& s : subs) {
    const BezierTriangle& piece = pieces[s.piece];
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; i + j <= kSteps; ++j) {
        const Vec2 uv = pieceUV(s, double(i) / kSteps, double(j) / kSteps);
        const Vec3 p = piece.position(uv.x(), uv.y());
        EXPECT_TRUE((p.array() >= s.bounds().lo.array() - 1e-12).all() &&
                    (p.array() <= s.bounds().hi.array() + 1e-12).all())
            << s.piece << " " << i << " " << j;
        const Vec3 r = p - s.p0;
        const double h = r.dot(vec(s.n)), l1 = r.dot(vec(s.g1)), l2 = r.dot(vec(s.g2));
        EXPECT_GE(h, s.hlo);
        EXPECT_LE(h, s.hhi);
        EXPECT_GE(l1, s.lmin[1]);
        EXPECT_GE(l2, s.lmin[2]);
        EXPECT_GE(1.0 - l1 - l2, s.lmin[0]);
      }
  }
}

// The regions do not depend on where the pieces are: moved a million units, the same pieces
// split into the same regions (their float boxes are relative to the corner p0, so they stay as
// tight as at the origin, where world-coordinate floats snapped them to a 0.0625 grid and the
// budget went on splitting regions whose boxes would not shrink), and each box still holds its
// region.
TEST(BezierSubPatch, RegionsAreTheSameFarFromTheOrigin) {
  const std::vector<BezierTriangle> pieces = curvedPieces();
  std::vector<BezierTriangle> moved = pieces;
  const Vec3 offset(1e6, -1e6, 5e5);
  for (BezierTriangle& piece : moved)
    for (Vec3& b : piece.b) b += offset;
  const std::vector<BezierSubPatch> near = bezierSubPatches(pieces);
  const std::vector<BezierSubPatch> far = bezierSubPatches(moved);
  ASSERT_EQ(near.size(), far.size());
  for (size_t i = 0; i < near.size(); ++i) {
    EXPECT_EQ(near[i].piece, far[i].piece) << i;
    EXPECT_EQ(near[i].depth, far[i].depth) << i;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(near[i].cu[c], far[i].cu[c]) << i;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(near[i].cv[c], far[i].cv[c]) << i;
    const Bounds3 a = near[i].bounds(), b = far[i].bounds();
    EXPECT_LT(((b.hi - b.lo) - (a.hi - a.lo)).cwiseAbs().maxCoeff(), 1e-6) << i;
    if (far[i].depth != 0) continue;  // a whole piece: its box holds its control points
    for (const Vec3& p : moved[far[i].piece].b) {
      EXPECT_TRUE((p.array() >= b.lo.array()).all() && (p.array() <= b.hi.array()).all()) << i;
    }
  }
}

TEST(BezierSubPatch, ConeCertifiesOneSignOfTheProjectedJacobian) {
  const std::vector<BezierTriangle> pieces = curvedPieces();
  const std::vector<BezierSubPatch> subs = bezierSubPatches(pieces);
  Pcg32 rng(43);
  int certified = 0;
  constexpr int kSteps = 12;
  for (const BezierSubPatch& s : subs) {
    if (s.sinCone > 1.0) continue;
    const BezierTriangle& piece = pieces[s.piece];
    for (int r = 0; r < 8; ++r) {
      // Directions just inside the cone's complement, where the fast path trusts it.
      // The angle to the axis: just below 90° less the cone's half-angle.
      const double angle = 0.5 * kPi - coneAngle(s.sinCone) - 0.01 * rng.nextDouble();
      if (angle <= 0.0) continue;
      const Vec3 axis = vec(s.axis).normalized();
      const Vec3 d = tilted(axis, sideways(axis, rng), angle, r % 2 ? 1.0 : -1.0);
      ASSERT_GT(d.dot(vec(s.axis)) * d.dot(vec(s.axis)), double(s.sinCone) * s.sinCone);
      ++certified;
      double lo = kInfinity, hi = -kInfinity;
      for (int i = 0; i <= kSteps; ++i)
        for (int j = 0; i + j <= kSteps; ++j) {
          const Vec2 uv = pieceUV(s, double(i) / kSteps, double(j) / kSteps);
          Vec3 du, dv;
          piece.derivatives(uv.x(), uv.y(), du, dv);
          const double jac = d.dot(du.cross(dv));
          lo = std::min(lo, jac), hi = std::max(hi, jac);
        }
      // One sign (zero where the piece's Jacobian vanishes, at the degenerate piece's collapsed
      // edge).
      EXPECT_TRUE(lo >= 0.0 || hi <= 0.0) << s.piece << ": " << lo << " " << hi;
    }
  }
  EXPECT_GT(certified, 100);
}

// The parent's cone, kept by each region, holds for the whole parent region.
TEST(BezierSubPatch, ParentConeCertifiesTheParentRegion) {
  const std::vector<BezierTriangle> pieces = curvedPieces();
  const std::vector<BezierSubPatch> subs = bezierSubPatches(pieces);
  Pcg32 rng(59);
  int certified = 0;
  constexpr int kSteps = 12;
  for (const BezierSubPatch& s : subs) {
    if (s.depth == 0) {
      EXPECT_GT(s.parentSinCone, 1.0f);
      continue;
    }
    if (s.parentSinCone > 1.0f) continue;
    BezierSubPatch parent = s;
    std::copy(s.parentU, s.parentU + 3, parent.cu);
    std::copy(s.parentV, s.parentV + 3, parent.cv);
    const BezierTriangle& piece = pieces[s.piece];
    const Vec3 axis = vec(s.parentAxis).normalized();
    for (int r = 0; r < 4; ++r) {
      const double angle = 0.5 * kPi - coneAngle(s.parentSinCone) - 0.01 * rng.nextDouble();
      if (angle <= 0.0) continue;
      const Vec3 d = tilted(axis, sideways(axis, rng), angle, r % 2 ? 1.0 : -1.0);
      ++certified;
      double lo = kInfinity, hi = -kInfinity;
      for (int i = 0; i <= kSteps; ++i)
        for (int j = 0; i + j <= kSteps; ++j) {
          const Vec2 uv = pieceUV(parent, double(i) / kSteps, double(j) / kSteps);
          Vec3 du, dv;
          piece.derivatives(uv.x(), uv.y(), du, dv);
          const double jac = d.dot(du.cross(dv));
          lo = std::min(lo, jac), hi = std::max(hi, jac);
        }
      EXPECT_TRUE(lo >= 0.0 || hi <= 0.0) << s.piece << ": " << lo << " " << hi;
    }
  }
  EXPECT_GT(certified, 100);
}

// The winding number of a region's projected boundary against every root of the whole piece: on
// lines its cone certifies, aimed near the region (a third of them within 1e-3 of an edge),
// Outside exactly when no root of the piece lies in the region, Inside when one does.
// Regions of the curved pieces, and whole pieces (the winding number of the net's own boundary
// rows, as the subdivision search takes it): gently curved paraboloid pieces, one region each.
void expectWindingTellsWhetherALineMeetsTheRegion(const std::vector<BezierTriangle>& pieces,
                                                  const std::vector<BezierSubPatch>& subs,
                                                  Pcg32& rng, int& inside, int& outside,
                                                  int& unknown) {
  for (size_t i = 0; i < subs.size(); i += 2) {
    const BezierSubPatch& s = subs[i];
    if (s.sinCone > 0.9f) continue;
    const BezierTriangle& piece = pieces[s.piece];
    const Vec3 axis = vec(s.axis).normalized();
    double cu[3], cv[3];
    s.corners(cu, cv);
    for (int r = 0; r < 6; ++r) {
      // A target in or around the region: its barycentric coordinates in [−0.5, 1.5], or 1e-6
      // to 1e-3 across an edge (log-uniform, either side).
      double a = 2.0 * rng.nextDouble() - 0.5, b = 2.0 * rng.nextDouble() - 0.5;
      if (r % 3 == 0) {
        const double along = rng.nextDouble();
        const double across =
            (rng.nextDouble() < 0.5 ? -1.0 : 1.0) * std::pow(10.0, -3.0 - 3.0 * rng.nextDouble());
        a = along - 0.5 * across, b = across;
      }
      const Vec2 uv = pieceUV(s, a, b);
      const Vec3 target = piece.position(uv.x(), uv.y());
      const double tilt = (0.5 * kPi - coneAngle(s.sinCone)) * 0.99 * rng.nextDouble();
      const Vec3 d = tilted(axis, sideways(axis, rng), tilt, r % 2 ? 1.0 : -1.0);
      if (d.dot(vec(s.axis)) * d.dot(vec(s.axis)) <= double(s.sinCone) * s.sinCone) continue;
      const double size = piece.bounds().diagonal().norm();
      const Vec3 o = target - 2.0 * size * d;
      // Every root of the piece on the line, and whether one lies in the region (skipping lines
      // within 1e-8 of its boundary, where rounding decides).
      std::vector<BezierHit> roots;
      intersectBezierTriangleAll(piece, o, d, -kInfinity, kInfinity, roots);
      bool in = false, near = false;
      for (const BezierHit& h : roots) {
        const double e1u = cu[1] - cu[0], e1v = cv[1] - cv[0], e2u = cu[2] - cu[0];
        const double e2v = cv[2] - cv[0], ru = h.u - cu[0], rv = h.v - cv[0];
        const double det = e1u * e2v - e1v * e2u;
        const double ba = (ru * e2v - rv * e2u) / det, bb = (e1u * rv - e1v * ru) / det;
        const double least = std::min({ba, bb, 1.0 - ba - bb});
        in |= least >= 0.0;
        near |= std::abs(least) < 1e-8;
      }
      if (near) continue;
      const RegionWinding w = bezierRegionWinding(piece, cu, cv, o, d);
      if (w == RegionWinding::Unknown) {
        ++unknown;
        continue;
      }
      EXPECT_EQ(w == RegionWinding::Inside, in) << "region " << i << " target " << a << " " << b;
      (in ? inside : outside) += 1;
    }
  }
}

TEST(BezierSubPatch, WindingOfTheBoundaryTellsWhetherALineMeetsTheRegion) {
  Pcg32 rng(67);
  {
    const std::vector<BezierTriangle> pieces = curvedPieces();
    int inside = 0, outside = 0, unknown = 0;
    expectWindingTellsWhetherALineMeetsTheRegion(pieces, bezierSubPatches(pieces), rng, inside,
                                                 outside, unknown);
    EXPECT_GT(inside, 300);
    EXPECT_GT(outside, 1000);
    EXPECT_LT(unknown, 5);
  }
  std::vector<BezierTriangle> gentle;
  for (int i = 0; i < 40; ++i) {
    const Vec2 a(rng.nextDouble() - 0.5, rng.nextDouble() - 0.5);
    gentle.push_back(paraboloidPiece(a, a + Vec2(0.3, 0.05 * rng.nextDouble()),
                                     a + Vec2(0.1 * rng.nextDouble(), 0.3)));
  }
  // One region per piece (a budget of one each and a cone wide enough): the whole piece.
  const std::vector<BezierSubPatch> whole = bezierSubPatches(gentle, 80.0, gentle.size());
  ASSERT_EQ(whole.size(), gentle.size());
  for (const BezierSubPatch& s : whole) ASSERT_EQ(s.depth, 0);
  int inside = 0, outside = 0, unknown = 0;
  for (int pass = 0; pass < 12; ++pass)
    expectWindingTellsWhetherALineMeetsTheRegion(gentle, whole, rng, inside, outside, unknown);
  EXPECT_GT(inside, 250);
  EXPECT_GT(outside, 500);
  EXPECT_LT(unknown, 5);
}

// Rays aimed just inside and just outside a region's edges (1e-4 of the edge in (u, v)), from
// directions its cone proves meet it at most once: the region reports the hit exactly when the
// target lies in it. Just outside, Newton from inside the region runs to the neighbour's root,
// and the winding number of the region's projected boundary must rule the region out.
TEST(BezierSubPatch, RaysPastARegionsEdgeMeetOnlyTheRegionHoldingThem) {
  const std::vector<BezierTriangle> pieces = curvedPieces();
  const std::vector<BezierSubPatch> subs = bezierSubPatches(pieces);
  Pcg32 rng(61);
  int inside = 0, outside = 0;
  for (size_t i = 0; i < subs.size(); i += 3) {
    const BezierSubPatch& s = subs[i];
    if (s.sinCone > 0.5f) continue;
    const BezierTriangle& piece = pieces[s.piece];
    const Vec3 axis = vec(s.axis).normalized();
    for (int r = 0; r < 4; ++r) {
      // A point of an edge, and one 1e-4 across it, towards the opposite corner or away.
      const int edge = int(rng.nextUint() % 3);
      const double along = 0.1 + 0.8 * rng.nextDouble();
      const bool in = r % 2 == 0;
      const double across = in ? 1e-4 : -1e-4;
      // Barycentric (a, b) of the region: edge 0 is corners 0 → 1 (b = 0), edge 1 is 1 → 2,
      // edge 2 is 2 → 0 (a = 0); `across` moves towards the corner opposite.
      double a = 0.0, b = 0.0;
      if (edge == 0) a = along - 0.5 * across, b = across;
      if (edge == 1) a = (1.0 - along) - 0.5 * across, b = along - 0.5 * across;
      if (edge == 2) a = across, b = (1.0 - along) - 0.5 * across;
      const Vec2 uv = pieceUV(s, a, b);
      if (uv.x() < 0.0 || uv.y() < 0.0 || uv.x() + uv.y() > 1.0) continue;  // off the piece
      const Vec3 target = piece.position(uv.x(), uv.y());
      // Within 60° of the cone's axis, well inside the directions it certifies.
      const Vec3 side = sideways(axis, rng);
      const double tilt =
          coneAngle(s.sinCone) + (kPi / 3.0 - coneAngle(s.sinCone)) * rng.nextDouble();
      const Vec3 d = tilted(axis, side, tilt, r / 2 ? 1.0 : -1.0);
      if (d.dot(vec(s.axis)) * d.dot(vec(s.axis)) <= 1.01 * double(s.sinCone) * s.sinCone) continue;
      const double size = piece.bounds().diagonal().norm();
      const Vec3 o = target - size * d;
      BezierHit h;
      const bool hit = intersectBezierSubPatch(piece, s, o, d, 0.0, kInfinity, h);
      EXPECT_EQ(occludesBezierSubPatch(piece, s, o, d, 0.0, kInfinity), hit) << i;
      if (in) {
        ++inside;
        ASSERT_TRUE(hit) << "region " << i << " edge " << edge;
        EXPECT_NEAR(h.t, size, 1e-9 * size);
        EXPECT_NEAR(h.u, uv.x(), 1e-7);
        EXPECT_NEAR(h.v, uv.y(), 1e-7);
      } else {
        ++outside;
        EXPECT_FALSE(hit) << "region " << i << " edge " << edge << " t " << h.t;
      }
    }
  }
  EXPECT_GT(inside, 500);
  EXPECT_GT(outside, 500);
}

// The nearest hit over a piece's sub-patches against intersectBezierTriangle on the whole
// piece: the same hits, to 1e-9, on rays aimed at the piece (a quarter of them grazing) and at
// random.
TEST(BezierSubPatch, HitsAreTheWholePieceHits) {
  const std::vector<BezierTriangle> pieces = curvedPieces();
  const std::vector<BezierSubPatch> subs = bezierSubPatches(pieces);
  Pcg32 rng(47);
  int hits = 0, compared = 0, againstAll = 0;
  for (size_t p = 0; p < pieces.size(); ++p) {
    const BezierTriangle& piece = pieces[p];
    const Vec3 centre = 0.5 * (piece.bounds().lo + piece.bounds().hi);
    const double size = piece.bounds().diagonal().norm();
    for (int i = 0; i < 1500; ++i) {
      double u = rng.nextDouble(), v = rng.nextDouble();
      if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
      const Vec3 target = i % 3 == 0 ? centre + size * (uniformDirection(rng) * rng.nextDouble())
                                     : piece.position(u, v);
      Vec3 d = uniformDirection(rng);
      if (i % 4 == 1) {  // within a few degrees of the tangent plane
        const Vec3 n = piece.normal(u, v);
        if (n.squaredNorm() == 0.0) continue;
        d = safeNormalized(d - d.dot(n) * n + 0.05 * (rng.nextDouble() - 0.5) * n);
      }
      const Vec3 o = target - (0.5 + 2.0 * rng.nextDouble()) * size * d;
      const double tmax = i % 5 == 0 ? kInfinity : 4.0 * size * rng.nextDouble();
      BezierHit whole;
      const bool wholeHit = intersectBezierTriangle(piece, o, d, 0.0, tmax, whole);
      // The nearest of every root (the all-hits search, which never rules a node out by its
      // boundary's winding number) is the nearest-hit search's; on every fourth ray (it is slow).
      std::vector<BezierHit> roots;
      if (i % 4 == 3) intersectBezierTriangleAll(piece, o, d, 0.0, tmax, roots);
      BezierHit nearestRoot;
      for (const BezierHit& h : roots)
        if (h.t < nearestRoot.t) nearestRoot = h;
      if (wholeHit && !roots.empty() && p != pieces.size() - 1) {
        ++againstAll;
        EXPECT_NEAR(whole.t, nearestRoot.t, 1e-9 * (size + whole.t)) << p << " " << i;
      }
      if (i % 4 == 3 && wholeHit != !roots.empty() && p != pieces.size() - 1) {
        // Only where the line touches the piece within 1e-6 of a double root.
        const BezierHit& h = wholeHit ? whole : nearestRoot;
        Vec3 du, dv;
        piece.derivatives(h.u, h.v, du, dv);
        EXPECT_LT(std::abs(d.dot(safeNormalized(du.cross(dv)))), 1e-4) << p << " " << i;
      }
      BezierHit best;
      bool anyHit = false, occluded = false;
      for (const BezierSubPatch& s : subs) {
        if (s.piece != p) continue;
        BezierHit h;
        if (intersectBezierSubPatch(piece, s, o, d, 0.0, tmax, h) && h.t < best.t) best = h;
        anyHit |= h.t < kInfinity;
        occluded |= occludesBezierSubPatch(piece, s, o, d, 0.0, tmax);
      }
      // Every hit lies on the surface.
      if (anyHit) {
        ++hits;
        EXPECT_NEAR((piece.position(best.u, best.v) - (o + best.t * d)).norm(), 0.0,
                    1e-9 * (size + best.t));
      }
      // The whole-piece search, out of nodes, misses some hits of the degenerate piece that its
      // regions find (on the surface, checked above).
      if (anyHit && !wholeHit && p == pieces.size() - 1) continue;
      // Rays within 1e-6 of a double root may find or miss it either way: compare the rest.
      if (wholeHit != anyHit) {
        const BezierHit& h = wholeHit ? whole : best;
        Vec3 du, dv;
        piece.derivatives(h.u, h.v, du, dv);
        const double cosine = std::abs(d.dot(safeNormalized(du.cross(dv))));
        EXPECT_LT(cosine, 1e-4) << p << " " << i << " whole " << wholeHit;
        continue;
      }
      EXPECT_EQ(occluded, anyHit) << p << " " << i;
      if (!anyHit) continue;
      ++compared;
      EXPECT_NEAR(best.t, whole.t, 1e-9 * (size + whole.t)) << p << " " << i;
      EXPECT_NEAR(best.u, whole.u, 1e-7) << p << " " << i;
      EXPECT_NEAR(best.v, whole.v, 1e-7) << p << " " << i;
    }
  }
  EXPECT_GT(compared, 3000);
  EXPECT_GT(againstAll, 800);
  EXPECT_GE(hits, compared);
}

TEST(BezierSubPatch, RegionsComePieceAfterPieceWhateverTheThreads) {
  // Enough pieces for many parallel blocks (64 pieces each).
  std::vector<BezierTriangle> pieces;
  while (pieces.size() < 1000) {
    const std::vector<BezierTriangle> more = curvedPieces();
    pieces.insert(pieces.end(), more.begin(), more.end());
  }
  const std::vector<BezierSubPatch> many = bezierSubPatches(pieces);
  const std::vector<BezierSubPatch> one = [&] {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    return bezierSubPatches(pieces);
  }();
  ASSERT_EQ(many.size(), one.size());
  for (size_t i = 0; i < many.size(); ++i) {
    ASSERT_EQ(many[i].piece, one[i].piece) << i;
    if (i > 0) {
      ASSERT_LE(many[i - 1].piece, many[i].piece) << i;
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(many[i].cu[c], one[i].cu[c]);
      EXPECT_EQ(many[i].cv[c], one[i].cv[c]);
    }
    EXPECT_EQ(std::memcmp(many[i].lo, one[i].lo, sizeof(many[i].lo)), 0);
  }
}

TEST(BezierSubPatch, DefaultBudgetIsTwoPerPieceBetweenItsFloorAndItsCap) {
  EXPECT_EQ(defaultSubPatchBudget(0), 65536u);
  EXPECT_EQ(defaultSubPatchBudget(8192), 65536u);
  EXPECT_EQ(defaultSubPatchBudget(17412), 65536u);         // the cow's pieces
  EXPECT_EQ(defaultSubPatchBudget(156000), 2u * 156000u);  // the armadillo's
  EXPECT_EQ(defaultSubPatchBudget(1048576), size_t(1) << 21);
  EXPECT_EQ(defaultSubPatchBudget(1048577), size_t(1) << 21);
  EXPECT_EQ(defaultSubPatchBudget(3000000), size_t(1) << 21);  // a 1,000,000-triangle mesh
}

}  // namespace
}  // namespace quadtri
