// Conversion throughput of every model (modelNames()), tessellation excluded: the time from a
// loaded mesh to the model's patches, reported as input triangles per second, with 1 and with
// 2 threads (tbb::global_control). A summary after the runs gives each model's seconds per
// 1,000,000-triangle mesh at 2 threads beside the target (0.5 s), and the scaling
// from 1 to 2 threads. Each model converts the 1,000,000-triangle mesh three times.
//
//   quadtri_bench --benchmark_filter=Convert --benchmark_min_time=0.1
//
// Tessellate/<model>/<mesh>/level:N/threads:T times tessellate() alone on a model converted
// once: level 1 on the 1,000,000-triangle torus (the lattice a render of a tessellated model
// builds under `auto` there) and level 8 on icosphere level 5 (an export's default, 1,310,720
// triangles out), with 1 and 2 threads; output triangles per second.
//
//   quadtri_bench --benchmark_filter=Tessellate
//
// Export/<model>/<format> times writing a converted model's patch data as `quadtri convert -o
// x.json` and `-o x.qtp` write it (writeConversionJson, writePatchTable), on icosphere level 6
// (81,920 patches), 2 threads, into a stream that counts and discards the bytes: patches and
// bytes per second.
//
//   quadtri_bench --benchmark_filter=Export
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <ostream>
#include <streambuf>
#include <string>
#include <tuple>

#include "bench_peer.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/convert_output.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

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

// The model converted once per (model, mesh), shared by its tessellation benchmarks.
std::shared_ptr<const quadtri::SurfaceModel> benchModel(const std::string& model,
                                                        const std::string& spec) {
  static std::map<std::pair<std::string, std::string>, std::shared_ptr<const quadtri::SurfaceModel>>
      cache;
  auto& slot = cache[{model, spec}];
  if (!slot) slot = quadtri::makeModel(model, benchMesh(spec));
  return slot;
}

void tessellateModel(benchmark::State& state, const std::string& model, const std::string& spec,
                     int level, int threads) {
  const std::shared_ptr<const quadtri::SurfaceModel> converted = benchModel(model, spec);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const quadtri::Tessellation tessellation{quadtri::Tessellation::Kind::Lattice, level};
  size_t triangles = 0;
  for (auto _ : state) {
    const quadtri::TriangleMesh out = quadtri::tessellate(*converted, tessellation);
    triangles = out.triangleCount();
    benchmark::DoNotOptimize(out.positions.data());
  }
  state.counters["triangles/s"] =
      benchmark::Counter(double(triangles), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["threads"] = threads;
}

// A stream buffer that counts what is written and keeps none of it.
class CountingBuffer : public std::streambuf {
 public:
  size_t bytes = 0;

 protected:
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += size_t(n);
    return n;
  }
  int_type overflow(int_type c) override {
    if (!traits_type::eq_int_type(c, traits_type::eof())) ++bytes;
    return traits_type::not_eof(c);
  }
};

void exportModel(benchmark::State& state, const std::string& model, const std::string& spec,
                 bool table) {
  const std::shared_ptr<const quadtri::SurfaceModel> converted = benchModel(model, spec);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(2));
  size_t bytes = 0;
  for (auto _ : state) {
    CountingBuffer buffer;
    std::ostream out(&buffer);
    if (table)
      quadtri::writePatchTable(*converted, quadtri::Tessellation{}, out);
    else
      quadtri::writeConversionJson(*converted, quadtri::Tessellation{}, out);
    bytes = buffer.bytes;
  }
  state.counters["patches/s"] = benchmark::Counter(double(converted->patchCount()),
                                                   benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes/s"] =
      benchmark::Counter(double(bytes), benchmark::Counter::kIsIterationInvariantRate);
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
  for (const std::string& model : quadtri::modelNames()) {
    if (model == "flat" || model == "shading" || model == "shading-offset") continue;
    for (const auto& [spec, level] : {std::pair{kLargeMesh, 1}, std::pair{"icosphere:5", 8}})
      for (int threads : kThreads)
        benchmark::RegisterBenchmark(("Tessellate/" + model + "/" + spec + "/level:" +
                                      std::to_string(level) + "/threads:" + std::to_string(threads))
                                         .c_str(),
                                     tessellateModel, model, std::string(spec), level, threads)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(3);
  }
  for (const std::string& model : quadtri::modelNames())
    for (const bool table : {false, true})
      benchmark::RegisterBenchmark(("Export/" + model + "/" + (table ? "qtp" : "json")).c_str(),
                                   exportModel, model, std::string("icosphere:6"), table)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(3);
  registerPeerBenchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  printSummary();
  printPeerSummary();
  return 0;
}
