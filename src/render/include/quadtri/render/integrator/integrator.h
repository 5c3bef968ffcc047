// The integrator interface: radiance along one camera ray, one Monte Carlo sample at a time.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/math/color.h"

namespace quadtri {

class RenderScene;
struct SurfaceInteraction;

/// Per-pixel sampling that stops once the pixel is known well enough (the thesis' "adaptive
/// integration"): after each batch, once at least minSamples were taken, stop when the
/// standard error of the mean luminance is below threshold × the mean; never more than
/// maxSamples.
struct AdaptiveSampling {
  int minSamples = 16;
  int maxSamples = 1024;
  int batch = 16;
  double threshold = 0.01;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// One estimate of the radiance arriving at the camera along `ray`; `rays` counts every ray
  /// traced (camera, extension and shadow rays). Traces `ray` and calls radianceFrom.
  Color radiance(const RenderScene& scene, const Ray& ray, Pcg32& rng, uint64_t& rays) const;
  /// The same estimate when `ray` was already traced and `first` is its nearest hit
  /// (RenderScene::intersect(ray)): the renderer traces a pixel's camera rays together, in
  /// packets. The camera ray counts in `rays` here all the same.
  virtual Color radianceFrom(const RenderScene& scene, const Ray& ray,
                             const std::optional<SurfaceInteraction>& first, Pcg32& rng,
                             uint64_t& rays) const = 0;
  /// The adaptive stopping rule, or null to take a fixed number of samples per pixel.
  virtual const AdaptiveSampling* adaptive() const { return nullptr; }
  /// The parameters in Mitsuba syntax, for logs.
  virtual std::string toString() const = 0;
};

}  // namespace quadtri
