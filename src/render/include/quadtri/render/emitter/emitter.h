// The light source interface shared by point, area and environment emitters.
#pragma once

#include <optional>
#include <string>

#include "quadtri/math/color.h"
#include "quadtri/math/vec.h"

namespace quadtri {

/// Radiance arriving at a reference point from a sampled point of a light.
struct LightSample {
  Color radiance;              ///< Li at the reference point (for a point light I/d²)
  Vec3 direction;              ///< unit, from the reference point towards the light
  double distance = 0.0;       ///< to the light point (infinite for the environment)
  double pdf = 0.0;            ///< solid-angle density at the reference point (1 for delta lights)
  Vec3 point;                  ///< on the light (meaningless for the environment)
  Vec3 normal = Vec3::Zero();  ///< unit geometric normal at `point`; zero for point lights
  /// How far the light's surface as the scene traces it may lie from `point` along `normal`
  /// (beyond float rounding): a shadow ray stops that far short of it (RenderScene::spawnRayTo).
  double pointError = 0.0;
  bool delta = false;  ///< a Dirac light: no BSDF sampling strategy can hit it
};

class Emitter {
 public:
  virtual ~Emitter() = default;
  /// Samples a direction from `ref` towards the light with two uniforms; nullopt when the
  /// sample carries no radiance (the back of a one-sided light, a degenerate geometry).
  virtual std::optional<LightSample> sampleLi(const Vec3& ref, const Vec2& u) const = 0;
  /// Solid-angle density with which sampleLi picks `direction` from `ref`, when that direction
  /// reaches the light at `lightPoint` with unit geometric normal `lightNormal`.
  virtual double pdfLi(const Vec3& ref, const Vec3& direction, const Vec3& lightPoint,
                       const Vec3& lightNormal) const = 0;
  /// Radiance leaving the light towards unit direction `w`: for a surface light at a point with
  /// geometric normal `normal` (one-sided: zero when normal·w ≤ 0); for the environment the
  /// radiance travelling along w, i.e. seen by a ray of direction −w (`normal` is ignored).
  virtual Color eval(const Vec3& normal, const Vec3& w) const = 0;
  virtual bool isDelta() const { return false; }
  virtual bool isEnvironment() const { return false; }
  /// Luminance of the emitted flux (watts), used to pick lights in proportion to their power;
  /// the environment's flux is the one entering the scene's bounding sphere.
  virtual double power(const Bounds3& sceneBounds) const = 0;
  /// The parameters in Mitsuba syntax, for logs and error messages.
  virtual std::string toString() const = 0;
};

}  // namespace quadtri
