#include "quadtri/render/renderer.h"

#include <tbb/task_arena.h>

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <limits>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>

#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/render/render_scene.h"

namespace quadtri {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kTileSize = 16;

// SplitMix64's finaliser: decorrelates nearby seeds and pixel indices.
uint64_t mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

struct PixelResult {
  Color value = Color::Zero();
  uint64_t samples = 0, rays = 0;
  size_t nonFinite = 0;
};

// One pixel: fixed samples, or batches until the adaptive rule holds.
PixelResult renderPixel(const RenderScene& scene, const Integrator& integrator,
                        const RenderOptions& options, int x, int y) {
  const PerspectiveCamera& camera = scene.camera();
  // The pixel's index on the whole film, so that a crop window draws the same samples as the
  // same pixels of the full render.
  const uint64_t index =
      uint64_t(y + camera.cropY()) * uint64_t(camera.filmWidth()) + uint64_t(x + camera.cropX());
  Pcg32 rng(mix64(options.seed ^ mix64(index)), mix64(index) ^ options.seed);
  // Camera rays (the filter's offsets) come from a stream of their own, so that a sample's
  // path draws the same numbers however the camera rays are grouped into packets.
  Pcg32 cameraRng(mix64(options.seed ^ mix64(index ^ 0x63616d657261ull)),
                  mix64(index) ^ options.seed ^ 0x63616d657261ull);
  std::array<Ray, Accel::kPacketSize> cameraRays;
  std::array<std::optional<SurfaceInteraction>, Accel::kPacketSize> firstHits;
  const AdaptiveSampling* adaptive = integrator.adaptive();
  const uint64_t target =
      adaptive ? uint64_t(adaptive->maxSamples) : uint64_t(options.samplesPerPixel);
  PixelResult r;
  Color sum = Color::Zero();
  double lumSum = 0.0, lumSquares = 0.0;
  const Vec2 centre(x + camera.cropX() + 0.5, y + camera.cropY() + 0.5);
  while (r.samples < target) {
    uint64_t batch = target - r.samples;
    if (adaptive)
      batch = std::min(batch, r.samples < uint64_t(adaptive->minSamples)
                                  ? uint64_t(adaptive->minSamples) - r.samples
                                  : uint64_t(adaptive->batch));
    // The batch's camera rays are traced in packets of Embree's, which share the traversal
    // (they leave one point towards one pixel); the rest of each path goes ray by ray.
    for (uint64_t done = 0; done < batch; done += cameraRays.size()) {
      const size_t n = size_t(std::min<uint64_t>(cameraRays.size(), batch - done));
      for (size_t i = 0; i < n; ++i)
        cameraRays[i] = camera.generateRay(centre + options.filter.sampleOffset(cameraRng));
      scene.intersect(std::span(cameraRays).first(n), std::span(firstHits).first(n));
      for (size_t i = 0; i < n; ++i) {
        Color l = integrator.radianceFrom(scene, cameraRays[i], firstHits[i], rng, r.rays);
        if (!l.allFinite()) {
          ++r.nonFinite;
          l = Color::Zero();
        }
        sum += l;
        const double lum = luminance(l);
        lumSum += lum;
        lumSquares += lum * lum;
      }
    }
    r.samples += batch;
    if (adaptive && r.samples >= uint64_t(adaptive->minSamples)) {
      const double n = double(r.samples), mean = lumSum / n;
      const double variance = std::max(0.0, (lumSquares - n * mean * mean) / (n - 1.0));
      const double standardError = std::sqrt(variance / n);
      if (standardError <= adaptive->threshold * std::abs(mean)) break;
      if (variance == 0.0) break;  // a constant pixel (black, say) is known exactly
    }
  }
  r.value = sum / double(r.samples);
  return r;
}

// Redraws "[####    ] 42% ETA 12s" in place, at most a few times a second.
class ProgressBar {
 public:
  ProgressBar(bool enabled, size_t total)
      : enabled_(enabled), total_(total), start_(Clock::now()) {}
  void update(size_t done) {
    if (!enabled_ || !mutex_.try_lock()) return;
    std::lock_guard<std::mutex> lock(mutex_, std::adopt_lock);
    const auto now = Clock::now();
    if (done < total_ && now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    draw(done, std::chrono::duration<double>(now - start_).count());
  }
  void finish(size_t done) {
    if (!enabled_) return;
    draw(done, std::chrono::duration<double>(Clock::now() - start_).count());
    std::fputc('\n', stderr);
  }

 private:
  void draw(size_t done, double elapsed) const {
    constexpr int kWidth = 40;
    const double fraction = total_ ? double(done) / double(total_) : 1.0;
    const int filled = int(fraction * kWidth);
    const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "\r[%s%s] %3d%%  %.0fs elapsed, ETA %.0fs ",
                 std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(kWidth - filled), ' ').c_str(), int(100.0 * fraction), elapsed,
                 eta);
    std::fflush(stderr);
  }
  bool enabled_;
  size_t total_;
  Clock::time_point start_, last_{};
  std::mutex mutex_;
};

}  // namespace

uint64_t renderImageBytes(int width, int height) {
  constexpr uint64_t kPerPixel = sizeof(Color) + 3 * sizeof(float) + 3 + 8;
  return uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0)) * kPerPixel;
}

RenderState RenderResult::state(uint64_t key) const {
  RenderState s;
  s.key = key;
  s.width = image.width;
  s.height = image.height;
  s.samples = pixelSamples;
  s.pixels = image.pixels;
  for (size_t i = 0; i < s.pixels.size(); ++i)
    if (s.samples[i] == 0) s.pixels[i] = Color::Zero();
  return s;
}

double RenderStats::meanSamplesPerPixel() const {
  return finishedPixels == 0 ? 0.0 : double(samples) / double(finishedPixels);
}

RenderResult render(const RenderScene& scene, const Integrator& integrator,
                    const RenderOptions& options) {
  const PerspectiveCamera& camera = scene.camera();
  if (!integrator.adaptive() && options.samplesPerPixel < 1)
    fail("samples per pixel {}: expected at least 1", options.samplesPerPixel);
  if (options.threads < 0)
    fail("threads {}: expected 0 (all) or a positive count", options.threads);
  const int width = camera.width(), height = camera.height();
  const int tilesX = (width + kTileSize - 1) / kTileSize,
            tilesY = (height + kTileSize - 1) / kTileSize;
  const size_t tileCount = size_t(tilesX) * size_t(tilesY);
  const size_t pixelCount = size_t(width) * size_t(height);
  const RenderState* resume = options.resume;
  if (resume) {
    if (resume->width != width || resume->height != height ||
        resume->samples.size() != pixelCount || resume->pixels.size() != pixelCount)
      fail("the render state to resume is {}x{}, the camera's image {}x{}", resume->width,
           resume->height, width, height);
    if (!integrator.adaptive())
      for (size_t i = 0; i < pixelCount; ++i)
        if (resume->samples[i] != 0 && resume->samples[i] != uint32_t(options.samplesPerPixel))
          fail("the render state to resume has {} samples in pixel {}, expected {} (or 0)",
               resume->samples[i], i, options.samplesPerPixel);
  }

  RenderResult result;
  result.image = Image(width, height);
  // Per pixel: the samples it got, stored (release) after its value, so that a checkpoint
  // reading a count (acquire) reads a final value.
  std::vector<std::atomic<uint32_t>> counts(pixelCount);
  std::atomic<uint64_t> samples{0}, rays{0};
  std::atomic<size_t> nonFinite{0}, finishedPixels{0}, unfinished{0}, resumed{0};
  std::atomic<bool> stopped{false};
  std::atomic<bool> firstPixelSeen{false};
  std::atomic<int64_t> firstPixelTicks{0};  // Clock ticks after `start`
  std::atomic<uint64_t> minSamples{std::numeric_limits<uint64_t>::max()}, maxSamples{0};
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(options.timeLimitSeconds));
  ProgressBar progress(options.progress, size_t(width) * size_t(height));
  const auto shouldStop = [&] {
    if (stopped.load(std::memory_order_relaxed)) return true;
    const bool stop = (options.cancel && options.cancel->load(std::memory_order_relaxed)) ||
                      (options.timeLimitSeconds > 0.0 && Clock::now() >= deadline);
    if (stop) stopped.store(true, std::memory_order_relaxed);
    return stop;
  };

  // Checkpoints: a thread that wakes every checkpointSeconds and hands the finished pixels to
  // the callback, until the render is done (the guard also ends it when rendering throws).
  struct Checkpointer {
    std::mutex mutex;
    std::condition_variable wake;
    bool done = false;
    std::thread thread;
    ~Checkpointer() {
      {
        std::lock_guard<std::mutex> lock(mutex);
        done = true;
      }
      wake.notify_all();
      if (thread.joinable()) thread.join();
    }
  } checkpointer;
  size_t checkpoints = 0;
  if (options.checkpoint && options.checkpointSeconds > 0.0) {
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(options.checkpointSeconds));
    checkpointer.thread = std::thread([&, period] {
      std::unique_lock<std::mutex> lock(checkpointer.mutex);
      while (!checkpointer.wake.wait_for(lock, period, [&] { return checkpointer.done; })) {
        lock.unlock();
        RenderState state;
        state.key = options.stateKey;
        state.width = width;
        state.height = height;
        state.samples.resize(pixelCount);
        state.pixels.assign(pixelCount, Color::Zero());
        for (size_t i = 0; i < pixelCount; ++i) {
          state.samples[i] = counts[i].load(std::memory_order_acquire);
          if (state.samples[i] > 0) state.pixels[i] = result.image.pixels[i];
        }
        try {
          options.checkpoint(state);
          ++checkpoints;
        } catch (const std::exception& e) {
          result.checkpointError = e.what();
          return;
        }
        lock.lock();
      }
    });
  }

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    parallelForRange(
        tbb::blocked_range<size_t>(0, tileCount, 1),
        [&](const tbb::blocked_range<size_t>& range) {
          const FlushToZeroScope flushToZero;
          for (size_t tile = range.begin(); tile != range.end(); ++tile) {
            const int x0 = int(tile % size_t(tilesX)) * kTileSize,
                      y0 = int(tile / size_t(tilesX)) * kTileSize;
            const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
            uint64_t tileSamples = 0, tileRays = 0, tileMin = std::numeric_limits<uint64_t>::max(),
                     tileMax = 0;
            size_t tileNonFinite = 0, tileDone = 0, tileSkipped = 0, tileResumed = 0;
            for (int y = y0; y < y1; ++y)
              for (int x = x0; x < x1; ++x) {
                const size_t index = size_t(y) * size_t(width) + size_t(x);
                if (resume && resume->samples[index] > 0) {
                  const uint32_t n = resume->samples[index];
                  result.image.at(x, y) = resume->pixels[index];
                  counts[index].store(n, std::memory_order_release);
                  tileSamples += n;
                  tileMin = std::min<uint64_t>(tileMin, n);
                  tileMax = std::max<uint64_t>(tileMax, n);
                  ++tileResumed;
                  ++tileDone;
                  continue;
                }
                if (shouldStop()) {
                  ++tileSkipped;
                  continue;
                }
                const PixelResult p = renderPixel(scene, integrator, options, x, y);
                if (!firstPixelSeen.load(std::memory_order_relaxed) &&
                    !firstPixelSeen.exchange(true))
                  firstPixelTicks = (Clock::now() - start).count();
                result.image.at(x, y) = p.value;
                counts[index].store(uint32_t(p.samples), std::memory_order_release);
                tileSamples += p.samples;
                tileRays += p.rays;
                tileNonFinite += p.nonFinite;
                tileMin = std::min(tileMin, p.samples);
                tileMax = std::max(tileMax, p.samples);
                ++tileDone;
              }
            for (uint64_t seen = minSamples.load(); tileMin < seen;)
              if (minSamples.compare_exchange_weak(seen, tileMin)) break;
            for (uint64_t seen = maxSamples.load(); tileMax > seen;)
              if (maxSamples.compare_exchange_weak(seen, tileMax)) break;
            samples += tileSamples;
            rays += tileRays;
            nonFinite += tileNonFinite;
            unfinished += tileSkipped;
            resumed += tileResumed;
            progress.update(finishedPixels += tileDone);
          }
        },
        tbb::simple_partitioner());
  });
  {
    std::lock_guard<std::mutex> lock(checkpointer.mutex);
    checkpointer.done = true;
  }
  checkpointer.wake.notify_all();
  if (checkpointer.thread.joinable()) checkpointer.thread.join();
  progress.finish(finishedPixels.load());
  result.pixelSamples.resize(pixelCount);
  for (size_t i = 0; i < pixelCount; ++i) result.pixelSamples[i] = counts[i].load();

  result.stats.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  result.stats.firstPixelSeconds =
      std::chrono::duration<double>(Clock::duration(firstPixelTicks.load())).count();
  result.stats.samples = samples.load();
  result.stats.rays = rays.load();
  result.stats.nonFiniteSamples = nonFinite.load();
  result.stats.unfinishedPixels = unfinished.load();
  result.stats.finishedPixels = finishedPixels.load();
  result.stats.minPixelSamples = result.stats.finishedPixels ? minSamples.load() : 0;
  result.stats.maxPixelSamples = maxSamples.load();
  result.stats.stopped = stopped.load();
  result.stats.resumedPixels = resumed.load();
  result.stats.checkpoints = checkpoints;
  return result;
}

}  // namespace quadtri
