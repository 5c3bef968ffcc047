// Conversion throughput of every model (modelNames()), tessellation excluded: the time from a
// loaded mesh to the model's patches, reported as input triangles per second, with 1 and with
// 2 threads (tbb::global_control). A summary after the runs gives each model's seconds per
// 1,000,000-triangle mesh at 2 threads beside the target (0.5 s), and the scaling
// from 1 to 2 threads. Each model converts the 1,000,000-triangle mesh three times.
//
//   quadtri_bench --benchmark_filter=Convert --benchmark_min_time=0.1
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "bench_peer.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/model.h"

namespace {

// The target: a 1,000,000-triangle mesh converts in under 0.5 s on 2 cores.
constexpr double kTargetTrianglesPerSecond = 1e6 / 0.5;

// The meshes are built once, on first use, and shared by every model's benchmark.
std::shared_ptr<const quadtri::TriangleMesh> benchMesh(const std::string& spec) {
  static std::map<std::string, std::shared_ptr<const quadtri::TriangleMesh>> cache;
  auto& slot = cache[spec];
  if (!slot) {
    slot = std::make_shared<const quadtri::TriangleMesh>(quadtri::parseBuiltinSpec(spec)->mesh);
  }
  return slot;
}

// Mean seconds per conversion, by (model, mesh, threads), for the summary.
std::map<std::tuple<std::string, std::string, int>, double>& seconds() {
  static std::map<std::tuple<std::string, std::string, int>, double> table;
  return table;
}

void convert(benchmark::State& state, const std::string& model, const std::string& spec,
             int threads) {
  const std::shared_ptr<const quadtri::TriangleMesh> mesh = benchMesh(spec);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  double total = 0.0;
  int64_t runs = 0;
  for (auto _ : state) {
    // A fresh copy each run, outside the clock: a mesh keeps the adjacency it built
    // (TriangleMesh::topology), and each conversion should pay for building it once, as a
    // command does.
    state.PauseTiming();
    const auto fresh = std::make_shared<const quadtri::TriangleMesh>(*mesh);
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<quadtri::SurfaceModel> converted = quadtri::makeModel(model, fresh);
    benchmark::DoNotOptimize(converted.get());
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++runs;
  }
  seconds()[{model, spec, threads}] = runs > 0 ? total / double(runs) : 0.0;
  state.counters["triangles/s"] = benchmark::Counter(double(mesh->triangleCount()),
                                                     benchmark::Counter::kIsIterationInvariantRate);
  state.counters["target_triangles/s"] = kTargetTrianglesPerSecond;
  state.counters["triangles"] = double(mesh->triangleCount());
  state.counters["threads"] = threads;
}

// icosphere level 5: 20,480 triangles; a 1000×500 torus: 1,000,000 triangles.
const char* const kLargeMesh = "torus:1,0.35,1000,500";
const char* const kMeshes[] = {"icosphere:5", kLargeMesh};
const int kThreads[] = {1, 2};

void printSummary() {
  const auto& table = seconds();
  if (table.empty()) return;
  std::printf("\n%-26s %-24s %12s %12s %14s %10s %8s\n", "model", "mesh", "s (1 thread)",
              "s (2 threads)", "triangles/s", "target", "1->2");
  for (const std::string& model : quadtri::modelNames())
    for (const char* spec : kMeshes) {
      const auto one = table.find({model, spec, 1});
      const auto two = table.find({model, spec, 2});
      if (one == table.end() && two == table.end()) continue;
      const double t1 = one != table.end() ? one->second : 0.0;
      const double t2 = two != table.end() ? two->second : 0.0;
      const double triangles = double(benchMesh(spec)->triangleCount());
      const double best = t2 > 0.0 ? t2 : t1;
      std::printf("%-26s %-24s %12.4f %12.4f %14.4g %10.4g %7.2fx\n", model.c_str(), spec, t1, t2,
                  best > 0.0 ? triangles / best : 0.0, kTargetTrianglesPerSecond,
                  t1 > 0.0 && t2 > 0.0 ? t1 / t2 : 0.0);
    }
}

}  // namespace

int main(int argc, char** argv) {
  for (const std::string& model : quadtri::modelNames())
    for (const char* spec : kMeshes)
      for (int threads : kThreads) {
        benchmark::internal::Benchmark* bench =
            benchmark::RegisterBenchmark(
                ("Convert/" + model + "/" + spec + "/threads:" + std::to_string(threads)).c_str(),
                convert, model, std::string(spec), threads)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
        // On the large mesh a fixed count: where the timed part is nearly free (flat, shading)
        // the iteration count would otherwise grow until the untimed copies of the mesh take
        // minutes.
        if (std::string(spec) == kLargeMesh) bench->Iterations(3);
      }
  registerPeerBenchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  printSummary();
  printPeerSummary();
  return 0;
}
