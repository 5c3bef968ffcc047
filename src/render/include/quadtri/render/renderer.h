// Rendering an image: tiles in parallel, one independent random stream per pixel.
#pragma once

#include <atomic>
#include <cstdint>

#include "quadtri/render/filter.h"
#include "quadtri/render/image_io.h"
#include "quadtri/render/integrator/integrator.h"

namespace quadtri {

class RenderScene;

struct RenderOptions {
  int samplesPerPixel = 16;  ///< fixed count; adaptive integrators use their own bounds
  uint64_t seed = 0;
  int threads = 0;              ///< 0: every hardware thread
  double timeLimitSeconds = 0;  ///< 0: none; otherwise pixels not started in time stay black
  ReconstructionFilter filter;
  const std::atomic<bool>* cancel = nullptr;  ///< when set to true, stop as after the time limit
  bool progress = false;                      ///< progress bar with ETA on stderr
};

struct RenderStats {
  double seconds = 0.0;
  uint64_t samples = 0;
  uint64_t rays = 0;
  size_t finishedPixels = 0;
  size_t unfinishedPixels = 0;  ///< left black by the time limit or a cancel
  size_t nonFiniteSamples = 0;  ///< NaN/Inf estimates dropped (counted as zero radiance)
  uint64_t minPixelSamples = 0, maxPixelSamples = 0;  ///< over the finished pixels (0 if none)
  bool stopped = false;  ///< the cancel flag or the time limit stopped it before every pixel
  /// Mean samples per finished pixel (differs from the fixed count only when adaptive).
  double meanSamplesPerPixel() const;
};

struct RenderResult {
  Image image;
  RenderStats stats;
};

/// Bytes of rendering and writing a width × height image: the film's double-precision pixels,
/// the float and 8-bit copies that writeImage encodes, and the per-pixel bookkeeping.
uint64_t renderImageBytes(int width, int height);

/// Renders scene.camera()'s image. Each pixel has its own PCG32 stream, seeded from
/// (seed, pixel index), and its film positions come from the reconstruction filter, so the
/// image is the same for any thread count and tile order. A sample whose radiance is NaN or
/// infinite is replaced by zero and counted; the image never holds one.
RenderResult render(const RenderScene& scene, const Integrator& integrator,
                    const RenderOptions& options);

}  // namespace quadtri
