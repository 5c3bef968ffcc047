// Rendering an image: tiles in parallel, one independent random stream per pixel.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "quadtri/render/filter.h"
#include "quadtri/render/image_io.h"
#include "quadtri/render/integrator/integrator.h"
#include "quadtri/render/render_state.h"

namespace quadtri {

class RenderScene;

/// How a pixel draws its samples: raised whenever a change gives the same seed other samples,
/// so that render states and tiles of the old scheme are not resumed or merged with the new.
/// 2: camera rays from a stream of their own, traced in packets.
inline constexpr int kSamplingScheme = 2;

struct RenderOptions {
  int samplesPerPixel = 16;  ///< fixed count; adaptive integrators use their own bounds
  uint64_t seed = 0;
  int threads = 0;              ///< 0: every hardware thread
  double timeLimitSeconds = 0;  ///< 0: none; otherwise pixels not started in time stay black
  ReconstructionFilter filter;
  const std::atomic<bool>* cancel = nullptr;  ///< when set to true, stop as after the time limit
  bool progress = false;                      ///< progress bar with ETA on stderr
  /// Pixels with samples > 0 in this state are taken as they are and not rendered again. Its
  /// size must match the camera's; its key is the caller's to check (renderKey).
  const RenderState* resume = nullptr;
  /// When both are set, `checkpoint` is called every checkpointSeconds, from a thread of its
  /// own while the render runs, with the pixels finished so far (key: stateKey). If it throws,
  /// checkpoints stop and RenderResult::checkpointError says why; the render goes on.
  double checkpointSeconds = 0;
  std::function<void(const RenderState&)> checkpoint;
  uint64_t stateKey = 0;
};

struct RenderStats {
  double seconds = 0.0;
  /// Seconds from the start of the render until its first pixel was finished (resumed pixels
  /// do not count); 0 when it rendered none.
  double firstPixelSeconds = 0.0;
  uint64_t samples = 0;
  uint64_t rays = 0;
  size_t finishedPixels = 0;
  size_t unfinishedPixels = 0;  ///< left black by the time limit or a cancel
  size_t nonFiniteSamples = 0;  ///< NaN/Inf estimates dropped (counted as zero radiance)
  uint64_t minPixelSamples = 0, maxPixelSamples = 0;  ///< over the finished pixels (0 if none)
  size_t resumedPixels = 0;  ///< finished pixels taken from RenderOptions::resume
  size_t checkpoints = 0;    ///< checkpoint calls that returned
  bool stopped = false;      ///< the cancel flag or the time limit stopped it before every pixel
  /// Mean samples per finished pixel (differs from the fixed count only when adaptive).
  double meanSamplesPerPixel() const;
};

struct RenderResult {
  Image image;
  RenderStats stats;
  std::vector<uint32_t> pixelSamples;  ///< per pixel: the samples it got, 0 when not rendered
  std::string checkpointError;         ///< why checkpoints stopped, when one threw
  /// The state to resume this render from (pixels with pixelSamples > 0 are finished).
  RenderState state(uint64_t key) const;
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
