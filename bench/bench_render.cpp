// Path-tracer speed per model on the thesis' setup (a), scenes/thesis/a-icosahedron.xml (a
// diffuse icosahedron in a room, point light), and the raw ray throughput of the same built
// geometry, so the cost of shading/sampling and the cost of the surface model separate:
//
//   Render/<model>   one 128×128, 16 spp render on 2 threads; rays/s = RenderStats.rays/seconds
//                    over every iteration. pt/raw = the fastest iteration's rays/s ÷ the best raw
//                    rays/s, raw passes taken at setup and after each render, so both are the
//                    best of passes taken in turns (pt_mean/raw: every iteration's rays/s).
//   Raw/<model>/...  the same number of camera rays (jittered film positions, pixel order, a
//                    pixel's 16 traced together as the renderer traces them), or of incoherent
//                    rays (camera position to uniform points in the scene bounds, one by one),
//                    traced through the scene on 2 threads; only the intersect calls are timed.
//
//   Ratio/<scene>    `shading`, `quadric-implicit`, `quadric-implicit-robust` and `quadric-g1`
//                    taking turns on every thesis scene (scenes/thesis: setups (a) and (b) with
//                    the triangle, tetrahedron, icosahedron, torus and, when data/teapot.obj is
//                    there, the teapot), on the real-mesh grid (scenes/corpus, when
//                    QUADTRI_CORPUS names the corpus folder) and on the icosphere series
//                    (scenes/thesis/scaling.xml with icosphere levels 0 to 8, 20 to 1,310,720
//                    triangles, written to a temporary folder): each iteration one 128×128,
//                    16 spp render on 2 threads with each model; the fastest of each.
//                    QUADTRI_RATIO_MODELS=quadric-g1 (a comma-separated list) compares fewer.
//
// Summaries after the benchmarks give each model's render time ÷ shading's at equal samples on
// setup (a), and per scene each compared model's ÷ shading's beside its target (implicit 1.15,
// robust 1.2, g1 1.5) and its time per traced ray ÷ shading's (a curved surface sends paths
// elsewhere, so the two ratios differ by the ratio of rays traced), with the spread of the
// ratio over the icosphere series (target 1.1).
//
//   quadtri_bench_render --benchmark_min_time=0.5
//   QUADTRI_CORPUS=corpus quadtri_bench_render --benchmark_filter=Ratio/
//   QUADTRI_RATIO_MODELS=quadric-g1 quadtri_bench_render --benchmark_filter='Ratio/(a|b)-'
#include <benchmark/benchmark.h>
#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/render/camera.h"
#include "quadtri/render/render_scene.h"
#include "quadtri/render/renderer.h"
#include "quadtri/scene/render_settings.h"
#include "quadtri/scene/scene_builder.h"
#include "quadtri/scene/scene_loader.h"

namespace {

using namespace quadtri;

constexpr int kThreads = 2;
constexpr int kResolution = 128;
constexpr int kSamplesPerPixel = 16;
// Raw throughput keeps the fastest of a few passes at setup (the one least disturbed by other
// processes), and of one more after each render.
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
/// every thread is ready and stops when the last one finishes. With `packets`, kSamplesPerPixel
/// rays at a time (a pixel's camera rays) go through the packet call, as the renderer traces
/// them; otherwise one by one.
TraceTiming traceBatch(const RenderScene& scene, const std::vector<Ray>& rays, bool packets) {
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
      if (packets) {
        std::array<std::optional<SurfaceInteraction>, kSamplesPerPixel> out;
        const std::span<const Ray> all(rays);
        for (size_t i = begin; i < end; i += out.size()) {
          const size_t n = std::min(out.size(), end - i);
          scene.intersect(all.subspan(i, n), std::span(out).first(n));
          for (size_t k = 0; k < n; ++k) count += out[k].has_value() ? 1 : 0;
        }
      } else {
        for (size_t i = begin; i < end; ++i) count += scene.intersect(rays[i]).has_value() ? 1 : 0;
      }
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
  /// Both batches together: the best pass so far (kRawPasses at setup, one after each render)
  double rawRaysPerSecond = 0.0;
};

/// Mean render seconds per model, filled by the Render benchmarks that ran.
std::map<std::string, double>& renderSeconds() {
  static std::map<std::string, double> seconds;
  return seconds;
}

/// pt/raw per model, filled by the Render benchmarks that ran.
std::map<std::string, double>& pathTracerShare() {
  static std::map<std::string, double> share;
  return share;
}
// The path tracer's rays/s as a share of raw Embree throughput that `shading` should reach.
constexpr double kPathTracerShareTarget = 0.75;

/// Raw rays/s of one pass over both batches: the camera rays as packets (as the renderer traces
/// them), then the incoherent rays one by one.
double rawThroughput(const RenderScene& scene, const BenchScene& bench) {
  const double seconds = traceBatch(scene, bench.camera, true).seconds +
                         traceBatch(scene, bench.incoherent, false).seconds;
  return double(bench.camera.size() + bench.incoherent.size()) / seconds;
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
  bench.rawRaysPerSecond = rawThroughput(scene, bench);
  for (int pass = 1; pass < kRawPasses; ++pass)
    bench.rawRaysPerSecond = std::max(bench.rawRaysPerSecond, rawThroughput(scene, bench));
  return bench;
}

void renderModel(benchmark::State& state, const std::string& model) {
  BenchScene& bench = benchScene(model);
  uint64_t rays = 0, fastestRays = 0;
  double seconds = 0.0, fastest = kInfinity;
  for (auto _ : state) {
    const RenderResult result =
        render(*bench.built.scene, *bench.built.integrator, bench.built.options);
    benchmark::DoNotOptimize(result.image.pixels.data());
    rays += result.stats.rays;
    seconds += result.stats.seconds;
    if (result.stats.seconds < fastest) {
      fastest = result.stats.seconds;
      fastestRays = result.stats.rays;
    }
    // A raw pass after each render, so that the two throughputs compared are each the best
    // of passes taken in turns, under the same load.
    state.PauseTiming();
    bench.rawRaysPerSecond =
        std::max(bench.rawRaysPerSecond, rawThroughput(*bench.built.scene, bench));
    state.ResumeTiming();
  }
  const double raysPerSecond = double(rays) / seconds;
  renderSeconds()[model] = seconds / double(state.iterations());
  state.counters["rays/s"] = raysPerSecond;
  state.counters["raw_rays/s"] = bench.rawRaysPerSecond;
  state.counters["pt/raw"] = double(fastestRays) / fastest / bench.rawRaysPerSecond;
  pathTracerShare()[model] = state.counters["pt/raw"];
  state.counters["pt_mean/raw"] = raysPerSecond / bench.rawRaysPerSecond;
  state.counters["rays/sample"] =
      double(rays) / (double(state.iterations()) * kResolution * kResolution * kSamplesPerPixel);
}

void rawModel(benchmark::State& state, const std::string& model, bool coherent) {
  BenchScene& bench = benchScene(model);
  const std::vector<Ray>& rays = coherent ? bench.camera : bench.incoherent;
  double seconds = 0.0;
  size_t hits = 0;
  for (auto _ : state) {
    const TraceTiming t = traceBatch(*bench.built.scene, rays, coherent);
    state.SetIterationTime(t.seconds);
    seconds += t.seconds;
    hits = t.hits;
  }
  state.counters["rays/s"] = double(rays.size()) * double(state.iterations()) / seconds;
  state.counters["hit_fraction"] = double(hits) / double(rays.size());
}

/// A scene of the ratio comparison: its name, file (absolute) and the defines it needs; for the
/// icosphere series, the level whose OBJ it reads (written on first use, -1 otherwise).
struct RatioScene {
  std::string name;
  std::filesystem::path file;
  SceneDefines defines;
  int icosphereLevel = -1;
};

/// The models compared with `shading`, and each one's render-time target against it.
struct RatioModel {
  const char* name;
  double target;
};
constexpr RatioModel kRatioModels[] = {
    {"quadric-implicit", 1.15}, {"quadric-implicit-robust", 1.2}, {"quadric-g1", 1.5}};
// Across the icosphere series, the largest ratio may be at most this times the smallest.
constexpr double kFlatSeries = 1.1;
constexpr int kLastIcosphereLevel = 8;  // 1,310,720 triangles

/// The models QUADTRI_RATIO_MODELS names (comma-separated), or all of kRatioModels.
std::vector<RatioModel> ratioModels() {
  const char* chosen = std::getenv("QUADTRI_RATIO_MODELS");
  const std::vector<std::string> names = chosen ? splitList(chosen) : std::vector<std::string>{};
  std::vector<RatioModel> models;
  for (const RatioModel& m : kRatioModels)
    if (!chosen || std::find(names.begin(), names.end(), m.name) != names.end())
      models.push_back(m);
  return models;
}

/// Where the icosphere series' scene and meshes are written: the scaling scene reads
/// ../../data/icosphere-L.obj beside itself.
std::filesystem::path seriesFolder() {
  static const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / fmt::format("quadtri-bench-{}", ::getpid());
  return folder;
}

std::vector<RatioScene> ratioScenes() {
  namespace fs = std::filesystem;
  const fs::path scenesDir = fs::path(QUADTRI_SOURCE_DIR) / "scenes";
  std::vector<RatioScene> scenes;
  for (const char* setup : {"a", "b"})
    for (const char* object : {"triangle", "tetrahedron", "icosahedron", "torus", "teapot"}) {
      const std::string name = std::string(setup) + "-" + object;
      if (std::string(object) == "teapot" &&
          !fs::exists(fs::path(QUADTRI_SOURCE_DIR) / "data/teapot.obj"))
        continue;
      scenes.push_back({name, scenesDir / "thesis" / (name + ".xml"), {}});
    }
  if (const char* corpus = std::getenv("QUADTRI_CORPUS"))
    for (const char* mesh : {"pinion", "armadillo", "cow", "fandisk", "elephant"}) {
      const fs::path folder = fs::absolute(corpus);
      if (!fs::exists(folder / "cgal" / (std::string(mesh) + ".off"))) {
        fmt::print(stderr, "Ratio/grid-{}: {} has no cgal/{}.off; skipped\n", mesh, folder.string(),
                   mesh);
        continue;
      }
      scenes.push_back({std::string("grid-") + mesh,
                        scenesDir / "corpus" / (std::string("grid-") + mesh + ".xml"),
                        {{"corpus", folder.string()}}});
    }
  for (int level = 0; level <= kLastIcosphereLevel; ++level) {
    const std::string shape = fmt::format("icosphere-{}", level);
    scenes.push_back(
        {shape, seriesFolder() / "scenes" / "thesis" / "scaling.xml", {{"shape", shape}}, level});
  }
  return scenes;
}

/// Writes the scaling scene and icosphere level `level`'s mesh into seriesFolder(), once.
void writeSeriesScene(int level) {
  namespace fs = std::filesystem;
  const fs::path sceneDir = seriesFolder() / "scenes" / "thesis";
  const fs::path mesh = seriesFolder() / "data" / fmt::format("icosphere-{}.obj", level);
  fs::create_directories(sceneDir);
  fs::create_directories(mesh.parent_path());
  if (!fs::exists(sceneDir / "scaling.xml"))
    fs::copy_file(fs::path(QUADTRI_SOURCE_DIR) / "scenes" / "thesis" / "scaling.xml",
                  sceneDir / "scaling.xml");
  if (!fs::exists(mesh)) saveMesh(loadMeshSpec(fmt::format("icosphere:{}", level)).mesh, mesh);
}

/// The fastest render of each model per scene in the ratio comparison: shading first, then
/// ratioModels() in order.
std::map<std::string, std::vector<double>>& ratioSeconds() {
  static std::map<std::string, std::vector<double>> seconds;
  return seconds;
}

/// The rays each model traced per render in the ratio comparison, in ratioSeconds()' order: a
/// curved surface sends paths elsewhere, so a ratio of times is a ratio of rays times a ratio
/// of the cost per ray, and the summary gives the second beside the first.
std::map<std::string, std::vector<double>>& ratioRays() {
  static std::map<std::string, std::vector<double>> rays;
  return rays;
}

/// The scene of the ratio comparison last asked for, built with shading and every compared
/// model (once: the benchmark library calls a benchmark again to settle its iterations, and the
/// builds stay out of the timing; only one scene is kept, the largest being gigabytes).
std::string& ratioKey() {
  static std::string key;
  return key;
}

std::vector<BuiltScene>& ratioBuiltScenes() {
  static std::vector<BuiltScene> built;
  return built;
}

std::vector<BuiltScene>& ratioBuilt(const RatioScene& scene) {
  std::string& key = ratioKey();
  std::vector<BuiltScene>& built = ratioBuiltScenes();
  if (key == scene.name && !built.empty()) return built;
  built.clear();
  key.clear();
  if (scene.icosphereLevel >= 0) writeSeriesScene(scene.icosphereLevel);
  SceneDefines defines = scene.defines;
  defines["res"] = std::to_string(kResolution);
  defines["spp"] = std::to_string(kSamplesPerPixel);
  const SceneDescription description = loadSceneDescription(scene.file, defines);
  std::vector<std::string> models = {"shading"};
  for (const RatioModel& m : ratioModels()) models.push_back(m.name);
  for (const std::string& model : models) {
    built.push_back(buildScene(description, model));
    built.back().options.samplesPerPixel = kSamplesPerPixel;
    built.back().options.threads = kThreads;
  }
  key = scene.name;
  return built;
}

/// Renders one scene with shading and every compared model in turn, each iteration all of
/// them, and keeps each model's fastest render: other processes on a shared machine only slow a
/// render down, and taking turns exposes every model to the same disturbances.
void compareRatios(benchmark::State& state, const RatioScene& scene) {
  std::vector<BuiltScene>& built = ratioBuilt(scene);
  std::vector<double> best(built.size(), kInfinity), rays(built.size(), 0.0);
  for (auto _ : state)
    for (size_t m = 0; m < built.size(); ++m) {
      const RenderResult result = render(*built[m].scene, *built[m].integrator, built[m].options);
      benchmark::DoNotOptimize(result.image.pixels.data());
      best[m] = std::min(best[m], result.stats.seconds);
      rays[m] = double(result.stats.rays);  // the same in every render: fixed seeds
    }
  ratioRays()[scene.name] = rays;
  // The benchmark library may call this more than once per scene: keep the fastest of all.
  auto [it, inserted] = ratioSeconds().try_emplace(scene.name, best);
  if (!inserted)
    for (size_t m = 0; m < best.size(); ++m) it->second[m] = std::min(it->second[m], best[m]);
  const std::vector<RatioModel> models = ratioModels();
  state.counters["shading_s"] = best[0];
  for (size_t m = 0; m < models.size(); ++m) {
    state.counters[std::string(models[m].name) + "/shading"] = best[m + 1] / best[0];
    state.counters[std::string(models[m].name) + "/shading_per_ray"] =
        (best[m + 1] / rays[m + 1]) / (best[0] / rays[0]);
  }
}

/// Every compared model's render time against shading's, scene by scene, beside its target;
/// then how flat each model's ratio stays across the icosphere series.
void printRatioSummary(const std::vector<RatioScene>& scenes) {
  const std::vector<RatioModel> models = ratioModels();
  bool header = false;
  std::vector<double> seriesLow(models.size(), kInfinity), seriesHigh(models.size(), 0.0);
  std::vector<int> seriesCount(models.size(), 0);
  for (const RatioScene& scene : scenes) {
    const auto it = ratioSeconds().find(scene.name);
    if (it == ratioSeconds().end()) continue;
    if (!header) {
      fmt::print(
          "\nrender time against shading at {}x{}, {} spp, {} threads (fastest of each, taking "
          "turns; target in brackets):\n  {:<16} {:>10}",
          kResolution, kResolution, kSamplesPerPixel, kThreads, "scene", "shading");
      for (const RatioModel& m : models)
        fmt::print("  {:>42}", fmt::format("{} (<= {})", m.name, m.target));
      fmt::print("\n");
    }
    header = true;
    const std::vector<double>& s = it->second;
    const std::vector<double>& r = ratioRays().at(scene.name);
    fmt::print("  {:<16} {:8.3f} s", scene.name, s[0]);
    for (size_t m = 0; m < models.size(); ++m) {
      const double ratio = s[m + 1] / s[0];
      const double perRay = ratio * r[0] / r[m + 1];
      fmt::print("  {:>42}", fmt::format("{:.3f} s {:5.2f}x ({:4.2f}x/ray) {:<6}", s[m + 1], ratio,
                                         perRay, ratio <= models[m].target ? "pass" : "MISSED"));
      if (scene.icosphereLevel >= 0) {
        seriesLow[m] = std::min(seriesLow[m], ratio);
        seriesHigh[m] = std::max(seriesHigh[m], ratio);
        ++seriesCount[m];
      }
    }
    fmt::print("\n");
  }
  for (size_t m = 0; m < models.size(); ++m) {
    if (seriesCount[m] < 2) continue;
    const double spread = seriesHigh[m] / seriesLow[m];
    fmt::print(
        "  {} over {} icosphere levels: ratio {:.2f}x to {:.2f}x, largest / smallest "
        "{:.2f} (target <= {}): {}\n",
        models[m].name, seriesCount[m], seriesLow[m], seriesHigh[m], spread, kFlatSeries,
        spread <= kFlatSeries ? "pass" : "MISSED");
  }
}

/// Each model's render time against shading's at the same resolution and samples per pixel.
void printSummary() {
  const auto shading = renderSeconds().find("shading");
  if (shading == renderSeconds().end()) return;
  fmt::print("\nrender time at {}x{}, {} spp, {} threads (ratio to shading; pt/raw):\n",
             kResolution, kResolution, kSamplesPerPixel, kThreads);
  for (const char* model : kModels) {
    const auto it = renderSeconds().find(model);
    if (it == renderSeconds().end()) continue;
    fmt::print("  {:<24} {:8.3f} s  {:6.2f}x  {:5.3f}\n", model, it->second,
               it->second / shading->second, pathTracerShare()[model]);
  }
  const double share = pathTracerShare()["shading"];
  fmt::print("  path tracer against raw Embree on shading: pt/raw {:.3f} (target >= {}) {}\n",
             share, kPathTracerShareTarget, share >= kPathTracerShareTarget ? "met" : "MISSED");
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
  const std::vector<RatioScene> scenes = ratioScenes();
  for (const RatioScene& scene : scenes)
    benchmark::RegisterBenchmark(("Ratio/" + scene.name).c_str(), compareRatios, scene)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  printSummary();
  printRatioSummary(scenes);
  ratioBuiltScenes().clear();  // the Embree scenes go before main returns, not after the
  ratioKey().clear();          // library's state
  std::error_code ignored;
  std::filesystem::remove_all(seriesFolder(), ignored);
  benchmark::Shutdown();
  return 0;
}
