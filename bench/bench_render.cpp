// Path-tracer speed per model on the thesis' setup (a), scenes/thesis/a-icosahedron.xml (a
// diffuse icosahedron in a room, point light), and the raw ray throughput of the same built
// geometry, so the cost of shading/sampling and the cost of the surface model separate:
//
//   Render/<model>   one 128×128, 16 spp render on 2 threads; rays/s = RenderStats.rays/seconds,
//                    pt/raw = that ÷ the raw rays/s measured once at setup.
//   Raw/<model>/...  the same number of camera rays (jittered film positions, pixel order), or
//                    of incoherent rays (camera position to uniform points in the scene bounds),
//                    traced through the scene on 2 threads; only the intersect calls are timed.
//
//   G1/<scene>       `shading` and `quadric-g1` taking turns on every thesis scene
//                    (scenes/thesis: setups (a) and (b) with the triangle, tetrahedron,
//                    icosahedron, torus and, when data/teapot.obj is there, the teapot) and on
//                    the real-mesh grid (scenes/corpus, when QUADTRI_CORPUS names the corpus
//                    folder): each iteration one 128×128, 16 spp render on 2 threads with each
//                    model; the fastest of each and their ratio.
//
// Summaries after the benchmarks give each model's render time ÷ shading's at equal samples,
// and quadric-g1's ÷ shading's per scene.
//
//   quadtri_bench_render --benchmark_min_time=0.5
//   QUADTRI_CORPUS=corpus quadtri_bench_render --benchmark_filter=G1/
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/render/camera.h"
#include "quadtri/render/render_scene.h"
#include "quadtri/render/renderer.h"
#include "quadtri/scene/scene_builder.h"
#include "quadtri/scene/scene_loader.h"

namespace {

using namespace quadtri;

constexpr int kThreads = 2;
constexpr int kResolution = 128;
constexpr int kSamplesPerPixel = 16;
// Raw throughput keeps the fastest of a few passes: the one least disturbed by other processes.
constexpr int kRawPasses = 8;
const char* const kModels[] = {"shading", "quadric-param", "quadric-implicit",
                               "quadric-implicit-robust", "quadric-g1"};

/// Seconds to trace a batch of rays and how many hit something.
struct TraceTiming {
  double seconds = 0.0;
  size_t hits = 0;
};

/// Traces `rays` through `scene` on kThreads threads (contiguous slices, as the renderer's tiles
/// keep neighbouring rays together) and times the intersect calls alone: the clock starts once
/// every thread is ready and stops when the last one finishes.
TraceTiming traceBatch(const RenderScene& scene, const std::vector<Ray>& rays) {
  std::vector<size_t> hits(kThreads, 0);
  std::vector<double> finished(kThreads, 0.0);
  std::atomic<int> ready{0};
  std::atomic<bool> go{false};
  using Clock = std::chrono::steady_clock;
  Clock::time_point start;
  std::vector<std::thread> workers;
  for (int w = 0; w < kThreads; ++w)
    workers.emplace_back([&, w] {
      enableFlushToZero();
      const size_t begin = rays.size() * size_t(w) / kThreads;
      const size_t end = rays.size() * size_t(w + 1) / kThreads;
      ready.fetch_add(1);
      while (!go.load(std::memory_order_acquire)) std::this_thread::yield();
      size_t count = 0;
      for (size_t i = begin; i < end; ++i) count += scene.intersect(rays[i]).has_value() ? 1 : 0;
      finished[size_t(w)] = std::chrono::duration<double>(Clock::now() - start).count();
      hits[size_t(w)] = count;
    });
  while (ready.load() < kThreads) std::this_thread::yield();
  start = Clock::now();
  go.store(true, std::memory_order_release);
  for (std::thread& t : workers) t.join();
  TraceTiming timing;
  for (int w = 0; w < kThreads; ++w) {
    timing.seconds = std::max(timing.seconds, finished[size_t(w)]);
    timing.hits += hits[size_t(w)];
  }
  return timing;
}

/// Camera rays as the renderer starts them: for each pixel in row order, kSamplesPerPixel rays
/// through uniformly jittered film positions inside it.
std::vector<Ray> cameraRays(const PerspectiveCamera& camera, Pcg32& rng) {
  std::vector<Ray> rays;
  rays.reserve(size_t(camera.width()) * size_t(camera.height()) * kSamplesPerPixel);
  for (int y = 0; y < camera.height(); ++y)
    for (int x = 0; x < camera.width(); ++x)
      for (int s = 0; s < kSamplesPerPixel; ++s)
        rays.push_back(camera.generateRay(Vec2(x, y) + rng.next2D()));
  return rays;
}

/// `count` incoherent rays from the camera position towards independent uniform points of the
/// scene's bounding box, in random order.
std::vector<Ray> incoherentRays(const Vec3& origin, const Bounds3& bounds, size_t count,
                                Pcg32& rng) {
  std::vector<Ray> rays(count);
  const Vec3 extent = bounds.hi - bounds.lo;
  for (Ray& ray : rays) {
    const Vec3 target =
        bounds.lo + Vec3(rng.nextDouble(), rng.nextDouble(), rng.nextDouble()).cwiseProduct(extent);
    ray.origin = origin;
    ray.direction = safeNormalized(target - origin, Vec3::UnitZ());
  }
  return rays;
}

/// One model's built scene with its ray batches and the raw throughput measured at setup.
struct BenchScene {
  BuiltScene built;
  std::vector<Ray> camera, incoherent;
  double rawRaysPerSecond = 0.0;  ///< both batches together, best of kRawPasses
};

/// Mean render seconds per model, filled by the Render benchmarks that ran.
std::map<std::string, double>& renderSeconds() {
  static std::map<std::string, double> seconds;
  return seconds;
}

/// Fastest of kRawPasses traces of `rays`.
TraceTiming bestTrace(const RenderScene& scene, const std::vector<Ray>& rays) {
  TraceTiming best = traceBatch(scene, rays);
  for (int pass = 1; pass < kRawPasses; ++pass) {
    const TraceTiming t = traceBatch(scene, rays);
    if (t.seconds < best.seconds) best = t;
  }
  return best;
}

/// Builds (once, on first use) the scene with every obj shape converted by `model`.
BenchScene& benchScene(const std::string& model) {
  static std::map<std::string, BenchScene> cache;
  auto [it, inserted] = cache.try_emplace(model);
  BenchScene& bench = it->second;
  if (!inserted) return bench;
  const SceneDefines defines = {{"res", std::to_string(kResolution)},
                                {"spp", std::to_string(kSamplesPerPixel)}};
  bench.built = buildScene(loadSceneDescription(QUADTRI_BENCH_SCENE, defines), model);
  bench.built.options.samplesPerPixel = kSamplesPerPixel;
  bench.built.options.threads = kThreads;
  const RenderScene& scene = *bench.built.scene;
  Pcg32 rng(0x5eed, 0xbe7c);
  bench.camera = cameraRays(scene.camera(), rng);
  const Vec3 eye = scene.camera().generateRay(Vec2(0.5 * kResolution, 0.5 * kResolution)).origin;
  bench.incoherent = incoherentRays(eye, scene.bounds(), bench.camera.size(), rng);
  const double seconds =
      bestTrace(scene, bench.camera).seconds + bestTrace(scene, bench.incoherent).seconds;
  bench.rawRaysPerSecond = double(bench.camera.size() + bench.incoherent.size()) / seconds;
  return bench;
}

void renderModel(benchmark::State& state, const std::string& model) {
  BenchScene& bench = benchScene(model);
  uint64_t rays = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const RenderResult result =
        render(*bench.built.scene, *bench.built.integrator, bench.built.options);
    benchmark::DoNotOptimize(result.image.pixels.data());
    rays += result.stats.rays;
    seconds += result.stats.seconds;
  }
  const double raysPerSecond = double(rays) / seconds;
  renderSeconds()[model] = seconds / double(state.iterations());
  state.counters["rays/s"] = raysPerSecond;
  state.counters["raw_rays/s"] = bench.rawRaysPerSecond;
  state.counters["pt/raw"] = raysPerSecond / bench.rawRaysPerSecond;
  state.counters["rays/sample"] =
      double(rays) / (double(state.iterations()) * kResolution * kResolution * kSamplesPerPixel);
}

void rawModel(benchmark::State& state, const std::string& model, bool coherent) {
  BenchScene& bench = benchScene(model);
  const std::vector<Ray>& rays = coherent ? bench.camera : bench.incoherent;
  double seconds = 0.0;
  size_t hits = 0;
  for (auto _ : state) {
    const TraceTiming t = traceBatch(*bench.built.scene, rays);
    state.SetIterationTime(t.seconds);
    seconds += t.seconds;
    hits = t.hits;
  }
  state.counters["rays/s"] = double(rays.size()) * double(state.iterations()) / seconds;
  state.counters["hit_fraction"] = double(hits) / double(rays.size());
}

/// A scene of the G1 comparison: its file (relative to scenes/) and the defines it needs.
struct G1Scene {
  std::string name, file;
  SceneDefines defines;
};

std::vector<G1Scene> g1Scenes() {
  std::vector<G1Scene> scenes;
  for (const char* setup : {"a", "b"})
    for (const char* object : {"triangle", "tetrahedron", "icosahedron", "torus", "teapot"}) {
      const std::string name = std::string(setup) + "-" + object;
      if (std::string(object) == "teapot" &&
          !std::filesystem::exists(std::filesystem::path(QUADTRI_SOURCE_DIR) / "data/teapot.obj"))
        continue;
      scenes.push_back({name, "thesis/" + name + ".xml", {}});
    }
  if (const char* corpus = std::getenv("QUADTRI_CORPUS"))
    for (const char* mesh : {"pinion", "armadillo", "cow", "fandisk", "elephant"}) {
      const std::filesystem::path folder = std::filesystem::absolute(corpus);
      if (!std::filesystem::exists(folder / "cgal" / (std::string(mesh) + ".off"))) {
        fmt::print(stderr, "G1/grid-{}: {} has no cgal/{}.off; skipped\n", mesh, folder.string(),
                   mesh);
        continue;
      }
      scenes.push_back({std::string("grid-") + mesh,
                        std::string("corpus/grid-") + mesh + ".xml",
                        {{"corpus", folder.string()}}});
    }
  return scenes;
}

/// The fastest render of each model per scene in the G1 comparison: {shading, quadric-g1}.
std::map<std::string, std::array<double, 2>>& g1Seconds() {
  static std::map<std::string, std::array<double, 2>> seconds;
  return seconds;
}

const char* const kG1Models[2] = {"shading", "quadric-g1"};

/// The scene of the G1 comparison last asked for, built with both models (once: the benchmark
/// library calls a benchmark again to settle its iterations, and the builds stay out of the
/// timing; only one scene is kept, the armadillo's sub-patches being hundreds of megabytes).
std::string& g1Key() {
  static std::string key;
  return key;
}

std::array<BuiltScene, 2>& g1Pair() {
  static std::array<BuiltScene, 2> built;
  return built;
}

std::array<BuiltScene, 2>& g1Built(const G1Scene& scene) {
  std::string& key = g1Key();
  std::array<BuiltScene, 2>& built = g1Pair();
  if (key == scene.name && built[0].scene) return built;
  built = {};
  SceneDefines defines = scene.defines;
  defines["res"] = std::to_string(kResolution);
  defines["spp"] = std::to_string(kSamplesPerPixel);
  const SceneDescription description = loadSceneDescription(
      std::filesystem::path(QUADTRI_SOURCE_DIR) / "scenes" / scene.file, defines);
  for (size_t m = 0; m < 2; ++m) {
    built[m] = buildScene(description, kG1Models[m]);
    built[m].options.samplesPerPixel = kSamplesPerPixel;
    built[m].options.threads = kThreads;
  }
  key = scene.name;
  return built;
}

/// Renders one scene of the G1 comparison with shading and quadric-g1 in turn, each iteration
/// both, and keeps each model's fastest render: other processes on a shared machine only slow a
/// render down, and taking turns exposes both models to the same disturbances.
void compareG1(benchmark::State& state, const G1Scene& scene) {
  std::array<BuiltScene, 2>& built = g1Built(scene);
  std::array<double, 2> best = {kInfinity, kInfinity};
  for (auto _ : state)
    for (size_t m = 0; m < 2; ++m) {
      const RenderResult result = render(*built[m].scene, *built[m].integrator, built[m].options);
      benchmark::DoNotOptimize(result.image.pixels.data());
      best[m] = std::min(best[m], result.stats.seconds);
    }
  // The benchmark library may call this more than once per scene: keep the fastest of all.
  auto [it, inserted] = g1Seconds().try_emplace(scene.name, best);
  if (!inserted)
    for (size_t m = 0; m < 2; ++m) it->second[m] = std::min(it->second[m], best[m]);
  state.counters["shading_s"] = best[0];
  state.counters["g1_s"] = best[1];
  state.counters["g1/shading"] = best[1] / best[0];
}

/// quadric-g1's render time against shading's, scene by scene.
void printG1Summary(const std::vector<G1Scene>& scenes) {
  bool header = false;
  for (const G1Scene& scene : scenes) {
    const auto it = g1Seconds().find(scene.name);
    if (it == g1Seconds().end()) continue;
    if (!header)
      fmt::print(
          "\nquadric-g1 against shading at {}x{}, {} spp, {} threads (fastest of each, taking "
          "turns):\n",
          kResolution, kResolution, kSamplesPerPixel, kThreads);
    header = true;
    const auto& [shading, g1] = it->second;
    fmt::print("  {:<16} shading {:8.3f} s  quadric-g1 {:8.3f} s  {:6.2f}x\n", scene.name, shading,
               g1, g1 / shading);
  }
}

/// Each model's render time against shading's at the same resolution and samples per pixel.
void printSummary() {
  const auto shading = renderSeconds().find("shading");
  if (shading == renderSeconds().end()) return;
  fmt::print("\nrender time at {}x{}, {} spp, {} threads (ratio to shading):\n", kResolution,
             kResolution, kSamplesPerPixel, kThreads);
  for (const char* model : kModels) {
    const auto it = renderSeconds().find(model);
    if (it == renderSeconds().end()) continue;
    fmt::print("  {:<24} {:8.3f} s  {:6.2f}x\n", model, it->second, it->second / shading->second);
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (const char* model : kModels) {
    const std::string name(model);
    benchmark::RegisterBenchmark(("Render/" + name).c_str(), renderModel, name)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    for (const bool coherent : {true, false})
      benchmark::RegisterBenchmark(("Raw/" + name + (coherent ? "/camera" : "/incoherent")).c_str(),
                                   rawModel, name, coherent)
          ->Unit(benchmark::kMillisecond)
          ->UseManualTime();
  }
  const std::vector<G1Scene> scenes = g1Scenes();
  for (const G1Scene& scene : scenes)
    benchmark::RegisterBenchmark(("G1/" + scene.name).c_str(), compareG1, scene)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  printSummary();
  printG1Summary(scenes);
  g1Pair() = {};  // the Embree scenes go before main returns, not after the library's state
  g1Key().clear();
  benchmark::Shutdown();
  return 0;
}
