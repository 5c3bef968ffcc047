// The ray-tracing acceleration structure: Embree 3 with native triangles, and quadric patches
// and Bézier pieces as user geometry. Shared by the renderer and the crack-rate analysis.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "quadtri/math/vec.h"
#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/surface/bezier_triangle.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

struct Ray {
  Vec3 origin;
  Vec3 direction;
  double tnear = 0.0;
  double tfar = kInfinity;
  /// For a ray spawned from a surface: the geometry, primitive and (u, v) of the hit it leaves
  /// (geometry ~0u: none). A Bézier region whose cone proves that the ray meets it at most once
  /// skips the ray when that point lies in it, without a solve.
  uint32_t fromGeometry = ~0u, fromPrimitive = ~0u;
  Vec2 fromUV = Vec2::Zero();
};

/// What a ray hit: which geometry (the id returned when it was added), which primitive, where.
struct RayHit {
  double t = kInfinity;
  uint32_t geometry = ~0u;
  uint32_t primitive = ~0u;
  double u = 0, v = 0;  ///< barycentric coordinates of the hit (triangles, Bézier pieces)
  Vec3 geometricNormal = Vec3::Zero();  ///< unit, not flipped towards the ray (zero: no hit)
  /// The surface point at (u, v) of a Bézier piece's hit (evaluated with the normal); zero for
  /// other hits, whose point is the ray's at t.
  Vec3 point = Vec3::Zero();
  bool valid() const { return geometry != ~0u; }
};

/// An Embree device and scene, committed once all geometry is added.
class Accel {
 public:
  struct Options {
    bool robust = false;  ///< RTC_SCENE_FLAG_ROBUST: watertight traversal (crack-rate analysis)
    bool collectHits = false;  ///< enables allHits() (an Embree context filter function)
  };
  explicit Accel(const Options& options);
  Accel() : Accel(Options{}) {}
  ~Accel();
  Accel(const Accel&) = delete;
  Accel& operator=(const Accel&) = delete;

  /// Adds a triangle mesh (copied, handed to Embree as floats at commit); returns its geometry
  /// id.
  uint32_t addTriangles(const TriangleMesh& mesh);
  /// Adds quadric patches as one Embree user geometry with a bound per patch; the patches are
  /// referenced, not copied, and must outlive the Accel. Given the `mesh` whose triangle t
  /// patch t stands for, a rendering structure (not Options.collectHits) traces the patches
  /// whose boxes are long against their triangles as parts with tighter boxes
  /// (quadricPatchParts); a hit's primitive is still its patch's index. Returns its geometry id.
  uint32_t addQuadricPatches(const std::vector<QuadricPatch>& patches,
                             const TriangleMesh* mesh = nullptr);
  /// Adds Bézier pieces as one Embree user geometry, intersected in double precision
  /// (bezier_intersect.h); referenced like the patches. Its primitives are the pieces'
  /// sub-patches (bezierSubPatches), each bounded by its control points, or, with
  /// Options.collectHits, the whole pieces. A hit's primitive is the piece's index, its (u, v)
  /// the piece's and its geometricNormal piece.normal(u, v). Returns its geometry id.
  uint32_t addBezierTriangles(const std::vector<BezierTriangle>& pieces);
  void commit();

  /// The largest coordinate Embree traces: its FLT_LARGE (1.844e18) rounded down. Beyond it
  /// Embree drops a primitive from its tree without a word and aborts on a ray (its Debian
  /// build asserts), so every vertex, bound and control point added is checked against it, and
  /// every ray traced against kLargestRayCoordinate (origin and direction components; tnear
  /// and tfar must not be NaN): Error names what is out of range.
  static constexpr double kLargestCoordinate = 1.8e18;
  /// The bound on a ray's origin and direction: nearer Embree's, so that a ray spawned from a
  /// surface at kLargestCoordinate (moved off it by about 2^-19 of its coordinate) is traced.
  static constexpr double kLargestRayCoordinate = 1.84e18;

  /// Whether intersect fills RayHit::geometricNormal for triangle and quadric-patch hits. A caller
  /// that derives its own normal from the hit in double precision (RenderScene) skips it; a
  /// Bézier piece's normal comes with its point and is always filled.
  enum class HitNormal { Fill, Skip };
  /// Nearest hit in (ray.tnear, ray.tfar), or an invalid RayHit.
  RayHit intersect(const Ray& ray, HitNormal normal = HitNormal::Fill) const;
  /// Rays traced together (up to kPacketSize at a time): the native triangles as one packet
  /// of Embree's, which coherent rays such as a pixel's camera rays share, then each ray alone
  /// through the user geometry. hits[i] is intersect(rays[i], normal): the same geometry, t and
  /// point, bit for bit in the tests; where two triangles are hit at exactly the same t,
  /// Embree's packet and single-ray kernels may settle the tie differently.
  static constexpr size_t kPacketSize = 16;
  void intersect(std::span<const Ray> rays, std::span<RayHit> hits,
                 HitNormal normal = HitNormal::Fill) const;
  /// True when anything is hit in (ray.tnear, ray.tfar).
  bool occluded(const Ray& ray) const;
  /// Every hit in (ray.tnear, ray.tfar), unordered, appended to `hits`: each candidate Embree
  /// finds is recorded and rejected, so none hides another. Needs Options.collectHits.
  void allHits(const Ray& ray, std::vector<RayHit>& hits) const;

  /// Bytes of geometry buffers and patch records handed to Embree.
  size_t geometryBytes() const;
  /// What tracing long patches as parts (addQuadricPatches) costs: the parts' records and
  /// Embree's share of each primitive beyond the patches. Zero where no patch was split.
  size_t patchPartBytes() const;
  /// Bounds of everything added, as Embree holds it (floats, patch bounds slightly inflated),
  /// in world coordinates.
  Bounds3 bounds() const;
  /// The point Embree's float coordinates are relative to (vertices, boxes, ray origins), chosen
  /// at commit: the centre of everything added where that lies farther from the world origin
  /// than 8 times its largest half-extent, so a scene far from the origin is traced as finely as
  /// the same scene around it; otherwise the world origin. A point p is held to about 2^-24 of
  /// the largest coordinate of p − origin().
  Vec3 origin() const;
  bool robust() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Sets flush-to-zero and denormals-are-zero for the calling thread, as Embree asks of every
/// thread that traces rays.
void enableFlushToZero();

/// enableFlushToZero for as long as it lives, then the thread's mode as it was: for the bodies
/// of parallel loops, which TBB also runs on the thread that started them (the caller's own
/// floating-point mode must not change under it).
class FlushToZeroScope {
 public:
  FlushToZeroScope();
  ~FlushToZeroScope();
  FlushToZeroScope(const FlushToZeroScope&) = delete;
  FlushToZeroScope& operator=(const FlushToZeroScope&) = delete;

 private:
  unsigned mode_;
};

}  // namespace quadtri
