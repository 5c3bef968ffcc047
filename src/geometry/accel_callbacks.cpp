#include "accel_callbacks.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "quadtri/math/error.h"
#include "quadtri/math/float_round.h"
#include "quadtri/math/parallel.h"

namespace quadtri::accel_detail {

RayHit patchHit(const std::vector<QuadricPatch>& patches, const Ray& ray, double t,
                unsigned geometry, unsigned primitive, bool withNormal) {
  RayHit hit;
  hit.t = t;
  hit.geometry = geometry;
  hit.primitive = primitive;
  if (withNormal)
    hit.geometricNormal =
        safeNormalized(primitiveNormal(patches, primitive, ray.origin + t * ray.direction));
  return hit;
}

namespace {

// allHits(): both roots of the patch, recorded without shortening the ray.
void collectPatchHits(const std::vector<QuadricPatch>& patches, TraceContext& ctx,
                      unsigned geometry, unsigned primitive) {
  double tmin = ctx.tnear, t;
  while (intersectPrimitive(patches, primitive, ctx.ray->origin, ctx.ray->direction, tmin,
                            ctx.ray->tfar, t)) {
    ctx.hits->push_back(patchHit(patches, *ctx.ray, t, geometry, primitive));
    tmin = t;
  }
}

}  // namespace

// allHits() for triangles: the context filter sees each candidate (its t in the ray's tfar),
// records it and rejects it so that traversal goes on.
void collectTriangleHit(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<TraceContext*>(args->context);
  RayHit hit;
  hit.t = RTCRayN_tfar(args->ray, 1, 0);
  hit.geometry = RTCHitN_geomID(args->hit, 1, 0);
  hit.primitive = RTCHitN_primID(args->hit, 1, 0);
  hit.u = RTCHitN_u(args->hit, 1, 0);
  hit.v = RTCHitN_v(args->hit, 1, 0);
  hit.geometricNormal = safeNormalized(Vec3(
      RTCHitN_Ng_x(args->hit, 1, 0), RTCHitN_Ng_y(args->hit, 1, 0), RTCHitN_Ng_z(args->hit, 1, 0)));
  ctx->hits->push_back(hit);
  args->valid[0] = 0;
}

namespace {

// Embree's float box holding b grown by `margin`, relative to `frame`.
void writeBounds(const Bounds3& b, double margin, const Vec3& frame, RTCBounds* o) {
  o->lower_x = floatDown(b.lo.x() - frame.x() - margin);
  o->lower_y = floatDown(b.lo.y() - frame.y() - margin);
  o->lower_z = floatDown(b.lo.z() - frame.z() - margin);
  o->upper_x = floatUp(b.hi.x() - frame.x() + margin);
  o->upper_y = floatUp(b.hi.y() - frame.y() + margin);
  o->upper_z = floatUp(b.hi.z() - frame.z() + margin);
}

}  // namespace

void patchBounds(const RTCBoundsFunctionArguments* args) {
  acquireEdge(args->geometryUserPtr);  // Accel::commit's release (ThreadSanitizer)
  const auto* g = static_cast<const PatchGeometry*>(args->geometryUserPtr);
  writeBounds(
      g->parts.empty() ? (*g->patches)[args->primID].bounds : g->parts[args->primID].bounds(),
      g->margin, g->origin, args->bounds_o);
  releaseEdge(&g->margin);
}

// Accel traces single rays (rtcIntersect1/rtcOccluded1), so every callback sees N == 1.
void intersectPatch(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* ctx = reinterpret_cast<TraceContext*>(args->context);
  auto* rayhit = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const auto* g = static_cast<const PatchGeometry*>(args->geometryUserPtr);
  const std::vector<QuadricPatch>& patches = *g->patches;
  if (ctx->hits) return collectPatchHits(patches, *ctx, args->geomID, args->primID);
  // While a patch is the nearest hit (or nothing is: both ids are then invalid and patchT is
  // the ray's tfar) its exact t bounds the search; after a triangle took over, its float t does.
  const bool patchIsNearest =
      rayhit->hit.geomID == ctx->patchGeometry && rayhit->hit.primID == ctx->patchPrimitive;
  const double tmax =
      patchIsNearest ? ctx->patchT : std::min(ctx->patchT, double(rayhit->ray.tfar));
  double t;
  unsigned primitive = args->primID;
  if (g->parts.empty()) {
    if (!intersectPrimitive(patches, primitive, ctx->ray->origin, ctx->ray->direction, ctx->tnear,
                            tmax, t))
      return;
  } else {
    const QuadricPatchPart& part = g->parts[primitive];
    primitive = part.patch;
    if (!intersectPrimitiveWithin(patches, primitive, part.bounds(), ctx->ray->origin,
                                  ctx->ray->direction, ctx->tnear, tmax, t))
      return;
  }
  ctx->patchT = t;
  ctx->patchGeometry = args->geomID;
  ctx->patchPrimitive = primitive;
  ctx->patches = &patches;
  ctx->pieces = nullptr;
  rayhit->ray.tfar = floatDown(t);
  rayhit->hit.geomID = args->geomID;
  rayhit->hit.primID = primitive;  // the patch's index, also for a part
  rayhit->hit.instID[0] = args->context->instID[0];
  rayhit->hit.u = rayhit->hit.v = 0.0f;
}

void occludedPatch(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* ctx = reinterpret_cast<const TraceContext*>(args->context);
  auto* ray = reinterpret_cast<RTCRay*>(args->ray);
  const auto* g = static_cast<const PatchGeometry*>(args->geometryUserPtr);
  double t;
  const bool hit =
      g->parts.empty()
          ? intersectPrimitive(*g->patches, args->primID, ctx->ray->origin, ctx->ray->direction,
                               ctx->tnear, ctx->ray->tfar, t)
          : intersectPrimitiveWithin(*g->patches, g->parts[args->primID].patch,
                                     g->parts[args->primID].bounds(), ctx->ray->origin,
                                     ctx->ray->direction, ctx->tnear, ctx->ray->tfar, t);
  if (hit) ray->tfar = -std::numeric_limits<float>::infinity();  // Embree's "occluded" mark
}

RayHit bezierHit(const BezierTriangle& piece, const BezierHit& h, unsigned geometry,
                 unsigned primitive) {
  RayHit hit;
  hit.t = h.t;
  hit.geometry = geometry;
  hit.primitive = primitive;
  hit.u = h.u;
  hit.v = h.v;
  piece.positionAndNormal(h.u, h.v, hit.point, hit.geometricNormal);
  // Where ∂u × ∂v vanishes (a collapsed corner), the normal a hair towards the centre.
  if (hit.geometricNormal.squaredNorm() == 0.0)
    hit.geometricNormal =
        piece.normal(h.u + 1e-7 * (1.0 / 3.0 - h.u), h.v + 1e-7 * (1.0 / 3.0 - h.v));
  return hit;
}

// Embree's hit of a flat piece's triangle, again in double precision (Möller–Trumbore on the
// double ray), its (u, v) kept in the triangle; Embree's float one where the ray runs in the
// triangle's plane.
BezierHit flatPieceHit(const BezierTriangle& piece, const Ray& ray, const RTCRayHit& rayhit) {
  BezierHit h{double(rayhit.ray.tfar), double(rayhit.hit.u), double(rayhit.hit.v)};
  const Vec3& p0 = piece.at(4, 0, 0);
  const Vec3 e1 = piece.at(0, 4, 0) - p0, e2 = piece.at(0, 0, 4) - p0;
  const Vec3 pv = ray.direction.cross(e2);
  const double det = e1.dot(pv);
  if (!(std::abs(det) > 0.0)) return h;
  const Vec3 tv = ray.origin - p0;
  const Vec3 qv = tv.cross(e1);
  const double t = e2.dot(qv) / det;
  double u = tv.dot(pv) / det, v = ray.direction.dot(qv) / det;
  if (!std::isfinite(t) || !std::isfinite(u) || !std::isfinite(v)) return h;
  u = std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0 - u);
  return {t, u, v};
}

void bezierBounds(const RTCBoundsFunctionArguments* args) {
  acquireEdge(args->geometryUserPtr);
  const auto* g = static_cast<const BezierGeometry*>(args->geometryUserPtr);
  writeBounds(g->tracesSubPatches ? g->subPatches[args->primID].bounds()
                                  : (*g->pieces)[args->primID].bounds(),
              g->margin, g->origin, args->bounds_o);
  releaseEdge(&g->margin);
}

namespace {

// The (u, v) the ray leaves the piece from, when it was spawned from a hit of that piece.
const Vec2* leavesFrom(const Ray& ray, unsigned geometry, unsigned piece) {
  return ray.fromGeometry == geometry && ray.fromPrimitive == piece ? &ray.fromUV : nullptr;
}

}  // namespace

void intersectBezier(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* ctx = reinterpret_cast<TraceContext*>(args->context);
  auto* rayhit = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const auto* g = static_cast<const BezierGeometry*>(args->geometryUserPtr);
  const std::vector<BezierTriangle>& pieces = *g->pieces;
  if (ctx->hits) {  // allHits(): every hit of the piece, without shortening the ray
    const BezierTriangle& piece = pieces[args->primID];
    thread_local std::vector<BezierHit> found;
    found.clear();
    intersectBezierTriangleAll(piece, ctx->ray->origin, ctx->ray->direction, ctx->tnear,
                               ctx->ray->tfar, found);
    for (const BezierHit& h : found)
      ctx->hits->push_back(bezierHit(piece, h, args->geomID, args->primID));
    return;
  }
  // As intersectPatch: the nearest user-geometry hit so far bounds the search exactly.
  const bool userIsNearest =
      rayhit->hit.geomID == ctx->patchGeometry && rayhit->hit.primID == ctx->patchPrimitive;
  const double tmax = userIsNearest ? ctx->patchT : std::min(ctx->patchT, double(rayhit->ray.tfar));
  BezierHit h;
  unsigned primitive = args->primID;
  if (!g->tracesSubPatches) {
    if (!intersectBezierTriangle(pieces[primitive], ctx->ray->origin, ctx->ray->direction,
                                 ctx->tnear, tmax, h))
      return;
  } else {
    const BezierSubPatch& sub = g->subPatches[primitive];
    primitive = sub.piece;
    const BezierTriangle& piece = pieces[primitive];
    if (!intersectBezierSubPatch(piece, sub, ctx->ray->origin, ctx->ray->direction, ctx->tnear,
                                 tmax, h, leavesFrom(*ctx->ray, args->geomID, primitive)))
      return;
  }
  ctx->patchT = h.t;
  ctx->patchGeometry = args->geomID;
  ctx->patchPrimitive = primitive;
  ctx->patches = nullptr;
  ctx->pieces = &pieces;
  ctx->pieceU = h.u;
  ctx->pieceV = h.v;
  rayhit->ray.tfar = floatDown(h.t);
  rayhit->hit.geomID = args->geomID;
  rayhit->hit.primID = primitive;  // the piece's index, also for a sub-patch
  rayhit->hit.instID[0] = args->context->instID[0];
  rayhit->hit.u = float(h.u);
  rayhit->hit.v = float(h.v);
}

void occludedBezier(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* ctx = reinterpret_cast<const TraceContext*>(args->context);
  auto* ray = reinterpret_cast<RTCRay*>(args->ray);
  const auto* g = static_cast<const BezierGeometry*>(args->geometryUserPtr);
  const std::vector<BezierTriangle>& pieces = *g->pieces;
  bool hit;
  if (!g->tracesSubPatches) {
    hit = occludesBezierTriangle(pieces[args->primID], ctx->ray->origin, ctx->ray->direction,
                                 ctx->tnear, ctx->ray->tfar);
  } else {
    const BezierSubPatch& sub = g->subPatches[args->primID];
    const BezierTriangle& piece = pieces[sub.piece];
    hit = occludesBezierSubPatch(piece, sub, ctx->ray->origin, ctx->ray->direction, ctx->tnear,
                                 ctx->ray->tfar, leavesFrom(*ctx->ray, args->geomID, sub.piece));
  }
  if (hit) ray->tfar = -std::numeric_limits<float>::infinity();  // Embree's "occluded" mark
}

void fillRay(const Ray& ray, const Vec3& frame, RTCRay& out) {
  // Comparisons that a NaN fails as well.
  const auto inRange = [](const Vec3& v) {
    return std::abs(v.x()) <= Accel::kLargestRayCoordinate &&
           std::abs(v.y()) <= Accel::kLargestRayCoordinate &&
           std::abs(v.z()) <= Accel::kLargestRayCoordinate;
  };
  if (!inRange(ray.origin) || !inRange(ray.direction) || std::isnan(ray.tnear) ||
      std::isnan(ray.tfar))
    fail(
        "ray from ({}, {}, {}) along ({}, {}, {}), t in [{}, {}]: a coordinate beyond ±{:g} (the "
        "largest Embree traces) or not a number",
        ray.origin.x(), ray.origin.y(), ray.origin.z(), ray.direction.x(), ray.direction.y(),
        ray.direction.z(), ray.tnear, ray.tfar, Accel::kLargestRayCoordinate);
  out.org_x = float(ray.origin.x() - frame.x());
  out.org_y = float(ray.origin.y() - frame.y());
  out.org_z = float(ray.origin.z() - frame.z());
  out.dir_x = float(ray.direction.x());
  out.dir_y = float(ray.direction.y());
  out.dir_z = float(ray.direction.z());
  out.tnear = floatDown(std::max(ray.tnear, 0.0));
  out.tfar = floatUp(ray.tfar);
  out.time = 0.0f;
  out.mask = ~0u;
  out.id = 0;
  out.flags = 0;
}

// Embree reports errors through a callback from inside its C API, on the thread whose call

}  // namespace quadtri::accel_detail
