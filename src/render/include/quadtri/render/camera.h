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
    int width = 768;  ///< the whole film, in pixels
    int height = 576;
    /// Mitsuba's crop window: only film pixels [cropX, cropX + cropWidth) × [cropY, cropY +
    /// cropHeight) are rendered, and the image has the crop's size. 0 width/height: the film.
    int cropX = 0, cropY = 0, cropWidth = 0, cropHeight = 0;
    /// Where the optical axis meets the film, relative to the film's centre in units of the
    /// film's size (Mitsuba's principal_point_offset_x/y): the principal point is at film
    /// position ((0.5 + x)·width, (0.5 + y)·height), y measured down from the top.
    Vec2 principalPointOffset = Vec2::Zero();
  };
  explicit PerspectiveCamera(const Params& params);

  /// The primary ray through continuous film position `film` (pixels of the whole film, (0,0)
  /// = its top-left corner; image pixel (x, y) of a crop window is film pixel (x + cropX(),
  /// y + cropY())): with (px, py) the principal point, camera direction
  /// (tanX·(1 − 2(x − px + W/2)/W), tanY·(1 − 2(y − py + H/2)/H), 1), clipped to [near, far]
  /// measured along the camera's z axis, as Mitsuba does.
  Ray generateRay(const Vec2& film) const;

  /// The rendered image's size: the crop window's.
  int width() const { return cropWidth_; }
  int height() const { return cropHeight_; }
  /// The whole film's size, and where the crop window starts on it.
  int filmWidth() const { return params_.width; }
  int filmHeight() const { return params_.height; }
  int cropX() const { return params_.cropX; }
  int cropY() const { return params_.cropY; }
  /// Horizontal field of view in degrees after converting from fov_axis.
  double fovXDegrees() const { return fovX_; }

 private:
  Params params_;
  double fovX_ = 0.0;
  double tanHalfX_ = 0.0, tanHalfY_ = 0.0;
  int cropWidth_ = 0, cropHeight_ = 0;
};

}  // namespace quadtri
