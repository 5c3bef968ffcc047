// Ray intersection of quartic Bézier triangles, traced directly (no tessellation).
//
// Method. The 15 control points are projected into the ray's frame: two unit vectors s, t
// perpendicular to d give (x, y) = ((b − o)·s, (b − o)·t), and z = (b − o)·d / |d|² is the ray
// parameter of the point's foot on the line. The ray hits the piece at (u, v) exactly where
// (x, y)(u, v) = (0, 0), and then t = z(u, v). By the convex-hull property a (sub-)net whose
// 2D box excludes the origin, or whose z range lies outside (tmin, tmax) (or beyond the nearest
// hit found so far), holds no hit and is culled; so is one whose mean-value enclosure
// F(centre) + [∂F/∂u]·Δu + [∂F/∂v]·Δv excludes it. Surviving nets are bisected (newest-vertex
// bisection: the edge opposite corner 0 at its midpoint, by one chain of de Casteljau steps that
// gives both halves; two bisections make a midpoint 4-split), depth first, nearer half first,
// on a fixed-size stack (no heap allocation).
//
// A net is solved once it is known to hold at most one hit: when every 2D cross product of a
// control vector of ∂(x, y)/∂u with one of ∂(x, y)/∂v has the same sign, the average Jacobian
// between any two points of the sub-triangle is non-singular, so (x, y) is injective on it.
// Newton then runs on the 2D system of the WHOLE piece, from where the ray crosses the
// sub-triangle's planar corner triangle; a root is accepted when it lies in the sub-triangle
// (up to 1e-6 of its size) and in the piece's domain up to 1e-9, so a ray through the boundary
// two pieces share is found by both (hits from neighbouring sub-triangles are merged by (u, v)).
// When Newton does not converge there, or converges outside (then the halves skip it), or the
// net may fold, bisection goes on; at the maximum depth (30 bisections: 1/32768 of the piece's
// size) Newton is tried anyway, from the corners too where the net may fold, and should it
// still fail, the planar corner triangle stands in, so no hit is lost. A budget of nodes bounds
// the work on degenerate pieces.
//
// Rendering traces sub-patches (BezierSubPatch): regions of a piece, up to 3 midpoint 4-splits
// deep, each an Embree primitive with its own box, so that the BVH culls what the subdivision
// culled before. Each region keeps a prism that holds its control points (the corner triangle's
// plane with the range of heights above it, and the least barycentric coordinate of a control
// point's projection for each corner) and the cone of its derivative crosses ∂u × ∂v (over all
// pairs of control vectors). A ray that misses the prism misses the region (a few dot products).
// One whose angle to the cone's axis is below 90° less the cone's half-angle sees every
// projected cross with one sign, which is the injectivity test above for the whole region: it
// meets the region at most once, so Newton in 3D on the piece, from where the ray crosses the
// corner triangle's plane, settles it when it converges in the region (a hit, or none in range).
// A root it finds outside the region proves the region empty when the parent region's cone
// (kept too) proves the ray meets the parent at most once and the root lies in the parent.
// Otherwise (a ray nearly tangent to the region, or Newton failing or leaving the region), the
// subdivision above runs on the region alone, in a frame whose y axis is the cone's axis as
// seen across the ray, so that the region's thin projection keeps thin boxes; a root Newton found
// there bounds its search. Its last level stays 1/1024 of the piece. Rendering queries there also
// cull a node whose control points all lie beyond a line through the origin across an edge of
// its corner triangle. All-hits queries keep whole pieces and the search above as it was.
#pragma once

#include <cstdint>
#include <vector>

#include "quadtri/math/vec.h"
#include "quadtri/surface/bezier_triangle.h"

namespace quadtri {

/// A ray's hit on a Bézier piece: the ray parameter and the piece's (u, v).
struct BezierHit {
  double t = kInfinity;
  double u = 0.0, v = 0.0;
};

/// Nearest hit of o + t·d (d need not be unit) with the piece for t in (tmin, tmax). Returns
/// false, leaving `hit` untouched, when there is none.
bool intersectBezierTriangle(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double tmin,
                             double tmax, BezierHit& hit);

/// True when the ray hits the piece anywhere in (tmin, tmax) (stops at the first hit found).
bool occludesBezierTriangle(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double tmin,
                            double tmax);

/// Appends every hit in (tmin, tmax) to `hits`, unordered and each once; returns how many.
size_t intersectBezierTriangleAll(const BezierTriangle& piece, const Vec3& o, const Vec3& d,
                                  double tmin, double tmax, std::vector<BezierHit>& hits);

/// The piece's 4 midpoint sub-triangles, each over a quarter of its domain: 0 at corner 0
/// ((0,0), (½,0), (0,½)), 1 at corner 1 ((½,0), (1,0), (½,½)), 2 at corner 2 ((0,½), (½,½),
/// (0,1)) and 3 in the middle ((½,½), (0,½), (½,0)), all with the piece's orientation, triangle
/// and piece ids, and bounds. Sub-triangle m at its (u', v') is the piece at
/// c0 + u'(c1 − c0) + v'(c2 − c0) for its corners c0, c1, c2 above.
std::array<BezierTriangle, 4> subdivideBezierTriangle(const BezierTriangle& piece);

/// The two halves of `piece` across the side opposite `corner` (0, 1 or 2), at its midpoint m:
/// the nets over (m, c, c+1) and (m, c+2, c) in the piece's corners c = `corner`, c+1, c+2
/// (mod 3), both with the piece's orientation.
std::array<BezierTriangle, 2> bisectBezierTriangle(const BezierTriangle& piece, int corner);

/// A region of a piece that rendering traces as one primitive (accel.cpp): a sub-triangle of the
/// piece's domain reached by midpoint 4-splits and, for elongated ones, bisections of the longest
/// edge, with what rejects most rays at the cost of a few dot products and tells when one Newton
/// solve is exact.
/// Directions and bounds are floats, computed so that they hold for the rounded directions.
struct BezierSubPatch {
  /// Splits from the piece, counted in bisections (a midpoint 4-split is two).
  static constexpr int kMaxDepth = 10;
  /// The prism that holds the region's control points: corner 0 `p0`, the corner triangle's
  /// unit normal `n`, and g1, g2 such that (x − p0)·g1 and (x − p0)·g2 are the corner triangle's
  /// barycentric coordinates 1 and 2 of x's projection along n. Every control point has
  /// (b − p0)·n in [hlo, hhi] and barycentric coordinate m at least lmin[m] (grown by a rounding
  /// margin). A degenerate corner triangle has an unbounded prism.
  Vec3 p0 = Vec3::Zero();
  float n[3] = {}, g1[3] = {}, g2[3] = {};
  float hlo = 0.0f, hhi = 0.0f;
  float lmin[3] = {};
  float inverseSize = 0.0f;  ///< 1 / the corner triangle's longest side (0 when degenerate)
  /// Every cross product of a control vector of ∂/∂u with one of ∂/∂v makes an angle with the
  /// unit `axis` whose sine is at most `sinCone` (2 when some does not lie on the axis' side or
  /// vanishes): a ray with |d̂·axis| > sinCone meets the region at most once.
  float axis[3] = {};
  float sinCone = 2.0f;
  /// The same for the region it was split from (sinCone 2 at level 0): where it proves a ray
  /// meets the parent at most once, a root Newton finds in the parent outside this region
  /// proves that none lies in it.
  float parentAxis[3] = {};
  float parentSinCone = 2.0f;
  float lo[3] = {}, hi[3] = {};  ///< box of the region's control points, relative to p0 (bounds())
  /// The region's corners in the piece's (u, v), and its parent's (both the whole domain for
  /// the piece itself), in units of 2^-kMaxDepth: every corner a split makes is a dyadic
  /// fraction with at most kMaxDepth bits.
  static constexpr double kCornerUnit = 1.0 / double(1 << kMaxDepth);
  uint16_t cu[3] = {0, 1 << kMaxDepth, 0}, cv[3] = {0, 0, 1 << kMaxDepth};
  uint16_t parentU[3] = {0, 1 << kMaxDepth, 0}, parentV[3] = {0, 0, 1 << kMaxDepth};
  uint32_t piece = 0;  ///< the piece's index
  uint8_t depth = 0;   ///< splits from the piece, in bisections (0: the whole piece)

  /// The region's corners in the piece's (u, v).
  void corners(double* u, double* v) const {
    for (int c = 0; c < 3; ++c) u[c] = cu[c] * kCornerUnit, v[c] = cv[c] * kCornerUnit;
  }
  /// Its parent's.
  void parentCorners(double* u, double* v) const {
    for (int c = 0; c < 3; ++c) u[c] = parentU[c] * kCornerUnit, v[c] = parentV[c] * kCornerUnit;
  }
  Bounds3 bounds() const;
};

/// The sub-patches that rendering traces in place of `pieces`: each piece's neediest region
/// split while the piece holds fewer than its share of `budget` (0: defaultSubPatchBudget): an
/// even share first, then what the pieces that needed less left over, given to those
/// that needed more in proportion to the regions they would need. Regions split down to
/// BezierSubPatch::kMaxDepth: one whose derivative cone is wider than `coneDegrees` (the
/// narrower the cone, the fewer rays meet a region where one Newton solve does not settle it),
/// or whose box has more than 6 times the area of its corner triangle (a ray enters such a box
/// far more often than it meets the region). An elongated region is bisected across its longest
/// edge, which shrinks its box, others split in 4.
/// The region budget rendering gives `pieces` pieces: 2 per piece, at least 65,536 and at most
/// 2,097,152 (2^21, 352 MiB of regions); a piece is always one region at least, so a mesh of
/// more pieces than that traces each piece whole. More per piece renders no faster: on the
/// armadillo (156,000 pieces) 8 per piece took 4 times the build and 2.4 times the memory for
/// a 5% slower render. On a fine mesh the regions are far below a
/// pixel and more of them only cost memory and build time: a 1,000,000-triangle torus had 24 M
/// regions and a 9.4 GB peak with no cap, 4.2 M and 2.9 GB under 2^22, and now 3 M (one per
/// piece, written in place) and 2.35 GB, its first pixel 2 to 4 s sooner and its render no
/// slower.
constexpr size_t kSubPatchesPerPiece = 2, kMinSubPatchBudget = 65536,
                 kMaxSubPatchBudget = size_t(1) << 21;
size_t defaultSubPatchBudget(size_t pieces);

std::vector<BezierSubPatch> bezierSubPatches(const std::vector<BezierTriangle>& pieces,
                                             double coneDegrees = 5.0, size_t budget = 0);

/// Where the line o + t·d lies against the region of `piece` with corners (cu[i], cv[i]) in its
/// (u, v), for a region whose projection along d is one to one (as a BezierSubPatch's cone
/// certifies): the winding number of the region's projected boundary around the line, 0 when the
/// line misses the region and ±1 when it meets it. Unknown when the line passes within rounding
/// of the boundary (or d is zero). Meaningless where the projection folds.
enum class RegionWinding { Outside, Inside, Unknown };
RegionWinding bezierRegionWinding(const BezierTriangle& piece, const double* cu, const double* cv,
                                  const Vec3& o, const Vec3& d);

/// Nearest hit of o + t·d with the sub-patch's region of `piece` (`sub.piece`'s piece), for t in
/// (tmin, tmax); (u, v) are the piece's. Exact as intersectBezierTriangle, restricted to the
/// region (up to 1e-6 of its size). Returns false, leaving `hit` untouched, when there is none.
/// `from`: for a ray spawned from a hit of this piece, that hit's (u, v). Where it lies in the
/// region and the region's cone proves the ray meets it at most once, that meeting is the origin
/// itself, and the region is skipped without a solve.
bool intersectBezierSubPatch(const BezierTriangle& piece, const BezierSubPatch& sub, const Vec3& o,
                             const Vec3& d, double tmin, double tmax, BezierHit& hit,
                             const Vec2* from = nullptr);

/// True when the ray hits the sub-patch's region anywhere in (tmin, tmax) (`from` as above).
bool occludesBezierSubPatch(const BezierTriangle& piece, const BezierSubPatch& sub, const Vec3& o,
                            const Vec3& d, double tmin, double tmax, const Vec2* from = nullptr);

}  // namespace quadtri
