// Tessellations of the curved models: counts, welding and closedness.
#include <gtest/gtest.h>

#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {
namespace {

std::shared_ptr<const TriangleMesh> icosphere(int level) {
  ShapeParams p;
  p.level = level;
  return std::make_shared<const TriangleMesh>(makeBuiltin("icosphere", p).mesh);
}

TEST(SurfaceTessellation, WeldedLatticeOfAnIcosphereIsAClosedSphere) {
  for (const char* name : {"quadric-edges", "quadric-param"})
    for (int level = 0; level <= 2; ++level)
      for (int n : {1, 2, 3, 8}) {
        const auto mesh = icosphere(level);
        const MeshTopology inputTopo(*mesh);
        const TriangleMesh out =
            tessellate(*makeModel(name, mesh), Tessellation{Tessellation::Kind::Lattice, n});
        const size_t T = mesh->triangleCount();
        EXPECT_EQ(out.triangleCount(), T * size_t(n * n)) << name;
        // Welded: each mesh vertex once, n-1 points per mesh edge, the rest inside the patches.
        EXPECT_EQ(out.positions.size(), mesh->positions.size() +
                                            inputTopo.edges.size() * size_t(n - 1) +
                                            T * size_t((n - 1) * (n - 2) / 2))
            << name;
        const MeshTopology topo(out);
        EXPECT_TRUE(topo.isClosed()) << name << " level " << level << " n " << n;
        EXPECT_EQ(long(out.positions.size()) - long(topo.edges.size()) + long(out.triangleCount()),
                  2)
            << name;
      }
}

TEST(SurfaceTessellation, ThesisPresetHas4802TrianglesAnd2500PointsPerPatch) {
  const Tessellation thesis = Tessellation::parse("thesis");
  EXPECT_EQ(thesis.trianglesPerPatch(), 4802u);
  const auto mesh = std::make_shared<const TriangleMesh>(makeBuiltin("icosahedron").mesh);
  // eq42 is not welded, so every patch keeps its own 2500 uv points.
  const TriangleMesh eq42 = tessellate(*makeModel("quadric-edges-eq42", mesh), thesis);
  EXPECT_EQ(eq42.triangleCount(), 4802u * 20);
  EXPECT_EQ(eq42.positions.size(), 2500u * 20);
  const TriangleMesh param = tessellate(*makeModel("quadric-param", mesh), thesis);
  EXPECT_EQ(param.triangleCount(), 4802u * 20);
  EXPECT_LT(param.positions.size(), 2500u * 20);
}

TEST(SurfaceTessellation, Eq42IsNotWelded) {
  const auto mesh = icosphere(1);
  const int n = 4;
  const TriangleMesh out = tessellate(*makeModel("quadric-edges-eq42", mesh),
                                      Tessellation{Tessellation::Kind::Lattice, n});
  EXPECT_EQ(out.positions.size(), mesh->triangleCount() * size_t((n + 1) * (n + 2) / 2));
  EXPECT_EQ(MeshTopology(out).boundaryEdgeCount(), mesh->triangleCount() * size_t(3 * n));
}

}  // namespace
}  // namespace quadtri
