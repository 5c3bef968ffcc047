// The pinhole camera of Mitsuba 3's `perspective` sensor.
#pragma once

#include "quadtri/geometry/accel.h"
#include "quadtri/math/vec.h"

namespace quadtri {

/// Which image extent the sensor's field of view spans (Mitsuba's fov_axis).
enum class FovAxis { X, Y, Diagonal, Smaller, Larger };

/// A perspective camera in Mitsuba 3's convention: in camera space it looks along +z with +y
/// up and +x to the image's *left* (lookat builds the frame (up×dir, dir×left, dir)), so image
/// column 0 is camera +x. `cameraToWorld` may scale; directions are normalised after mapping.
class PerspectiveCamera {
 public:
  struct Params {
    Mat4 cameraToWorld = Mat4::Identity();
    double fovDegrees = 45.0;
    FovAxis fovAxis = FovAxis::X;
    double nearClip = 1e-2;
    double farClip = 1e4;
    int width = 768;
    int height = 576;
  };
  explicit PerspectiveCamera(const Params& params);

  /// The primary ray through continuous film position `film` (pixels, (0,0) = top-left corner
  /// of the image): camera direction (tanX·(1 − 2x/W), tanY·(1 − 2y/H), 1), clipped to
  /// [near, far] measured along the camera's z axis, as Mitsuba does.
  Ray generateRay(const Vec2& film) const;

  int width() const { return params_.width; }
  int height() const { return params_.height; }
  /// Horizontal field of view in degrees after converting from fov_axis.
  double fovXDegrees() const { return fovX_; }

 private:
  Params params_;
  double fovX_ = 0.0;
  double tanHalfX_ = 0.0, tanHalfY_ = 0.0;
};

}  // namespace quadtri
