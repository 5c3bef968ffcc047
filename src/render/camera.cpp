#include "quadtri/render/camera.h"

#include "quadtri/math/error.h"

namespace quadtri {
namespace {

constexpr double kDegToRad = kPi / 180.0;

// Mitsuba 3 stores every fov as the horizontal one; these are its conversions.
double horizontalFov(double fov, FovAxis axis, double aspect) {
  const auto fromVertical = [&] {
    return 2.0 * std::atan(std::tan(0.5 * fov * kDegToRad) * aspect) / kDegToRad;
  };
  switch (axis) {
    case FovAxis::X:
      return fov;
    case FovAxis::Y:
      return fromVertical();
    case FovAxis::Diagonal: {
      const double diagonal = 2.0 * std::tan(0.5 * fov * kDegToRad);
      const double width = diagonal / std::sqrt(1.0 + 1.0 / (aspect * aspect));
      return 2.0 * std::atan(0.5 * width) / kDegToRad;
    }
    case FovAxis::Smaller:
      return aspect > 1.0 ? fromVertical() : fov;
    case FovAxis::Larger:
      return aspect > 1.0 ? fov : fromVertical();
  }
  return fov;
}

}  // namespace

PerspectiveCamera::PerspectiveCamera(const Params& params) : params_(params) {
  if (params.width <= 0 || params.height <= 0)
    fail("film size {}x{}: expected positive width and height", params.width, params.height);
  if (!(params.fovDegrees > 0.0 && params.fovDegrees < 180.0))
    fail("fov {}: expected an angle in (0, 180) degrees", params.fovDegrees);
  if (!(params.nearClip > 0.0 && params.farClip > params.nearClip))
    fail("near_clip {} and far_clip {}: expected 0 < near_clip < far_clip", params.nearClip,
         params.farClip);
  if (!params.cameraToWorld.allFinite() ||
      std::abs(params.cameraToWorld.topLeftCorner<3, 3>().determinant()) == 0.0)
    fail("camera to_world: expected a finite, invertible matrix");
  cropWidth_ = params.cropWidth > 0 ? params.cropWidth : params.width - params.cropX;
  cropHeight_ = params.cropHeight > 0 ? params.cropHeight : params.height - params.cropY;
  if (params.cropX < 0 || params.cropY < 0 || cropWidth_ <= 0 || cropHeight_ <= 0 ||
      params.cropX + cropWidth_ > params.width || params.cropY + cropHeight_ > params.height)
    fail("crop window {}x{} at ({}, {}): expected a non-empty window inside the {}x{} film",
         cropWidth_, cropHeight_, params.cropX, params.cropY, params.width, params.height);
  if (!params.principalPointOffset.allFinite())
    fail("principal point offset: expected finite numbers");
  const double aspect = double(params.width) / double(params.height);
  fovX_ = horizontalFov(params.fovDegrees, params.fovAxis, aspect);
  if (!(fovX_ > 0.0 && fovX_ < 180.0))
    fail("fov {}: the horizontal field of view {} is not in (0, 180)", params.fovDegrees, fovX_);
  tanHalfX_ = std::tan(0.5 * fovX_ * kDegToRad);
  tanHalfY_ = tanHalfX_ / aspect;
}

Ray PerspectiveCamera::generateRay(const Vec2& film) const {
  // Film position relative to the principal point, as a fraction of the film: 0.5 at the
  // principal point, which is the film's centre unless principal_point_offset moves it.
  const double fx = film.x() / params_.width - params_.principalPointOffset.x();
  const double fy = film.y() / params_.height - params_.principalPointOffset.y();
  // The direction in camera space at unit depth; normalised once, after the rotation to world
  // space (which may also scale).
  const Vec3 local(tanHalfX_ * (1.0 - 2.0 * fx), tanHalfY_ * (1.0 - 2.0 * fy), 1.0);
  const Mat4& m = params_.cameraToWorld;
  Ray ray;
  ray.direction = safeNormalized(m.topLeftCorner<3, 3>() * local);
  ray.origin = m.topRightCorner<3, 1>();
  // Clip planes are distances along the camera's z axis, so they depend on the pixel: depth z
  // is reached after z·|local| along the unit direction.
  const double length = local.norm();
  ray.tnear = params_.nearClip * length;
  ray.tfar = params_.farClip * length;
  return ray;
}

}  // namespace quadtri
