#include "quadtri/render/render_scene.h"

#include <array>

#include "quadtri/geometry/model_geometry.h"
#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/render/emitter/constant_emitter.h"
#include "quadtri/render/emitter/mesh_area_emitter.h"
#include "quadtri/render/emitter/point_emitter.h"
#include "quadtri/render/emitter/sphere_area_emitter.h"
#include "quadtri/surface/quadric_patch.h"
#include "quadtri/surface/shading_offset.h"

namespace quadtri {
namespace {

double maxAbs(const Vec3& v) {
  return v.cwiseAbs().maxCoeff();
}

// Coefficients A..J of the quadric xᵀ Q x = 0 for a symmetric 4×4 Q over (x, y, z, 1).
QuadricCoeffs coeffsFromMatrix(const Mat4& q) {
  return {q(0, 0),     q(1, 1),     q(2, 2),     2 * q(0, 1), 2 * q(0, 2),
          2 * q(1, 2), 2 * q(0, 3), 2 * q(1, 3), 2 * q(2, 3), q(3, 3)};
}

// The box of every element's box (a million or more on a large mesh: in parallel).
template <typename T, typename Box>
Bounds3 boundsOf(const std::vector<T>& items, const Box& box) {
  return parallelReduce(
      tbb::blocked_range<size_t>(0, items.size(), 4096), Bounds3(),
      [&](const tbb::blocked_range<size_t>& range, Bounds3 sum) {
        for (size_t i = range.begin(); i != range.end(); ++i) sum.extend(box(items[i]));
        return sum;
      },
      [](Bounds3 a, const Bounds3& b) {
        a.extend(b);
        return a;
      });
}

}  // namespace

RenderScene::RenderScene() = default;
RenderScene::~RenderScene() = default;

uint32_t RenderScene::addRecord(GeometryRecord record, uint32_t geometryId) {
  if (geometryId >= records_.size()) records_.resize(geometryId + 1);
  records_[geometryId] = std::move(record);
  return geometryId;
}

uint32_t RenderScene::addModel(std::shared_ptr<const SurfaceModel> model,
                               const Tessellation& tessellation, std::shared_ptr<const Bsdf> bsdf,
                               const std::optional<Color>& areaRadiance, const std::string& name) {
  if (committed_) fail("{}: geometry added after the scene was committed", name);
  GeometryRecord record;
  record.bsdf = std::move(bsdf);
  ModelGeometry geometry = modelGeometry(*model, tessellation);
  // Refused before anything is counted, so a failed call leaves the scene as it was.
  if (geometry.bezier && areaRadiance)
    fail("{}: an area emitter needs triangles or a sphere, not the Bézier model '{}'", name,
         model->name());
  primitives_ += geometry.primitiveCount();
  if (geometry.bezier) {
    record.normals = GeometryRecord::Normals::Surface;
    record.bezier = geometry.bezier;
    bounds_.extend(
        boundsOf(*geometry.bezier, [](const BezierTriangle& piece) { return piece.bounds(); }));
    record.owner = model;
    return addRecord(std::move(record), addModelGeometry(accel_, geometry));
  }
  if (geometry.patches) {
    if (areaRadiance)
      fail("{}: an area emitter needs triangles or a sphere, not the implicit model '{}'", name,
           model->name());
    record.normals = GeometryRecord::Normals::Gradient;
    record.patches = geometry.patches;
    bounds_.extend(
        boundsOf(*geometry.patches, [](const QuadricPatch& patch) { return patch.bounds; }));
    record.owner = model;
    return addRecord(std::move(record), addModelGeometry(accel_, geometry));
  }
  record.normals = geometry.shadingNormals ? GeometryRecord::Normals::Interpolated
                                           : GeometryRecord::Normals::Geometric;
  record.liftRayOrigins = geometry.liftRayOrigins;
  record.mesh = std::make_shared<TriangleMesh>(std::move(geometry.triangles));
  bounds_.extend(record.mesh->bounds());
  if (areaRadiance) {
    emitters_.push_back(std::make_unique<MeshAreaEmitter>(record.mesh, *areaRadiance));
    record.emitter = emitters_.back().get();
  }
  const uint32_t id = accel_.addTriangles(*record.mesh);
  return addRecord(std::move(record), id);
}

void RenderScene::addSphere(const Vec3& center, double radius, const Mat4& toWorld,
                            bool flipNormals, std::shared_ptr<const Bsdf> bsdf,
                            const std::optional<Color>& areaRadiance, const std::string& name) {
  if (committed_) fail("{}: geometry added after the scene was committed", name);
  if (!(radius > 0.0) || !std::isfinite(radius) || !allFinite(center))
    fail("{}: expected a finite centre and a positive radius (got {})", name, radius);
  const Mat3 linear = toWorld.topLeftCorner<3, 3>();
  if (!toWorld.allFinite() || !(std::abs(linear.determinant()) > 0.0))
    fail("{}: to_world is not a finite, invertible transform", name);
  // Object space: |x − c|² − r² as a symmetric matrix over homogeneous points; world space:
  // Q_world = M⁻ᵀ Q M⁻¹, scaled so its quadratic part has unit size (keeps the sign, so the
  // gradient still points outwards).
  Mat4 objectQ = Mat4::Identity();
  objectQ.topRightCorner<3, 1>() = -center;
  objectQ.bottomLeftCorner<1, 3>() = -center.transpose();
  objectQ(3, 3) = center.squaredNorm() - radius * radius;
  const Mat4 inverse = toWorld.inverse();
  Mat4 worldQ = inverse.transpose() * objectQ * inverse;
  worldQ = 0.5 * (worldQ + worldQ.transpose()).eval();
  worldQ /= worldQ.topLeftCorner<3, 3>().cwiseAbs().maxCoeff();

  auto patches = std::make_shared<std::vector<QuadricPatch>>(1);
  QuadricPatch& patch = patches->front();
  patch.q = coeffsFromMatrix(worldQ);
  patch.orientation = flipNormals ? -1.0 : 1.0;
  // The image of the sphere's box: half extent along world axis i is r·|row i of the linear part|.
  const Vec3 worldCenter = (toWorld * center.homogeneous()).head<3>();
  const Vec3 halfExtent = radius * linear.rowwise().norm();
  patch.bounds.extend(worldCenter - halfExtent);
  patch.bounds.extend(worldCenter + halfExtent);
  // Roots at the silhouette may round just outside the exact box.
  patch.bounds.inflate(1e-9 * (maxAbs(worldCenter) + halfExtent.maxCoeff()));
  bounds_.extend(patch.bounds);
  primitives_ += 1;

  GeometryRecord record;
  record.normals = GeometryRecord::Normals::Gradient;
  record.patches = patches.get();
  record.owner = patches;
  record.bsdf = std::move(bsdf);
  if (areaRadiance) {
    const Mat3 gram = linear.transpose() * linear;
    const double scale2 = gram.trace() / 3.0;
    if (!(gram - scale2 * Mat3::Identity()).isZero(1e-9 * scale2))
      fail(
          "{}: an emitting sphere's to_world must be a similarity (rotation, uniform scale, "
          "translation)",
          name);
    emitters_.push_back(std::make_unique<SphereAreaEmitter>(worldCenter, radius * std::sqrt(scale2),
                                                            flipNormals, *areaRadiance));
    record.emitter = emitters_.back().get();
  }
  addRecord(std::move(record), accel_.addQuadricPatches(*patches));
}

void RenderScene::addPointLight(const Vec3& position, const Color& intensity) {
  emitters_.push_back(std::make_unique<PointEmitter>(position, intensity));
}

void RenderScene::setEnvironment(const Color& radiance) {
  if (environment_) fail("the scene has more than one environment emitter");
  emitters_.push_back(std::make_unique<ConstantEmitter>(radiance));
  environment_ = emitters_.back().get();
}

void RenderScene::commit() {
  if (committed_) return;
  accel_.commit();
  origin_ = accel_.origin();
  std::vector<const Emitter*> lights;
  for (const auto& e : emitters_) lights.push_back(e.get());
  lightSampler_ = LightSampler(std::move(lights), bounds_);
  committed_ = true;
}

const PerspectiveCamera& RenderScene::camera() const {
  if (!camera_) fail("the scene has no sensor");
  return *camera_;
}

std::optional<SurfaceInteraction> RenderScene::intersect(const Ray& ray) const {
  // Triangle and patch normals are derived from the double-precision hit (interactionOf).
  return interactionOf(ray, accel_.intersect(ray, Accel::HitNormal::Skip));
}

void RenderScene::intersect(std::span<const Ray> rays,
                            std::span<std::optional<SurfaceInteraction>> out) const {
  if (out.size() != rays.size())
    fail("intersect: {} rays but room for {} interactions", rays.size(), out.size());
  std::array<RayHit, Accel::kPacketSize> hits;
  for (size_t first = 0; first < rays.size(); first += hits.size()) {
    const size_t n = std::min(hits.size(), rays.size() - first);
    accel_.intersect(rays.subspan(first, n), std::span(hits).first(n), Accel::HitNormal::Skip);
    for (size_t i = 0; i < n; ++i) out[first + i] = interactionOf(rays[first + i], hits[i]);
  }
}

std::optional<SurfaceInteraction> RenderScene::interactionOf(const Ray& ray,
                                                             const RayHit& hit) const {
  if (!hit.valid()) return std::nullopt;
  const GeometryRecord& record = records_[hit.geometry];
  SurfaceInteraction si;
  si.t = hit.t;
  si.geometry = &record;
  si.geometryId = hit.geometry;
  si.primitive = hit.primitive;
  si.uv = Vec2(hit.u, hit.v);
  if (record.bezier) {
    // The exact surface point of the piece at the double-precision (u, v) of the hit.
    const BezierTriangle& piece = (*record.bezier)[hit.primitive];
    si.p = hit.point;
    si.geometricNormal = hit.geometricNormal;
    if (si.geometricNormal.squaredNorm() == 0.0) si.geometricNormal = -ray.direction;
    si.shadingNormal = si.geometricNormal;
    // The largest coordinate of the hit and of the piece's control points (those of its box's
    // corners, without building the box).
    double extent = maxAbs(si.p - origin_);
    for (const Vec3& c : piece.b) extent = std::max(extent, maxAbs(c - origin_));
    si.offset = floatErrorOffset(extent);
    si.liftedP = si.p;
    return si;
  }
  if (record.patches) {
    const QuadricPatch& patch = (*record.patches)[hit.primitive];
    // Embree hands back t as a float: one Newton step along the gradient puts the point back
    // on q = 0 to double precision.
    Vec3 p = ray.origin + hit.t * ray.direction;
    const Vec3 g = quadricGradient(patch.q, p);
    if (g.squaredNorm() > 0.0) p -= (evalQuadric(patch.q, p) / g.squaredNorm()) * g;
    si.p = p;
    const std::vector<QuadricPatch>& patches = *record.patches;
    si.geometricNormal = primitiveNormal(patches, hit.primitive, p);
    if (si.geometricNormal.squaredNorm() == 0.0) si.geometricNormal = -ray.direction;
    si.shadingNormal =
        patch.isBridge() ? primitiveShadingNormal(patches, hit.primitive, p) : si.geometricNormal;
    // The float error of the boxes and ray copies Embree holds, or, where larger (a quadric
    // far from the world origin), 32 units of rounding of the root the quadric gives.
    si.offset =
        std::max(floatErrorOffset(std::max({maxAbs(p - origin_), maxAbs(patch.bounds.lo - origin_),
                                            maxAbs(patch.bounds.hi - origin_)})),
                 quadricRootError(patch.q, p, g.norm()));
    si.liftedP = p;
    return si;
  }
  const TriangleMesh& mesh = *record.mesh;
  const size_t t = hit.primitive;
  const double b0 = 1.0 - hit.u - hit.v;
  // From the double-precision vertices, so the point lies in the triangle's plane exactly.
  si.p = b0 * mesh.corner(t, 0) + hit.u * mesh.corner(t, 1) + hit.v * mesh.corner(t, 2);
  si.geometricNormal = mesh.faceNormal(t);
  si.shadingNormal = si.geometricNormal;
  if (record.normals == GeometryRecord::Normals::Interpolated)
    si.shadingNormal =
        safeNormalized(b0 * mesh.cornerNormal(t, 0) + hit.u * mesh.cornerNormal(t, 1) +
                           hit.v * mesh.cornerNormal(t, 2),
                       si.geometricNormal);
  si.offset = floatErrorOffset(
      std::max({maxAbs(mesh.corner(t, 0) - origin_), maxAbs(mesh.corner(t, 1) - origin_),
                maxAbs(mesh.corner(t, 2) - origin_)}));
  if (record.liftRayOrigins) {
    si.liftedP = shadingOffsetPoint(mesh, t, Vec3(b0, hit.u, hit.v));
    si.lifted = true;
  } else {
    si.liftedP = si.p;
  }
  return si;
}

Ray RenderScene::spawnRay(const SurfaceInteraction& si, const Vec3& direction) const {
  Ray ray;
  const double side = direction.dot(si.geometricNormal) >= 0.0 ? 1.0 : -1.0;
  const Vec3& base = si.lifted && direction.dot(si.shadingNormal) > 0.0 ? si.liftedP : si.p;
  ray.origin = base + side * si.offset * si.geometricNormal;
  ray.direction = direction;
  ray.tnear = 0.0;
  ray.tfar = kInfinity;
  ray.fromGeometry = si.geometryId;
  ray.fromPrimitive = si.primitive;
  ray.fromUV = si.uv;
  return ray;
}

Ray RenderScene::spawnRayTo(const SurfaceInteraction& si, const Vec3& target,
                            const Vec3& targetNormal, double targetError) const {
  // spawnRay only needs the direction's side of the two normals, not its length (+z for a
  // target at the point itself, as safeNormalized gives).
  const Vec3 toTarget = target - si.p;
  Ray ray = spawnRay(si, toTarget != Vec3::Zero() ? toTarget : Vec3(Vec3::UnitZ()));
  const double side = targetNormal.dot(ray.origin - target) >= 0.0 ? 1.0 : -1.0;
  const Vec3 end = target + side *
                                std::max(floatErrorOffset(maxAbs(target - origin_)), targetError) *
                                targetNormal;
  const Vec3 toEnd = end - ray.origin;
  ray.direction = safeNormalized(toEnd, ray.tfar);
  return ray;
}

}  // namespace quadtri
