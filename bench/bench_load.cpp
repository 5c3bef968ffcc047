// Loading and writing meshes (the loading target): a 1,000,000-triangle torus written as
// OBJ and as binary PLY once, then timed as `quadtri convert big.obj --model flat -o big.ply`
// spends it: loadMesh (the checks, Assimp, welding, repairs, normals, validation) and saveMesh.
// On 2 threads (tbb::global_control), wall-clock time. A summary after the runs gives each
// step's seconds beside the target: load and write back as PLY in under 1.5 s.
//
//   quadtri_bench_load --benchmark_min_time=1
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"

namespace {

namespace fs = std::filesystem;

// The target: a 1,000,000-triangle OBJ or binary PLY loads and writes back as PLY in
// under 1.5 s on 2 cores.
constexpr double kTargetSeconds = 1.5;
constexpr const char* kSpec = "torus:1,0.35,1000,500";

fs::path workDir() {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / "quadtri_bench_load";
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// The torus, and its files in each format, made once on first use.
const quadtri::TriangleMesh& torus() {
  static const quadtri::TriangleMesh mesh = quadtri::parseBuiltinSpec(kSpec)->mesh;
  return mesh;
}

fs::path meshFile(const std::string& ext) {
  const fs::path path = workDir() / ("torus" + ext);
  if (!fs::exists(path)) quadtri::saveMesh(torus(), path);
  return path;
}

std::map<std::string, double>& seconds() {
  static std::map<std::string, double> table;
  return table;
}

template <typename Step>
void timed(benchmark::State& state, const std::string& name, const Step& step) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  double total = 0.0;
  int64_t runs = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    step();
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++runs;
  }
  seconds()[name] = runs > 0 ? total / double(runs) : 0.0;
  state.counters["triangles"] = double(torus().triangleCount());
  state.counters["triangles/s"] = benchmark::Counter(double(torus().triangleCount()),
                                                     benchmark::Counter::kIsIterationInvariantRate);
}

// Load, and load then write back as binary PLY (what the target times).
void load(benchmark::State& state, const std::string& ext, bool write) {
  const fs::path in = meshFile(ext);
  const fs::path out = workDir() / "out.ply";
  timed(state, (write ? "LoadSave/" : "Load/") + ext.substr(1), [&] {
    const quadtri::TriangleMesh mesh = quadtri::loadMesh(in);
    benchmark::DoNotOptimize(mesh.triangles.data());
    if (write) quadtri::saveMesh(mesh, out);
  });
}

void save(benchmark::State& state, const std::string& ext) {
  const quadtri::TriangleMesh& mesh = torus();
  const fs::path out = workDir() / ("out" + ext);
  timed(state, "Save/" + ext.substr(1), [&] { quadtri::saveMesh(mesh, out); });
}

void printSummary() {
  if (seconds().empty()) return;
  std::printf("\n%s (%zu triangles), 2 threads\n%-16s %10s %10s\n", kSpec, torus().triangleCount(),
              "step", "seconds", "target");
  for (const auto& [name, s] : seconds())
    if (name.rfind("LoadSave/", 0) == 0)
      std::printf("%-16s %10.3f %10.3f\n", name.c_str(), s, kTargetSeconds);
    else
      std::printf("%-16s %10.3f\n", name.c_str(), s);
}

}  // namespace

int main(int argc, char** argv) {
  for (const char* ext : {".obj", ".ply"}) {
    benchmark::RegisterBenchmark((std::string("Load/") + (ext + 1)).c_str(), load, ext, false)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark((std::string("LoadSave/") + (ext + 1)).c_str(), load, ext, true)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark((std::string("Save/") + (ext + 1)).c_str(), save, ext)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  printSummary();
  std::error_code ec;
  fs::remove_all(workDir(), ec);
  return 0;
}
