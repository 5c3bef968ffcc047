// The Embree user-geometry callbacks behind Accel (accel.cpp): what each geometry hands its
// callbacks, the context that carries the double-precision ray through Embree's traversal, and
// the callbacks that intersect quadric patches and Bézier pieces in double precision. Private to
// the geometry layer.
#pragma once

#include <embree3/rtcore.h>

#include <vector>

#include "quadtri/geometry/accel.h"
#include "quadtri/surface/bezier_intersect.h"
#include "quadtri/surface/quadric_patch_parts.h"

namespace quadtri::accel_detail {

constexpr unsigned kInvalidId = RTC_INVALID_GEOMETRY_ID;

// What the patch callbacks need: the patches and how much to grow their bounds. The double ray
// differs from Embree's float copy by about 6e-8 of the distance travelled, so boxes grow by
// 1e-5 of the geometry's extent to never cull a hit of the double ray. Rendering structures
// trace long patches as `parts` (quadric_patch_parts.h), when the mesh has any: primitive i is
// then parts[i], its hits reported as its patch's. Otherwise primitive i is patch i.
struct PatchGeometry {
  const std::vector<QuadricPatch>* patches = nullptr;
  std::vector<QuadricPatchPart> parts;
  Bounds3 bounds;              // of every patch, in world coordinates
  Vec3 origin = Vec3::Zero();  // Accel::origin(): Embree's boxes are relative to it
  double margin = 0.0;
};

// The same for Bézier pieces. Rendering structures trace `subPatches` (regions of the pieces,
// the primitives of Embree's user geometry, each hit reported as its piece's); those that collect
// every hit (crack rates) have none and trace whole pieces, one primitive each.
// Rendering structures also trace the pieces that are their own corner triangle, linearly
// parametrised (BezierTriangle::isAffine: a flat face with one normal), as native triangles of a
// geometry of their own, `flatGeometry`: triangle i is piece flatPieces[i], its Embree (u, v)
// the piece's. Accel::intersect reports its hits as the pieces' own.
struct BezierGeometry {
  const std::vector<BezierTriangle>* pieces = nullptr;
  bool tracesSubPatches = false;
  std::vector<BezierSubPatch> subPatches;
  unsigned id = kInvalidId, flatGeometry = kInvalidId;
  std::vector<uint32_t> flatPieces;
  Bounds3 bounds;              // of every piece, in world coordinates
  Vec3 origin = Vec3::Zero();  // Accel::origin(): Embree's boxes are relative to it
  double margin = 0.0;
};

// Embree's context extended with the double-precision ray, so quadric patches are intersected
// in double while Embree traverses with floats. Embree hands this pointer to the callbacks.
struct TraceContext {
  RTCIntersectContext embree;  // first member: the callbacks cast the context back
  const Ray* ray = nullptr;
  double tnear = 0.0;         // the ray's tnear clamped to >= 0, as Embree clamps its copy
  double patchT = kInfinity;  // the nearest patch hit so far, in double
  unsigned patchGeometry = kInvalidId, patchPrimitive = kInvalidId;
  const std::vector<QuadricPatch>* patches = nullptr;  // those of the nearest patch hit
  // Or the pieces of the nearest hit, when it is a Bézier piece, and its (u, v).
  const std::vector<BezierTriangle>* pieces = nullptr;
  double pieceU = 0.0, pieceV = 0.0;
  std::vector<RayHit>* hits = nullptr;  // set by allHits(): record every hit, keep none
};

/// A patch hit at t, its normal filled when `withNormal`.
RayHit patchHit(const std::vector<QuadricPatch>& patches, const Ray& ray, double t,
                unsigned geometry, unsigned primitive, bool withNormal = true);
/// A Bézier piece's hit at h: its point and normal from one evaluation.
RayHit bezierHit(const BezierTriangle& piece, const BezierHit& h, unsigned geometry,
                 unsigned primitive);
/// Embree's hit of a flat piece's triangle, again in double precision.
BezierHit flatPieceHit(const BezierTriangle& piece, const Ray& ray, const RTCRayHit& rayhit);
/// Embree's float copy of the ray, its origin relative to `frame` (Accel::origin()), its
/// interval rounded outward.
void fillRay(const Ray& ray, const Vec3& frame, RTCRay& out);

// The callbacks Embree calls (single rays: N == 1).
void collectTriangleHit(const RTCFilterFunctionNArguments* args);
void patchBounds(const RTCBoundsFunctionArguments* args);
void intersectPatch(const RTCIntersectFunctionNArguments* args);
void occludedPatch(const RTCOccludedFunctionNArguments* args);
void bezierBounds(const RTCBoundsFunctionArguments* args);
void intersectBezier(const RTCIntersectFunctionNArguments* args);
void occludedBezier(const RTCOccludedFunctionNArguments* args);

}  // namespace quadtri::accel_detail
