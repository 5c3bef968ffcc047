#include "quadtri/render/emitter/sphere_area_emitter.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"
#include "quadtri/render/sampling/warp.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

SphereAreaEmitter::SphereAreaEmitter(const Vec3& center, double radius, bool flipNormals,
                                     const Color& radiance)
    : center_(center),
      radius_(radius),
      orientation_(flipNormals ? -1.0 : 1.0),
      radiance_(radiance) {
  if (!radiance.allFinite() || (radiance < 0.0).any())
    fail("area emitter: expected a finite, non-negative radiance");
  if (!(radius > 0.0) || !std::isfinite(radius) || !allFinite(center))
    fail("area emitter on a sphere: expected a finite centre and a positive radius");
}

namespace {

// How far the sphere as the scene traces it (RenderScene::addSphere: a quadric in world
// coordinates) may lie from its exact point x: the bound RenderScene::interactionOf offsets a
// quadric hit by, for |x − c|² − r², whose gradient at x has length 2r.
double tracedSurfaceError(const Vec3& c, double r, const Vec3& x) {
  const QuadricCoeffs sphere = {1, 1,          1,          0,          0,
                                0, -2 * c.x(), -2 * c.y(), -2 * c.z(), c.squaredNorm() - r * r};
  return quadricRootError(sphere, x, 2.0 * r);
}

}  // namespace

std::optional<LightSample> SphereAreaEmitter::sampleLi(const Vec3& ref, const Vec2& u) const {
  const SphereDirectionSample cap = sampleSphereCap(ref, center_, radius_, u);
  if (!(cap.pdf > 0.0) || !(cap.distance > 0.0)) return std::nullopt;
  LightSample s;
  s.direction = cap.direction;
  s.distance = cap.distance;
  s.point = ref + cap.distance * cap.direction;
  const Vec3 normal = orientation_ * (s.point - center_) / radius_;
  s.normal = normal;
  s.radiance = eval(normal, -s.direction);
  if (isBlack(s.radiance)) return std::nullopt;
  s.pdf = cap.pdf;
  s.pointError = tracedSurfaceError(center_, radius_, s.point);
  return s;
}

double SphereAreaEmitter::pdfLi(const Vec3& ref, const Vec3& direction, const Vec3&,
                                const Vec3&) const {
  return sphereCapPdf(ref, center_, radius_, direction);
}

Color SphereAreaEmitter::eval(const Vec3& normal, const Vec3& w) const {
  return normal.dot(w) > 0.0 ? radiance_ : Color::Zero();
}

double SphereAreaEmitter::power(const Bounds3&) const {
  return kPi * luminance(radiance_) * 4.0 * kPi * radius_ * radius_;
}

std::string SphereAreaEmitter::toString() const {
  return fmt::format("area(radiance=[{}, {}, {}]) on sphere(center=[{}, {}, {}], radius={})",
                     radiance_[0], radiance_[1], radiance_[2], center_.x(), center_.y(),
                     center_.z(), radius_);
}

}  // namespace quadtri
