#include "quadtri/geometry/accel.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cmath>
#include <string>

#include "quadtri/math/error.h"
#include "quadtri/math/float_round.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/bezier_intersect.h"

namespace quadtri {
namespace {

constexpr unsigned kInvalidId = RTC_INVALID_GEOMETRY_ID;
// A Bézier piece within this share of its box's diagonal of its corner triangle is traced as
// that triangle (far below what a float hit resolves).
constexpr double kFlatPieceTolerance = 1e-12;

// What the patch callbacks need: the patches and how much to grow their bounds. The double ray
// differs from Embree's float copy by about 6e-8 of the distance travelled, so boxes grow by
// 1e-5 of the geometry's extent to never cull a hit of the double ray.
struct PatchGeometry {
  const std::vector<QuadricPatch>* patches = nullptr;
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

RayHit patchHit(const std::vector<QuadricPatch>& patches, const Ray& ray, double t,
                unsigned geometry, unsigned primitive, bool withNormal = true) {
  RayHit hit;
  hit.t = t;
  hit.geometry = geometry;
  hit.primitive = primitive;
  if (withNormal)
    hit.geometricNormal =
        safeNormalized(primitiveNormal(patches, primitive, ray.origin + t * ray.direction));
  return hit;
}

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

// Embree's float box holding b grown by `margin`.
void writeBounds(const Bounds3& b, double margin, RTCBounds* o) {
  o->lower_x = floatDown(b.lo.x() - margin);
  o->lower_y = floatDown(b.lo.y() - margin);
  o->lower_z = floatDown(b.lo.z() - margin);
  o->upper_x = floatUp(b.hi.x() + margin);
  o->upper_y = floatUp(b.hi.y() + margin);
  o->upper_z = floatUp(b.hi.z() + margin);
}

void patchBounds(const RTCBoundsFunctionArguments* args) {
  acquireEdge(args->geometryUserPtr);  // Accel::commit's release (ThreadSanitizer)
  const auto* g = static_cast<const PatchGeometry*>(args->geometryUserPtr);
  writeBounds((*g->patches)[args->primID].bounds, g->margin, args->bounds_o);
  releaseEdge(&g->margin);
}

// Accel traces single rays (rtcIntersect1/rtcOccluded1), so every callback sees N == 1.
void intersectPatch(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* ctx = reinterpret_cast<TraceContext*>(args->context);
  auto* rayhit = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const std::vector<QuadricPatch>& patches =
      *static_cast<const PatchGeometry*>(args->geometryUserPtr)->patches;
  if (ctx->hits) return collectPatchHits(patches, *ctx, args->geomID, args->primID);
  // While a patch is the nearest hit (or nothing is: both ids are then invalid and patchT is
  // the ray's tfar) its exact t bounds the search; after a triangle took over, its float t does.
  const bool patchIsNearest =
      rayhit->hit.geomID == ctx->patchGeometry && rayhit->hit.primID == ctx->patchPrimitive;
  const double tmax =
      patchIsNearest ? ctx->patchT : std::min(ctx->patchT, double(rayhit->ray.tfar));
  double t;
  if (!intersectPrimitive(patches, args->primID, ctx->ray->origin, ctx->ray->direction, ctx->tnear,
                          tmax, t))
    return;
  ctx->patchT = t;
  ctx->patchGeometry = args->geomID;
  ctx->patchPrimitive = args->primID;
  ctx->patches = &patches;
  ctx->pieces = nullptr;
  rayhit->ray.tfar = floatDown(t);
  rayhit->hit.geomID = args->geomID;
  rayhit->hit.primID = args->primID;
  rayhit->hit.instID[0] = args->context->instID[0];
  rayhit->hit.u = rayhit->hit.v = 0.0f;
}

void occludedPatch(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto* ctx = reinterpret_cast<const TraceContext*>(args->context);
  auto* ray = reinterpret_cast<RTCRay*>(args->ray);
  const std::vector<QuadricPatch>& patches =
      *static_cast<const PatchGeometry*>(args->geometryUserPtr)->patches;
  double t;
  if (intersectPrimitive(patches, args->primID, ctx->ray->origin, ctx->ray->direction, ctx->tnear,
                         ctx->ray->tfar, t))
    ray->tfar = -std::numeric_limits<float>::infinity();  // Embree's "occluded" mark
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
                                  : (*g->pieces)[args->primID].bounds,
              g->margin, args->bounds_o);
  releaseEdge(&g->margin);
}

// The (u, v) the ray leaves the piece from, when it was spawned from a hit of that piece.
const Vec2* leavesFrom(const Ray& ray, unsigned geometry, unsigned piece) {
  return ray.fromGeometry == geometry && ray.fromPrimitive == piece ? &ray.fromUV : nullptr;
}

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

void fillRay(const Ray& ray, RTCRay& out) {
  out.org_x = float(ray.origin.x());
  out.org_y = float(ray.origin.y());
  out.org_z = float(ray.origin.z());
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
// failed; throwing across it is not allowed, so each thread keeps its first message until
// Accel::Impl::check() throws it once the call has returned.
thread_local std::string embreeError;

void onEmbreeError(void*, RTCError code, const char* message) {
  if (embreeError.empty())
    embreeError = fmt::format("Embree error {}: {}", int(code), message ? message : "");
}

// One Embree device for the process. A device per acceleration structure started and
// reconfigured Embree's task scheduler every time, and structures built on several threads at
// once (a study, the soak) raced inside Embree's device set-up (ThreadSanitizer).
RTCDevice sharedDevice() {
  static const RTCDevice device = [] {
    const RTCDevice d = rtcNewDevice(nullptr);
    if (!d) fail("creating the Embree device failed (error {})", int(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(d, &onEmbreeError, nullptr);
    return d;
  }();
  return device;
}

}  // namespace

struct Accel::Impl {
  Options options;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  bool committed = false;
  size_t bytes = 0;
  std::vector<std::unique_ptr<PatchGeometry>> patchGeometries;  // stable user pointers
  std::vector<std::unique_ptr<BezierGeometry>> bezierGeometries;
  // By geometry id: the Bézier geometry whose flat pieces that native geometry holds.
  std::vector<const BezierGeometry*> flatOwner;
  // The triangle geometries' vertex and index buffers (Embree reads them in place).
  std::vector<std::vector<float>> vertexBuffers;
  std::vector<std::vector<uint32_t>> indexBuffers;

  // Throws this thread's pending Embree error, naming the step.
  static void check(const char* what) {
    if (!embreeError.empty()) {
      std::string message = std::move(embreeError);
      embreeError.clear();
      fail("{}: {}", what, message);
    }
  }
  // One Embree user geometry of `count` primitives with these callbacks, attached to the scene;
  // `what` names the step in an error.
  uint32_t attachUserGeometry(size_t count, void* user, RTCBoundsFunction bounds,
                              RTCIntersectFunctionN intersect, RTCOccludedFunctionN occluded,
                              const char* what) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    check("creating a user geometry");
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(count));
    rtcSetGeometryUserData(geom, user);
    rtcSetGeometryBoundsFunction(geom, bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, intersect);
    rtcSetGeometryOccludedFunction(geom, occluded);
    rtcCommitGeometry(geom);
    const uint32_t id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    check(what);
    return id;
  }
  void requireCommitted(const char* what) const {
    if (!committed) fail("{}: the acceleration structure has not been committed", what);
  }
};

Accel::Accel(const Options& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->device = sharedDevice();
  embreeError.clear();  // from an earlier structure's call on this thread, already reported
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(
      impl_->scene,
      RTCSceneFlags((options.robust ? RTC_SCENE_FLAG_ROBUST : 0) |
                    (options.collectHits ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION : 0)));
  impl_->check("creating the Embree scene");
}

Accel::~Accel() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
}

uint32_t Accel::addTriangles(const TriangleMesh& mesh) {
  if (impl_->committed) fail("adding triangles: the acceleration structure is already committed");
  if (mesh.triangles.empty())
    fail("triangles for the acceleration structure: the mesh has no triangles");
  // The buffers are the Accel's, shared with Embree: large ones ask for huge pages before they
  // are filled (math/large_array.h). One float of padding: Embree reads the last vertex with a
  // 16-byte load.
  std::vector<float> vertexBuffer = largeVector<float>(3 * mesh.positions.size() + 1);
  std::vector<uint32_t> indexBuffer = largeVector<uint32_t>(3 * mesh.triangles.size());
  float* vertices = vertexBuffer.data();
  uint32_t* indices = indexBuffer.data();
  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  impl_->check("creating a triangle geometry");
  // The entry check for any caller's mesh, made while copying (no second pass over a mesh the
  // loader has validated already): what Embree reads must be finite as float and in range.
  constexpr const char* kWhat = "triangles for the acceleration structure";
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float x = float(mesh.positions[i][c]);
      if (!std::isfinite(x)) {
        rtcReleaseGeometry(geom);
        fail("{}: vertex {} has a coordinate that is not a finite float ({})", kWhat, i,
             mesh.positions[i][c]);
      }
      vertices[3 * i + c] = x;
    }
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = mesh.triangles[t][c];
      if (v >= mesh.positions.size()) {
        rtcReleaseGeometry(geom);
        fail("{}: triangle {} corner {} indexes vertex {}, but there are only {} vertices", kWhat,
             t, c, v, mesh.positions.size());
      }
      indices[3 * t + c] = v;
    }
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices, 0,
                             3 * sizeof(float), mesh.positions.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0,
                             3 * sizeof(uint32_t), mesh.triangles.size());
  rtcCommitGeometry(geom);
  const uint32_t id = rtcAttachGeometry(impl_->scene, geom);
  rtcReleaseGeometry(geom);
  impl_->check("attaching a triangle geometry");
  impl_->vertexBuffers.push_back(std::move(vertexBuffer));
  impl_->indexBuffers.push_back(std::move(indexBuffer));
  impl_->bytes += (mesh.positions.size() + mesh.triangles.size()) * 3 * sizeof(float);
  return id;
}

uint32_t Accel::addQuadricPatches(const std::vector<QuadricPatch>& patches) {
  if (impl_->committed)
    fail("adding quadric patches: the acceleration structure is already committed");
  double extent = 0.0;
  for (size_t i = 0; i < patches.size(); ++i) {
    const Bounds3& b = patches[i].bounds;
    if (b.empty() || !allFinite(b.lo) || !allFinite(b.hi))
      fail("quadric patch {}: its bounds are empty or not finite", i);
    for (int32_t side : patches[i].joins)
      if (patches[i].isBridge() &&
          (side < 0 || size_t(side) >= patches.size() || patches[size_t(side)].isBridge()))
        fail("quadric patch {}: a bridge must join two patches of the same geometry, not {}", i,
             side);
    extent = std::max({extent, b.lo.cwiseAbs().maxCoeff(), b.hi.cwiseAbs().maxCoeff()});
  }
  auto user = std::make_unique<PatchGeometry>();
  user->patches = &patches;
  user->margin = 1e-5 * extent;
  const uint32_t id =
      impl_->attachUserGeometry(patches.size(), user.get(), &patchBounds, &intersectPatch,
                                &occludedPatch, "attaching the quadric patches");
  impl_->patchGeometries.push_back(std::move(user));
  impl_->bytes += patches.size() * sizeof(QuadricPatch);
  return id;
}

uint32_t Accel::addBezierTriangles(const std::vector<BezierTriangle>& pieces) {
  if (impl_->committed)
    fail("adding Bézier pieces: the acceleration structure is already committed");
  if (pieces.empty()) fail("Bézier pieces for the acceleration structure: there are none");
  double extent = 0.0;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const Bounds3& b = pieces[i].bounds;
    if (b.empty() || !allFinite(b.lo) || !allFinite(b.hi))
      fail("Bézier piece {}: its bounds are empty or not finite", i);
    for (const Vec3& p : pieces[i].b)
      if (!allFinite(p) || (p.array() < b.lo.array()).any() || (p.array() > b.hi.array()).any())
        fail("Bézier piece {}: a control point is not finite or outside the piece's bounds", i);
    extent = std::max({extent, b.lo.cwiseAbs().maxCoeff(), b.hi.cwiseAbs().maxCoeff()});
  }
  auto user = std::make_unique<BezierGeometry>();
  user->pieces = &pieces;
  user->margin = 1e-5 * extent;
  if (!impl_->options.collectHits) {
    user->tracesSubPatches = true;
    std::vector<char> flat(pieces.size(), 0);
    parallelFor(size_t(0), pieces.size(),
                [&](size_t i) { flat[i] = pieces[i].isAffine(kFlatPieceTolerance) ? 1 : 0; });
    for (size_t i = 0; i < pieces.size(); ++i)
      if (flat[i]) user->flatPieces.push_back(uint32_t(i));
    user->subPatches = bezierSubPatches(pieces);
    std::erase_if(user->subPatches,
                  [&](const BezierSubPatch& sub) { return flat[sub.piece] != 0; });
  }
  const size_t primitives = user->tracesSubPatches ? user->subPatches.size() : pieces.size();
  const uint32_t id =
      impl_->attachUserGeometry(primitives, user.get(), &bezierBounds, &intersectBezier,
                                &occludedBezier, "attaching the Bézier pieces");
  user->id = id;
  impl_->bytes +=
      pieces.size() * sizeof(BezierTriangle) + user->subPatches.size() * sizeof(BezierSubPatch);
  if (!user->flatPieces.empty()) {
    TriangleMesh flat;
    flat.positions.reserve(3 * user->flatPieces.size());
    flat.triangles.reserve(user->flatPieces.size());
    for (uint32_t p : user->flatPieces) {
      const BezierTriangle& piece = pieces[p];
      const uint32_t first = uint32_t(flat.positions.size());
      flat.positions.push_back(piece.at(4, 0, 0));
      flat.positions.push_back(piece.at(0, 4, 0));
      flat.positions.push_back(piece.at(0, 0, 4));
      flat.triangles.push_back({first, first + 1, first + 2});
    }
    user->flatGeometry = addTriangles(flat);
    if (impl_->flatOwner.size() <= user->flatGeometry)
      impl_->flatOwner.resize(user->flatGeometry + 1, nullptr);
    impl_->flatOwner[user->flatGeometry] = user.get();
    impl_->bytes += user->flatPieces.size() * sizeof(uint32_t);
  }
  impl_->bezierGeometries.push_back(std::move(user));
  return id;
}

void Accel::commit() {
  // Embree builds on its own (TBB) threads and calls the bounds functions there: for
  // ThreadSanitizer, everything before this call is ordered before them, and they before what
  // follows it (the user geometry's address and its margin's are the two edges' tokens).
  for (const auto& g : impl_->patchGeometries) releaseEdge(g.get());
  for (const auto& g : impl_->bezierGeometries) releaseEdge(g.get());
  rtcCommitScene(impl_->scene);
  for (const auto& g : impl_->patchGeometries) acquireEdge(&g->margin);
  for (const auto& g : impl_->bezierGeometries) acquireEdge(&g->margin);
  impl_->check("building the acceleration structure");
  impl_->committed = true;
}

RayHit Accel::intersect(const Ray& ray, HitNormal normal) const {
  impl_->requireCommitted("intersect");
  TraceContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  ctx.ray = &ray;
  ctx.tnear = std::max(ray.tnear, 0.0);
  ctx.patchT = ray.tfar;
  RTCRayHit rayhit;
  fillRay(ray, rayhit.ray);
  rayhit.hit.geomID = rayhit.hit.primID = rayhit.hit.instID[0] = kInvalidId;
  rtcIntersect1(impl_->scene, &ctx.embree, &rayhit);
  RayHit hit;
  if (rayhit.hit.geomID == kInvalidId) return hit;
  if (rayhit.hit.geomID == ctx.patchGeometry && rayhit.hit.primID == ctx.patchPrimitive &&
      ctx.pieces)
    return bezierHit((*ctx.pieces)[rayhit.hit.primID],
                     BezierHit{ctx.patchT, ctx.pieceU, ctx.pieceV}, rayhit.hit.geomID,
                     rayhit.hit.primID);
  if (rayhit.hit.geomID == ctx.patchGeometry && rayhit.hit.primID == ctx.patchPrimitive)
    return patchHit(*ctx.patches, ray, ctx.patchT, rayhit.hit.geomID, rayhit.hit.primID,
                    normal == HitNormal::Fill);
  if (rayhit.hit.geomID < impl_->flatOwner.size() && impl_->flatOwner[rayhit.hit.geomID]) {
    // A flat Bézier piece traced as its triangle: the hit is the piece's, at the same (u, v).
    const BezierGeometry& g = *impl_->flatOwner[rayhit.hit.geomID];
    const uint32_t piece = g.flatPieces[rayhit.hit.primID];
    return bezierHit((*g.pieces)[piece], flatPieceHit((*g.pieces)[piece], ray, rayhit), g.id,
                     piece);
  }
  hit.t = rayhit.ray.tfar;
  hit.geometry = rayhit.hit.geomID;
  hit.primitive = rayhit.hit.primID;
  hit.u = rayhit.hit.u;
  hit.v = rayhit.hit.v;
  // Embree's Ng is (v1 - v0) × (v2 - v0) for triangles, the same side as faceNormal().
  if (normal == HitNormal::Fill)
    hit.geometricNormal = safeNormalized(Vec3(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z));
  return hit;
}

bool Accel::occluded(const Ray& ray) const {
  impl_->requireCommitted("occluded");
  TraceContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  ctx.ray = &ray;
  ctx.tnear = std::max(ray.tnear, 0.0);
  RTCRay r;
  fillRay(ray, r);
  rtcOccluded1(impl_->scene, &ctx.embree, &r);
  return r.tfar < 0.0f;
}

void Accel::allHits(const Ray& ray, std::vector<RayHit>& hits) const {
  impl_->requireCommitted("allHits");
  if (!impl_->options.collectHits)
    fail("allHits: the acceleration structure was built without collectHits");
  TraceContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  ctx.embree.filter = &collectTriangleHit;
  ctx.ray = &ray;
  ctx.tnear = std::max(ray.tnear, 0.0);
  ctx.hits = &hits;
  RTCRayHit rayhit;
  fillRay(ray, rayhit.ray);
  rayhit.hit.geomID = rayhit.hit.primID = rayhit.hit.instID[0] = kInvalidId;
  rtcIntersect1(impl_->scene, &ctx.embree, &rayhit);
}

size_t Accel::geometryBytes() const {
  return impl_->bytes;
}

Bounds3 Accel::bounds() const {
  impl_->requireCommitted("bounds");
  RTCBounds b;
  rtcGetSceneBounds(impl_->scene, &b);
  Bounds3 out;
  if (b.lower_x <= b.upper_x) {
    out.extend(Vec3(b.lower_x, b.lower_y, b.lower_z));
    out.extend(Vec3(b.upper_x, b.upper_y, b.upper_z));
  }
  return out;
}

bool Accel::robust() const {
  return impl_->options.robust;
}

void enableFlushToZero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace quadtri
