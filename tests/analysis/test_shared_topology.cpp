// One edge adjacency per mesh (TriangleMesh::topology): the loader's repair, the normals, a
// model, its metrics and its tessellation share it; copies and edited meshes get their own.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include "quadtri/analysis/metrics.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {
namespace {

// The adjacency two meshes' topologies describe is the same edge for edge.
void expectSameTopology(const MeshTopology& a, const MeshTopology& b) {
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (size_t e = 0; e < a.edges.size(); ++e) {
    EXPECT_EQ(a.edges[e].a, b.edges[e].a);
    EXPECT_EQ(a.edges[e].b, b.edges[e].b);
    EXPECT_EQ(a.edges[e].sides.size(), b.edges[e].sides.size());
  }
  EXPECT_EQ(a.edgeOf, b.edgeOf);
}

TEST(SharedTopology, ABuiltMeshBuildsItOnceForModelMetricsAndTessellation) {
  BuiltinMesh b = makeBuiltin("torus");
  auto mesh = std::make_shared<const TriangleMesh>(std::move(b.mesh));
  // Every model that needs adjacency (edge curves, creases, bridges), then the metrics (edge
  // continuity, crack rate on a closed mesh) and a tessellation of each.
  for (const char* name : {"quadric-implicit-robust", "pn", "quadric-param", "quadric-g1"}) {
    const std::unique_ptr<SurfaceModel> model = makeModel(name, mesh);
    AnalysisOptions options;
    options.crack.lines = 100;
    analyzeModel(*model, "torus", std::nullopt, 0.0, options);
    tessellate(*model, Tessellation{});
  }
  EXPECT_EQ(mesh->topologyCache.builds(), 1u);
  expectSameTopology(mesh->topology(), MeshTopology(*mesh));
}

TEST(SharedTopology, TheLoaderKeepsTheRepairsAdjacency) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("quadtri-shared-topology-" + std::to_string(::getpid()) + ".obj");
  saveMesh(makeBuiltin("icosphere").mesh, path);
  // Default normals: angle-weighted, split at creases, from the adjacency the repair built.
  const TriangleMesh loaded = loadMesh(path);
  std::filesystem::remove(path);
  const auto mesh = std::make_shared<const TriangleMesh>(loaded);  // a copy: builds its own
  EXPECT_EQ(loaded.topologyCache.builds(), 0u);
  expectSameTopology(loaded.topology(), MeshTopology(loaded));
  EXPECT_EQ(loaded.topologyCache.builds(), 0u);
  makeModel("quadric-implicit-robust", mesh);
  EXPECT_EQ(mesh->topologyCache.builds(), 1u);
}

TEST(SharedTopology, EditedAndCopiedMeshesAreRebuilt) {
  TriangleMesh mesh = makeBuiltin("icosahedron").mesh;
  EXPECT_TRUE(mesh.topology().isClosed());
  TriangleMesh copy = mesh;
  EXPECT_EQ(copy.topologyCache.builds(), 0u);
  // Dropping a face opens the mesh: the resized array is noticed without forget().
  copy.triangles.pop_back();
  EXPECT_FALSE(copy.topology().isClosed());
  EXPECT_EQ(copy.topology().boundaryEdgeCount(), 3u);
  EXPECT_TRUE(mesh.topology().isClosed());
  // An edit in place is noticed after forget().
  std::swap(mesh.triangles[0][1], mesh.triangles[0][2]);
  mesh.topologyCache.forget();
  expectSameTopology(mesh.topology(), MeshTopology(mesh));
  EXPECT_EQ(mesh.topologyCache.builds(), 2u);
}

TEST(SharedTopology, RequestsFromManyThreadsSeeOneAdjacency) {
  const TriangleMesh mesh = makeBuiltin("torus").mesh;
  std::vector<const MeshTopology*> seen(64, nullptr);
  parallelFor(size_t(0), seen.size(), [&](size_t i) { seen[i] = &mesh.topology(); });
  for (const MeshTopology* t : seen) EXPECT_EQ(t, &mesh.topology());
  expectSameTopology(mesh.topology(), MeshTopology(mesh));
}

}  // namespace
}  // namespace quadtri
