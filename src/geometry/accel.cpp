#include "quadtri/geometry/accel.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "accel_callbacks.h"
#include "quadtri/math/error.h"
#include "quadtri/math/frame_origin.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"

namespace quadtri {
namespace {

// A Bézier piece within this share of its box's diagonal of its corner triangle is traced as
// that triangle (far below what a float hit resolves).
constexpr double kFlatPieceTolerance = 1e-12;
// Embree's share of a user-geometry primitive: its build reference and its part of the BVH's
// nodes and leaves (charged for the parts of long patches, which the measured per-triangle
// costs leave out).
constexpr size_t kUserPrimitiveBytes = 128;

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

// Native triangles and user geometry are two Embree scenes (Accel::Impl::scenes).
enum SceneKind { kNative = 0, kUser = 1 };

// The largest coordinate of b relative to `frame`.
double extentFrom(const Bounds3& b, const Vec3& frame) {
  return std::max((b.lo - frame).cwiseAbs().maxCoeff(), (b.hi - frame).cwiseAbs().maxCoeff());
}

// Whether the ray meets box b within [t0, t1] (the slab test). The selections are written as
// the comparisons minsd and maxsd make, so they compile to those alone. A NaN step (a zero
// direction component with the origin in a face's plane) comes out as a miss, which a box
// grown beyond its contents (Accel::Impl::userReach) can afford.
bool meetsBox(const Bounds3& b, const Ray& ray, double t0, double t1) {
  for (int a = 0; a < 3; ++a) {
    const double inverse = 1.0 / ray.direction[a];
    const double tn = (b.lo[a] - ray.origin[a]) * inverse;
    const double tf = (b.hi[a] - ray.origin[a]) * inverse;
    const double near = tn < tf ? tn : tf, far = tn > tf ? tn : tf;
    t0 = near > t0 ? near : t0;
    t1 = far < t1 ? far : t1;
  }
  return t0 <= t1;
}

}  // namespace

struct Accel::Impl {
  Options options;
  RTCDevice device = nullptr;
  // Embree builds a BVH per kind of primitive and traverses every one of a scene for each ray,
  // and a traversal costs about 200 instructions before it tests a box, even of a BVH that the
  // ray misses at its root. So native triangles and user geometry are two scenes, and a ray
  // enters the user scene only where it meets that scene's bounds (`userReach`, grown for the
  // double ray) before its nearest triangle hit. Geometry ids run over both scenes
  // (rtcAttachGeometryByID).
  RTCScene scenes[2] = {nullptr, nullptr};
  size_t sceneGeometries[2] = {0, 0};
  Bounds3 userReach;  // in world coordinates
  // Every geometry's box in world coordinates, and the origin of the coordinates Embree holds,
  // chosen from it at commit (frameOrigin): a scene far from the world origin is traced in
  // floats relative to its own centre.
  Bounds3 added;
  Vec3 origin = Vec3::Zero();
  // Triangle geometries wait for the origin: their vertices in double precision, their index
  // buffer ready, their id reserved.
  struct PendingTriangles {
    uint32_t id;
    std::vector<double> positions;
    std::vector<uint32_t> indices;
  };
  std::vector<PendingTriangles> pendingTriangles;
  uint32_t nextId = 0;
  bool committed = false;
  size_t bytes = 0, partBytes = 0;
  std::vector<std::unique_ptr<accel_detail::PatchGeometry>>
      patchGeometries;  // stable user pointers
  std::vector<std::unique_ptr<accel_detail::BezierGeometry>> bezierGeometries;
  // By geometry id: the Bézier geometry whose flat pieces that native geometry holds.
  std::vector<const accel_detail::BezierGeometry*> flatOwner;
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
  // Attaches `geom` to scene `kind` under the next id and releases it; `what` names the step in
  // an error.
  uint32_t attach(RTCGeometry geom, SceneKind kind, const char* what) {
    const uint32_t id = nextId++;
    rtcAttachGeometryByID(scenes[kind], geom, id);
    rtcReleaseGeometry(geom);
    check(what);
    ++sceneGeometries[kind];
    return id;
  }
  // Reserves the next id for a triangle geometry handed to Embree at commit.
  uint32_t addPending(PendingTriangles pending, const Bounds3& box) {
    pending.id = nextId++;
    ++sceneGeometries[kNative];
    added.extend(box);
    bytes += (pending.positions.size() + pending.indices.size()) * sizeof(float);
    pendingTriangles.push_back(std::move(pending));
    return pendingTriangles.back().id;
  }
  // Hands a pending triangle geometry to Embree, its vertices as floats relative to `origin`.
  void attachTriangles(PendingTriangles& pending) {
    const size_t vertexCount = pending.positions.size() / 3;
    // The buffers are the Accel's, shared with Embree: large ones ask for huge pages before
    // they are filled (math/large_array.h). One float of padding: Embree reads the last vertex
    // with a 16-byte load.
    std::vector<float> vertexBuffer = largeVector<float>(pending.positions.size() + 1);
    for (size_t i = 0; i < vertexCount; ++i)
      for (int c = 0; c < 3; ++c)
        vertexBuffer[3 * i + size_t(c)] = float(pending.positions[3 * i + size_t(c)] - origin[c]);
    std::vector<double>().swap(pending.positions);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    check("creating a triangle geometry");
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               vertexBuffer.data(), 0, 3 * sizeof(float), vertexCount);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               pending.indices.data(), 0, 3 * sizeof(uint32_t),
                               pending.indices.size() / 3);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scenes[kNative], geom, pending.id);
    rtcReleaseGeometry(geom);
    check("attaching a triangle geometry");
    vertexBuffers.push_back(std::move(vertexBuffer));
    indexBuffers.push_back(std::move(pending.indices));
  }
  // One Embree user geometry of `count` primitives with these callbacks, attached to the user
  // scene; `what` names the step in an error.
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
    return attach(geom, kUser, what);
  }
  // Whether the ray may meet the user scene within [tnear, tfar]: it has geometry and the ray
  // meets its bounds there. (Native triangles are traced without the test: they are usually a
  // room that nearly every ray meets. Nor is the user scene tested when it is the only one:
  // the test would spare a ray only Embree's own test of the same box.)
  bool reachesUser(const Ray& ray, double tnear, double tfar) const {
    return sceneGeometries[kUser] != 0 &&
           (sceneGeometries[kNative] == 0 || meetsBox(userReach, ray, tnear, tfar));
  }
  void requireCommitted(const char* what) const {
    if (!committed) fail("{}: the acceleration structure has not been committed", what);
  }
  RayHit hitOf(const accel_detail::TraceContext& ctx, const Ray& ray, const RTCRayHit& rayhit,
               HitNormal normal) const;
};

Accel::Accel(const Options& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->device = sharedDevice();
  embreeError.clear();  // from an earlier structure's call on this thread, already reported
  for (RTCScene& scene : impl_->scenes) {
    scene = rtcNewScene(impl_->device);
    rtcSetSceneFlags(
        scene, RTCSceneFlags((options.robust ? RTC_SCENE_FLAG_ROBUST : 0) |
                             (options.collectHits ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION : 0)));
    impl_->check("creating the Embree scene");
  }
}

Accel::~Accel() {
  for (RTCScene scene : impl_->scenes)
    if (scene) rtcReleaseScene(scene);
}

uint32_t Accel::addTriangles(const TriangleMesh& mesh) {
  if (impl_->committed) fail("adding triangles: the acceleration structure is already committed");
  if (mesh.triangles.empty())
    fail("triangles for the acceleration structure: the mesh has no triangles");
  // Kept in double precision until commit, when the origin of Embree's coordinates is known.
  Impl::PendingTriangles pending{0, std::vector<double>(3 * mesh.positions.size()),
                                 largeVector<uint32_t>(3 * mesh.triangles.size())};
  // The entry check for any caller's mesh, made while copying (no second pass over a mesh the
  // loader has validated already): what Embree reads must be finite and within the range it
  // traces.
  constexpr const char* kWhat = "triangles for the acceleration structure";
  Bounds3 box;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = mesh.positions[i][c];
      if (!(std::abs(x) <= kLargestCoordinate))
        fail(
            "{}: vertex {} has a coordinate of {}: expected a finite number within ±{:g}, the "
            "largest Embree traces",
            kWhat, i, x, kLargestCoordinate);
      pending.positions[3 * i + size_t(c)] = x;
    }
    box.extend(mesh.positions[i]);
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = mesh.triangles[t][c];
      if (v >= mesh.positions.size())
        fail("{}: triangle {} corner {} indexes vertex {}, but there are only {} vertices", kWhat,
             t, c, v, mesh.positions.size());
      pending.indices[3 * t + size_t(c)] = v;
    }
  return impl_->addPending(std::move(pending), box);
}

uint32_t Accel::addQuadricPatches(const std::vector<QuadricPatch>& patches,
                                  const TriangleMesh* mesh) {
  if (impl_->committed)
    fail("adding quadric patches: the acceleration structure is already committed");
  // Checked in parallel blocks (a record each, 368 MB on a million triangles); the error names
  // the first bad patch, as a scan in order would.
  struct Scan {
    size_t firstBad = SIZE_MAX;
    int32_t badSide = 0;  // the side a bad bridge joins; 0 where the bounds are bad
    bool badBounds = false;
    Bounds3 box;
  };
  const Scan scan = parallelReduce(
      tbb::blocked_range<size_t>(0, patches.size(), 4096), Scan(),
      [&](const tbb::blocked_range<size_t>& range, Scan s) {
        for (size_t i = range.begin(); i != range.end() && i < s.firstBad; ++i) {
          const Bounds3& b = patches[i].bounds;
          if (b.empty() || !(b.lo.cwiseAbs().maxCoeff() <= kLargestCoordinate) ||
              !(b.hi.cwiseAbs().maxCoeff() <= kLargestCoordinate) || !allFinite(b.lo) ||
              !allFinite(b.hi)) {
            s.firstBad = i, s.badBounds = true;
            break;
          }
          for (int32_t side : patches[i].joins)
            if (patches[i].isBridge() &&
                (side < 0 || size_t(side) >= patches.size() || patches[size_t(side)].isBridge())) {
              s.firstBad = i, s.badSide = side;
              break;
            }
          if (s.firstBad == i) break;
          s.box.extend(b);
        }
        return s;
      },
      [](Scan a, const Scan& b) {
        if (b.firstBad < a.firstBad)
          a.firstBad = b.firstBad, a.badSide = b.badSide, a.badBounds = b.badBounds;
        a.box.extend(b.box);
        return a;
      });
  if (scan.firstBad != SIZE_MAX && scan.badBounds)
    fail(
        "quadric patch {}: its bounds are empty, not finite or beyond ±{:g} (the largest "
        "coordinate Embree traces)",
        scan.firstBad, kLargestCoordinate);
  if (scan.firstBad != SIZE_MAX)
    fail("quadric patch {}: a bridge must join two patches of the same geometry, not {}",
         scan.firstBad, scan.badSide);
  auto user = std::make_unique<accel_detail::PatchGeometry>();
  user->patches = &patches;
  user->bounds = scan.box;  // the margin is set at commit, from the origin
  impl_->added.extend(scan.box);
  // Collecting every hit needs each root once: those structures trace patches whole.
  if (mesh && !impl_->options.collectHits) user->parts = quadricPatchParts(patches, *mesh);
  const size_t primitives = user->parts.empty() ? patches.size() : user->parts.size();
  const uint32_t id = impl_->attachUserGeometry(
      primitives, user.get(), &accel_detail::patchBounds, &accel_detail::intersectPatch,
      &accel_detail::occludedPatch, "attaching the quadric patches");
  const size_t partBytes = user->parts.empty()
                               ? 0
                               : user->parts.size() * sizeof(QuadricPatchPart) +
                                     (user->parts.size() - patches.size()) * kUserPrimitiveBytes;
  impl_->bytes += patches.size() * sizeof(QuadricPatch) + partBytes;
  impl_->partBytes += partBytes;
  impl_->patchGeometries.push_back(std::move(user));
  return id;
}

uint32_t Accel::addBezierTriangles(const std::vector<BezierTriangle>& pieces) {
  if (impl_->committed)
    fail("adding Bézier pieces: the acceleration structure is already committed");
  if (pieces.empty()) fail("Bézier pieces for the acceleration structure: there are none");
  // The first piece with a point that is not finite, and the largest coordinate of the rest,
  // in parallel (3 pieces per triangle: a million-triangle mesh has 45 million points).
  struct Scan {
    size_t firstNonFinite = SIZE_MAX;
    Bounds3 box;
  };
  const Scan scan = parallelReduce(
      tbb::blocked_range<size_t>(0, pieces.size(), 4096), Scan(),
      [&](const tbb::blocked_range<size_t>& range, Scan s) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
          if (!std::all_of(pieces[i].b.begin(), pieces[i].b.end(), [](const Vec3& p) {
                return p.cwiseAbs().maxCoeff() <= kLargestCoordinate && allFinite(p);
              })) {
            s.firstNonFinite = std::min(s.firstNonFinite, i);
            continue;
          }
          s.box.extend(pieces[i].bounds());
        }
        return s;
      },
      [](Scan a, const Scan& b) {
        a.firstNonFinite = std::min(a.firstNonFinite, b.firstNonFinite);
        a.box.extend(b.box);
        return a;
      });
  if (scan.firstNonFinite != SIZE_MAX)
    fail(
        "Bézier piece {}: a control point is not finite or beyond ±{:g} (the largest coordinate "
        "Embree traces)",
        scan.firstNonFinite, kLargestCoordinate);
  auto user = std::make_unique<accel_detail::BezierGeometry>();
  user->pieces = &pieces;
  user->bounds = scan.box;  // the margin is set at commit, from the origin
  impl_->added.extend(scan.box);
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
  const uint32_t id = impl_->attachUserGeometry(
      primitives, user.get(), &accel_detail::bezierBounds, &accel_detail::intersectBezier,
      &accel_detail::occludedBezier, "attaching the Bézier pieces");
  user->id = id;
  impl_->bytes +=
      pieces.size() * sizeof(BezierTriangle) + user->subPatches.size() * sizeof(BezierSubPatch);
  if (!user->flatPieces.empty()) {
    // The corner triangles, straight into a pending geometry (the pieces were checked above).
    Impl::PendingTriangles flat{0, std::vector<double>(9 * user->flatPieces.size()),
                                largeVector<uint32_t>(3 * user->flatPieces.size())};
    Bounds3 box;
    for (size_t f = 0; f < user->flatPieces.size(); ++f) {
      const BezierTriangle& piece = pieces[user->flatPieces[f]];
      const Vec3 corners[3] = {piece.at(4, 0, 0), piece.at(0, 4, 0), piece.at(0, 0, 4)};
      for (size_t k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) flat.positions[9 * f + 3 * k + size_t(c)] = corners[k][c];
        flat.indices[3 * f + k] = uint32_t(3 * f + k);
        box.extend(corners[k]);
      }
    }
    user->flatGeometry = impl_->addPending(std::move(flat), box);
    if (impl_->flatOwner.size() <= user->flatGeometry)
      impl_->flatOwner.resize(user->flatGeometry + 1, nullptr);
    impl_->flatOwner[user->flatGeometry] = user.get();
    impl_->bytes += user->flatPieces.size() * sizeof(uint32_t);
  }
  impl_->bezierGeometries.push_back(std::move(user));
  return id;
}

void Accel::commit() {
  if (impl_->committed) return;
  impl_->origin = frameOrigin(impl_->added);
  // Each one leaves the list once attached, so that a failure leaves only those not attached.
  while (!impl_->pendingTriangles.empty()) {
    impl_->attachTriangles(impl_->pendingTriangles.back());
    impl_->pendingTriangles.pop_back();
  }
  // The double ray differs from Embree's float copy by about 6e-8 of its coordinates relative
  // to the origin: boxes grow by 1e-5 of the geometry's extent from there.
  for (const auto& g : impl_->patchGeometries) {
    g->origin = impl_->origin;
    g->margin = 1e-5 * extentFrom(g->bounds, impl_->origin);
  }
  for (const auto& g : impl_->bezierGeometries) {
    g->origin = impl_->origin;
    g->margin = 1e-5 * extentFrom(g->bounds, impl_->origin);
  }
  // Embree builds on its own (TBB) threads and calls the bounds functions there: for
  // ThreadSanitizer, everything before this call is ordered before them, and they before what
  // follows it (the user geometry's address and its margin's are the two edges' tokens).
  for (const auto& g : impl_->patchGeometries) releaseEdge(g.get());
  for (const auto& g : impl_->bezierGeometries) releaseEdge(g.get());
  for (RTCScene scene : impl_->scenes) rtcCommitScene(scene);
  if (impl_->sceneGeometries[kUser] != 0) {
    // The user scene's float bounds (its primitives' boxes, already grown for the double ray),
    // grown again by 1e-5 of their extent, against the slab test's own rounding.
    RTCBounds b;
    rtcGetSceneBounds(impl_->scenes[kUser], &b);
    Bounds3& r = impl_->userReach;
    r = Bounds3();
    r.extend(Vec3(b.lower_x, b.lower_y, b.lower_z));
    r.extend(Vec3(b.upper_x, b.upper_y, b.upper_z));
    r.inflate(1e-5 * std::max(r.lo.cwiseAbs().maxCoeff(), r.hi.cwiseAbs().maxCoeff()));
    // In world coordinates, where the rays' slab test is made: moved by the origin, grown by a
    // few of its double ulps.
    r.lo += impl_->origin;
    r.hi += impl_->origin;
    r.inflate(0x1.0p-50 * impl_->origin.cwiseAbs().maxCoeff());
  }
  for (const auto& g : impl_->patchGeometries) acquireEdge(&g->margin);
  for (const auto& g : impl_->bezierGeometries) acquireEdge(&g->margin);
  impl_->check("building the acceleration structure");
  impl_->committed = true;
}

// The hit a trace left in `rayhit` and `ctx` (a single ray's, or one lane's of a packet).
RayHit Accel::Impl::hitOf(const accel_detail::TraceContext& ctx, const Ray& ray,
                          const RTCRayHit& rayhit, HitNormal normal) const {
  RayHit hit;
  if (rayhit.hit.geomID == accel_detail::kInvalidId) return hit;
  if (rayhit.hit.geomID == ctx.patchGeometry && rayhit.hit.primID == ctx.patchPrimitive &&
      ctx.pieces)
    return accel_detail::bezierHit((*ctx.pieces)[rayhit.hit.primID],
                                   BezierHit{ctx.patchT, ctx.pieceU, ctx.pieceV}, rayhit.hit.geomID,
                                   rayhit.hit.primID);
  if (rayhit.hit.geomID == ctx.patchGeometry && rayhit.hit.primID == ctx.patchPrimitive)
    return accel_detail::patchHit(*ctx.patches, ray, ctx.patchT, rayhit.hit.geomID,
                                  rayhit.hit.primID, normal == HitNormal::Fill);
  if (rayhit.hit.geomID < flatOwner.size() && flatOwner[rayhit.hit.geomID]) {
    // A flat Bézier piece traced as its triangle: the hit is the piece's, at the same (u, v).
    const accel_detail::BezierGeometry& g = *flatOwner[rayhit.hit.geomID];
    const uint32_t piece = g.flatPieces[rayhit.hit.primID];
    return accel_detail::bezierHit((*g.pieces)[piece],
                                   accel_detail::flatPieceHit((*g.pieces)[piece], ray, rayhit),
                                   g.id, piece);
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

namespace {

void startTrace(accel_detail::TraceContext& ctx, const Ray& ray) {
  ctx.ray = &ray;
  ctx.tnear = std::max(ray.tnear, 0.0);
  ctx.patchT = ray.tfar;
}

}  // namespace

RayHit Accel::intersect(const Ray& ray, HitNormal normal) const {
  impl_->requireCommitted("intersect");
  accel_detail::TraceContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  startTrace(ctx, ray);
  RTCRayHit rayhit;
  accel_detail::fillRay(ray, impl_->origin, rayhit.ray);
  rayhit.hit.geomID = rayhit.hit.primID = rayhit.hit.instID[0] = accel_detail::kInvalidId;
  // Native triangles first: their hit bounds the user geometry's search (the callbacks read it
  // from rayhit, as they would in one scene), and the user scene is skipped where the ray
  // meets its bounds only beyond that hit.
  if (impl_->sceneGeometries[kNative] != 0)
    rtcIntersect1(impl_->scenes[kNative], &ctx.embree, &rayhit);
  if (impl_->reachesUser(ray, ctx.tnear, std::min(ray.tfar, double(rayhit.ray.tfar))))
    rtcIntersect1(impl_->scenes[kUser], &ctx.embree, &rayhit);
  return impl_->hitOf(ctx, ray, rayhit, normal);
}

void Accel::intersect(std::span<const Ray> rays, std::span<RayHit> hits, HitNormal normal) const {
  impl_->requireCommitted("intersect");
  if (hits.size() != rays.size())
    fail("intersect: {} rays but room for {} hits", rays.size(), hits.size());
  if (impl_->sceneGeometries[kNative] == 0) {
    // Only user geometry: its callbacks take one ray at a time, so a packet would only add the
    // copying in and out.
    for (size_t i = 0; i < rays.size(); ++i) hits[i] = intersect(rays[i], normal);
    return;
  }
  constexpr size_t kLanes = kPacketSize;
  for (size_t first = 0; first < rays.size(); first += kLanes) {
    const size_t n = std::min(kLanes, rays.size() - first);
    // Native triangles as one packet (no callbacks)...
    RTCIntersectContext packet;
    rtcInitIntersectContext(&packet);
    packet.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    RTCRayHit16 rayhit;
    alignas(64) int valid[kLanes];  // Embree loads the mask as one vector
    RTCRay singles[kLanes];         // each lane's float ray, kept for the user scene below
    for (size_t i = 0; i < kLanes; ++i) {
      valid[i] = i < n ? -1 : 0;
      rayhit.hit.geomID[i] = rayhit.hit.primID[i] = rayhit.hit.instID[0][i] =
          accel_detail::kInvalidId;
      RTCRay& single = singles[i];
      // An inactive lane gets a defined ray all the same, though Embree only reads the active.
      static const Ray kIdle{Vec3::Zero(), Vec3::UnitZ()};
      accel_detail::fillRay(i < n ? rays[first + i] : kIdle, impl_->origin, single);
      rayhit.ray.org_x[i] = single.org_x;
      rayhit.ray.org_y[i] = single.org_y;
      rayhit.ray.org_z[i] = single.org_z;
      rayhit.ray.dir_x[i] = single.dir_x;
      rayhit.ray.dir_y[i] = single.dir_y;
      rayhit.ray.dir_z[i] = single.dir_z;
      rayhit.ray.tnear[i] = single.tnear;
      rayhit.ray.tfar[i] = single.tfar;
      rayhit.ray.time[i] = single.time;
      rayhit.ray.mask[i] = single.mask;
      rayhit.ray.id[i] = single.id;
      rayhit.ray.flags[i] = single.flags;
    }
    rtcIntersect16(valid, impl_->scenes[kNative], &packet, &rayhit);
    // ...then each ray on its own through the user scene, where it meets the scene's bounds
    // before its triangle hit, as a single ray does.
    for (size_t i = 0; i < n; ++i) {
      const Ray& ray = rays[first + i];
      accel_detail::TraceContext ctx;
      startTrace(ctx, ray);
      RTCRayHit lane;
      lane.ray = singles[i];
      lane.ray.tfar = rayhit.ray.tfar[i];
      lane.hit.geomID = rayhit.hit.geomID[i];
      lane.hit.primID = rayhit.hit.primID[i];
      lane.hit.instID[0] = accel_detail::kInvalidId;
      if (lane.hit.geomID != accel_detail::kInvalidId) {  // Embree wrote the rest only on a hit
        lane.hit.u = rayhit.hit.u[i];
        lane.hit.v = rayhit.hit.v[i];
        lane.hit.Ng_x = rayhit.hit.Ng_x[i];
        lane.hit.Ng_y = rayhit.hit.Ng_y[i];
        lane.hit.Ng_z = rayhit.hit.Ng_z[i];
      }
      if (impl_->reachesUser(ray, ctx.tnear, std::min(ray.tfar, double(lane.ray.tfar)))) {
        rtcInitIntersectContext(&ctx.embree);
        rtcIntersect1(impl_->scenes[kUser], &ctx.embree, &lane);
      }
      hits[first + i] = impl_->hitOf(ctx, ray, lane, normal);
    }
  }
}

bool Accel::occluded(const Ray& ray) const {
  impl_->requireCommitted("occluded");
  accel_detail::TraceContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  ctx.ray = &ray;
  ctx.tnear = std::max(ray.tnear, 0.0);
  RTCRay r;
  accel_detail::fillRay(ray, impl_->origin, r);
  if (impl_->sceneGeometries[kNative] != 0) {
    rtcOccluded1(impl_->scenes[kNative], &ctx.embree, &r);
    if (r.tfar < 0.0f) return true;
  }
  if (impl_->reachesUser(ray, ctx.tnear, ray.tfar))
    rtcOccluded1(impl_->scenes[kUser], &ctx.embree, &r);
  return r.tfar < 0.0f;
}

void Accel::allHits(const Ray& ray, std::vector<RayHit>& hits) const {
  impl_->requireCommitted("allHits");
  if (!impl_->options.collectHits)
    fail("allHits: the acceleration structure was built without collectHits");
  accel_detail::TraceContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  ctx.embree.filter = &accel_detail::collectTriangleHit;
  ctx.ray = &ray;
  ctx.tnear = std::max(ray.tnear, 0.0);
  ctx.hits = &hits;
  RTCRayHit rayhit;
  accel_detail::fillRay(ray, impl_->origin, rayhit.ray);
  rayhit.hit.geomID = rayhit.hit.primID = rayhit.hit.instID[0] = accel_detail::kInvalidId;
  for (SceneKind kind : {kNative, kUser})
    if (impl_->sceneGeometries[kind] != 0) rtcIntersect1(impl_->scenes[kind], &ctx.embree, &rayhit);
}

size_t Accel::geometryBytes() const {
  return impl_->bytes;
}

size_t Accel::patchPartBytes() const {
  return impl_->partBytes;
}

Bounds3 Accel::bounds() const {
  impl_->requireCommitted("bounds");
  Bounds3 out;
  for (RTCScene scene : impl_->scenes) {
    RTCBounds b;
    rtcGetSceneBounds(scene, &b);
    if (b.lower_x <= b.upper_x) {
      out.extend(Vec3(b.lower_x, b.lower_y, b.lower_z));
      out.extend(Vec3(b.upper_x, b.upper_y, b.upper_z));
    }
  }
  if (out.empty()) return out;
  out.lo += impl_->origin;
  out.hi += impl_->origin;
  out.inflate(0x1.0p-50 * impl_->origin.cwiseAbs().maxCoeff());
  return out;
}

Vec3 Accel::origin() const {
  impl_->requireCommitted("origin");
  return impl_->origin;
}

bool Accel::robust() const {
  return impl_->options.robust;
}

void enableFlushToZero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

FlushToZeroScope::FlushToZeroScope() : mode_(_mm_getcsr()) {
  enableFlushToZero();
}

FlushToZeroScope::~FlushToZeroScope() {
  _mm_setcsr(mode_);
}

}  // namespace quadtri
