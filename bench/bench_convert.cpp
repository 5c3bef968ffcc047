// Conversion throughput of every model (modelNames()), tessellation excluded: the time from a
// loaded mesh to the model's patches, reported as input triangles per second.
//
//   quadtri_bench --benchmark_filter=Convert --benchmark_min_time=0.1
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/model.h"

namespace {

// The meshes are built once, on first use, and shared by every model's benchmark.
std::shared_ptr<const quadtri::TriangleMesh> benchMesh(const std::string& spec) {
  static std::map<std::string, std::shared_ptr<const quadtri::TriangleMesh>> cache;
  auto& slot = cache[spec];
  if (!slot) {
    slot = std::make_shared<const quadtri::TriangleMesh>(quadtri::parseBuiltinSpec(spec)->mesh);
  }
  return slot;
}

void convert(benchmark::State& state, const std::string& model, const std::string& spec) {
  const std::shared_ptr<const quadtri::TriangleMesh> mesh = benchMesh(spec);
  for (auto _ : state) {
    std::unique_ptr<quadtri::SurfaceModel> converted = quadtri::makeModel(model, mesh);
    benchmark::DoNotOptimize(converted.get());
  }
  state.counters["triangles/s"] = benchmark::Counter(double(mesh->triangleCount()),
                                                     benchmark::Counter::kIsIterationInvariantRate);
  state.counters["triangles"] = double(mesh->triangleCount());
}

// icosphere level 5: 20,480 triangles; a 1000×500 torus: 1,000,000 triangles.
const char* const kMeshes[] = {"icosphere:5", "torus:1,0.35,1000,500"};

}  // namespace

int main(int argc, char** argv) {
  for (const std::string& model : quadtri::modelNames())
    for (const char* spec : kMeshes)
      benchmark::RegisterBenchmark(("Convert/" + model + "/" + spec).c_str(), convert, model,
                                   std::string(spec))
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
