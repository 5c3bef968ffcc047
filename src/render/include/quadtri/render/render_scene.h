// Everything the integrators see: geometry in Embree with per-geometry shading data,
// materials, lights and the camera.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "quadtri/geometry/accel.h"
#include "quadtri/render/bsdf/bsdf.h"
#include "quadtri/render/camera.h"
#include "quadtri/render/emitter/emitter.h"
#include "quadtri/render/emitter/light_sampler.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

/// What one Embree geometry is made of and how it shades.
struct GeometryRecord {
  enum class Normals {
    Geometric,     ///< flat triangles: the face normal
    Interpolated,  ///< barycentric interpolation of per-corner normals, renormalised, no correction
    Gradient,      ///< quadric patches: the oriented, normalised gradient
    Surface,       ///< Bézier pieces: the oriented, normalised ∂u × ∂v of the piece
  } normals = Normals::Geometric;
  /// shading-offset: rays leaving towards the shading normal's side start from the lifted point
  /// of shadingOffsetPoint (only with Interpolated normals on triangles).
  bool liftRayOrigins = false;
  std::shared_ptr<const TriangleMesh> mesh;             ///< triangles, in world space
  const std::vector<QuadricPatch>* patches = nullptr;   ///< patches, in world space
  const std::vector<BezierTriangle>* bezier = nullptr;  ///< Bézier pieces, in world space
  std::shared_ptr<const void> owner;                    ///< keeps `patches` or `bezier` alive
  std::shared_ptr<const Bsdf> bsdf;
  const Emitter* emitter = nullptr;  ///< area light on this geometry, if any
};

/// A ray's hit with what shading needs, in world space.
struct SurfaceInteraction {
  Vec3 p;                ///< the hit point, on the surface to double precision
  Vec3 geometricNormal;  ///< unit; triangle winding or patch orientation, not flipped to the ray
  Vec3 shadingNormal;    ///< unit
  double t = 0.0;
  double offset = 0.0;  ///< distance along geometricNormal that clears the surface's float error
  /// With a lifting record (shading-offset): the shadow-terminator offset point of the hit, the
  /// origin of rays that leave towards the shading normal's side; equals p otherwise.
  Vec3 liftedP;
  bool lifted = false;
  const GeometryRecord* geometry = nullptr;
  uint32_t geometryId = ~0u;  ///< the id addModel returned for the geometry hit
  uint32_t primitive = ~0u;   ///< its triangle or patch (RayHit::primitive)
  Vec2 uv = Vec2::Zero();     ///< the hit's (u, v) on that primitive (RayHit::u, v)
};

class RenderScene {
 public:
  RenderScene();
  ~RenderScene();
  RenderScene(const RenderScene&) = delete;
  RenderScene& operator=(const RenderScene&) = delete;

  /// Adds a world-space model as the renderer draws it: its triangles (flat: face normals;
  /// shading: interpolated normals), its tessellation (interpolated surface normals), its
  /// quadric patches (gradient normals) or its Bézier pieces (their surface normals). With
  /// `areaRadiance`, the geometry is an area light; implicit and Bezier models cannot be (Error
  /// naming `name`). Returns the geometry's id
  /// (SurfaceInteraction::geometryId of its hits).
  uint32_t addModel(std::shared_ptr<const SurfaceModel> model, const Tessellation& tessellation,
                    std::shared_ptr<const Bsdf> bsdf, const std::optional<Color>& areaRadiance,
                    const std::string& name);
  /// Adds the analytic sphere |x − center| = radius mapped by `toWorld` (a quadric patch with no
  /// clip planes: an ellipsoid under non-uniform scale). An emitting sphere needs a similarity
  /// transform so it stays a sphere for cone sampling (Error otherwise).
  void addSphere(const Vec3& center, double radius, const Mat4& toWorld, bool flipNormals,
                 std::shared_ptr<const Bsdf> bsdf, const std::optional<Color>& areaRadiance,
                 const std::string& name);
  void addPointLight(const Vec3& position, const Color& intensity);
  /// Sets the constant environment (at most one; Error on a second).
  void setEnvironment(const Color& radiance);
  void setCamera(const PerspectiveCamera& camera) { camera_ = camera; }
  /// Builds the acceleration structure and the light sampler; no geometry may be added after.
  void commit();

  /// Nearest hit in (ray.tnear, ray.tfar).
  std::optional<SurfaceInteraction> intersect(const Ray& ray) const;
  /// intersect(rays[i]) for every ray, into out[i]: the rays are traced together in packets
  /// (Accel::intersect of several rays), which coherent rays (a pixel's camera rays) share.
  /// Where a ray hits two triangles at exactly the same t, the one it gets may depend on the
  /// other rays of its packet (Accel::intersect): callers that want results independent of
  /// threads keep the same rays together.
  void intersect(std::span<const Ray> rays, std::span<std::optional<SurfaceInteraction>> out) const;
  bool occluded(const Ray& ray) const { return accel_.occluded(ray); }
  /// A ray leaving `si` along unit `direction`, its origin pushed by si.offset along the
  /// geometric normal to the side `direction` leaves on, so it cannot find the surface it
  /// starts on (the float error of the hit is below the offset) yet does not skip a nearby one.
  /// On shading-offset geometry a ray with direction·shadingNormal > 0 (shadow rays and
  /// reflected BSDF rays alike) starts from si.liftedP instead of si.p before that push; rays
  /// into the surface (transmission) start from si.p.
  Ray spawnRay(const SurfaceInteraction& si, const Vec3& direction) const;
  /// A shadow ray from `si` to `target` on a surface of unit normal `targetNormal` (zero for a
  /// point in space): the target too is pushed off its surface, towards the ray's side, by its
  /// float error or by `targetError` where larger (LightSample::pointError), so a grazing
  /// shadow ray cannot find the light's own surface before its end.
  Ray spawnRayTo(const SurfaceInteraction& si, const Vec3& target, const Vec3& targetNormal,
                 double targetError = 0.0) const;

  const PerspectiveCamera& camera() const;
  const LightSampler& lightSampler() const { return lightSampler_; }
  const Emitter* environment() const { return environment_; }
  size_t primitiveCount() const { return primitives_; }
  size_t geometryBytes() const { return accel_.geometryBytes(); }
  /// Accel::patchPartBytes: what tracing long patches as parts took.
  size_t patchPartBytes() const { return accel_.patchPartBytes(); }
  const Bounds3& bounds() const { return bounds_; }

 private:
  uint32_t addRecord(GeometryRecord record, uint32_t geometryId);
  std::optional<SurfaceInteraction> interactionOf(const Ray& ray, const RayHit& hit) const;

  Accel accel_;
  std::vector<GeometryRecord> records_;  ///< indexed by Embree geometry id
  std::vector<std::unique_ptr<Emitter>> emitters_;
  const Emitter* environment_ = nullptr;
  LightSampler lightSampler_;
  std::optional<PerspectiveCamera> camera_;
  Bounds3 bounds_;
  Vec3 origin_ = Vec3::Zero();  ///< accel_.origin(): float error is relative to it
  size_t primitives_ = 0;
  bool committed_ = false;
};

/// The offset that clears float error around a point of magnitude `magnitude` (the largest
/// coordinate involved, relative to Accel::origin()): Embree stores vertices and ray origins as
/// floats, so a hit is only known to about 2^-24·magnitude; the offset is 2^-19·magnitude (32
/// float ulps).
inline double floatErrorOffset(double magnitude) {
  return 0x1.0p-19 * magnitude;
}

}  // namespace quadtri
