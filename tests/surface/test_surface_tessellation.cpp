// Tessellations of the curved models: counts, welding and closedness.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

#include "quadtri/math/error.h"
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

// position() is evaluate()'s position, bit for bit, for every model (the parametric ones skip
// the normal).
TEST(SurfaceTessellation, PositionIsTheEvaluatedPosition) {
  const auto mesh =
      std::make_shared<const TriangleMesh>(parseBuiltinSpec("torus:1,0.35,12,8")->mesh);
  for (const std::string& name : modelNames()) {
    SCOPED_TRACE(name);
    const auto model = makeModel(name, mesh);
    const std::array<Vec2, 4> uv = {Vec2(0.0, 0.0), Vec2(1.0, 0.0), Vec2(0.0, 1.0),
                                    Vec2(0.25, 0.5)};
    for (size_t t = 0; t < mesh->triangleCount(); t += 7) {
      // positions() is position() at every point, bit for bit, whether or not it is overridden.
      std::array<Vec3, 4> batch;
      model->positions(t, uv.data(), uv.size(), batch.data());
      for (size_t i = 0; i < uv.size(); ++i) {
        const double u = uv[i].x(), v = uv[i].y();
        EXPECT_EQ(model->position(t, u, v), model->evaluate(t, u, v).position) << t;
        EXPECT_EQ(batch[i], model->position(t, u, v)) << t;
      }
    }
  }
}

TEST(SurfaceTessellation, AutoParsesItsToleranceAndRefusesAnythingElse) {
  const Tessellation automatic = Tessellation::parse("auto");
  EXPECT_EQ(automatic.kind, Tessellation::Kind::Adaptive);
  EXPECT_EQ(automatic.tolerance, Tessellation::kDefaultTolerance);
  EXPECT_EQ(automatic.level, Tessellation::kMaxAdaptiveLevel);
  EXPECT_EQ(automatic.trianglesPerPatch(), 1u);  // charged at level 1 until it is resolved
  EXPECT_EQ(Tessellation::parse("auto:2.5e-6").tolerance, 2.5e-6);
  for (const char* bad : {"auto:", "auto:0", "auto:-1e-4", "auto:1", "auto:nan", "auto:inf",
                          "auto:1e-4x", "autox", "auto:0x1p-10q", "0", "257"}) {
    SCOPED_TRACE(bad);
    try {
      (void)Tessellation::parse(bad);
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("'auto:TOLERANCE'"), std::string::npos) << e.what();
    }
  }
}

// The picked level is the lowest whose estimate, levelOneDeviation / n², is within the
// tolerance (or the highest level allowed): coarse meshes keep the highest, dense ones get few
// triangles per patch, and the choice does not depend on the mesh's scale.
// The flat triangle, except at one sample point, where the position is `bad`.
class OnePointModel final : public SurfaceModel {
 public:
  OnePointModel(std::shared_ptr<const TriangleMesh> mesh, Vec2 where, double bad)
      : SurfaceModel(std::move(mesh)), where_(where), bad_(bad) {}
  std::string_view name() const override { return "one-point"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override {
    if (u == where_.x() && v == where_.y()) return {Vec3::Constant(bad_), Vec3::UnitZ()};
    const Vec3 p =
        (1.0 - u - v) * mesh().corner(t, 0) + u * mesh().corner(t, 1) + v * mesh().corner(t, 2);
    return {p, Vec3::UnitZ()};
  }
  void patchRecord(size_t, PatchRecord&) const override {}

 private:
  Vec2 where_;
  double bad_;
};

TEST(SurfaceTessellation, AutoTakesTheHighestLevelWhereAPatchIsNotFinite) {
  // A NaN or infinite position anywhere the deviation samples (a corner, a midpoint, the
  // centroid, a quarter point) makes the estimate infinite, so the level is the highest allowed.
  const auto mesh = icosphere(3);
  for (const Vec2& where :
       {Vec2(0, 0), Vec2(0.5, 0.5), Vec2(1.0 / 3.0, 1.0 / 3.0), Vec2(0.75, 0.25)})
    for (const double bad : {std::nan(""), kInfinity}) {
      const OnePointModel model(mesh, where, bad);
      EXPECT_EQ(levelOneDeviation(model), kInfinity) << where.transpose() << " " << bad;
      EXPECT_EQ(resolveTessellation(model, Tessellation::adaptive()).level,
                Tessellation::kMaxAdaptiveLevel);
    }
  // And a finite flat model deviates by nothing.
  EXPECT_EQ(levelOneDeviation(OnePointModel(mesh, Vec2(-1, -1), 0.0)), 0.0);
}

TEST(SurfaceTessellation, AutoPicksTheLowestLevelWithinItsTolerance) {
  for (const char* name : {"quadric-param", "pn", "phong", "nagata", "quadric-edges"})
    for (int level = 0; level <= 5; ++level)
      for (const double tolerance : {1e-3, 1e-4, 1e-5}) {
        SCOPED_TRACE(::testing::Message()
                     << name << " icosphere " << level << " tolerance " << tolerance);
        const auto mesh = icosphere(level);
        const auto model = makeModel(name, mesh);
        const Tessellation picked = resolveTessellation(*model, Tessellation::adaptive(tolerance));
        ASSERT_EQ(picked.kind, Tessellation::Kind::Lattice);
        const int n = picked.level;
        ASSERT_GE(n, 1);
        ASSERT_LE(n, Tessellation::kMaxAdaptiveLevel);
        const Bounds3 box = mesh->bounds();
        const double allowed = tolerance * (box.hi - box.lo).norm();
        const double deviation = levelOneDeviation(*model);
        ASSERT_GT(deviation, 0.0);
        if (n < Tessellation::kMaxAdaptiveLevel) {
          EXPECT_LE(deviation, allowed * n * n);
        }
        if (n > 1) {
          EXPECT_GT(deviation, allowed * (n - 1) * (n - 1));
        }
        // A sphere's patches bulge by about (edge length)²/8: halving the edges (one icosphere
        // level) quarters the deviation.
        if (level == 0) {
          EXPECT_EQ(n, Tessellation::kMaxAdaptiveLevel);
        }
        if (level == 5 && tolerance == 1e-3) {
          EXPECT_EQ(n, 1);
        }
        // The same choice at any scale.
        for (const double scale : {1e-6, 1e6}) {
          TriangleMesh scaled = *mesh;
          for (Vec3& p : scaled.positions) p *= scale;
          const auto scaledModel = makeModel(name, std::make_shared<const TriangleMesh>(scaled));
          EXPECT_EQ(resolveTessellation(*scaledModel, Tessellation::adaptive(tolerance)).level, n)
              << "scale " << scale;
        }
      }
}

// An S-shaped PN edge (both corner normals tilted the same way along it) is flat at its midpoint;
// the estimate still sees how far the patch strays, from the edges' quarter points (without
// them this test fails).
TEST(SurfaceTessellation, AutoSeesAnSShapedCubicEdge) {
  TriangleMesh tri;
  tri.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  tri.triangles = {{0, 1, 2}};
  // One normal, tilted along (1, 1, 0): edges 0-1 and 0-2 are S-shaped and edge 1-2 is straight,
  // so the patch is flat at every edge's midpoint and at its centroid.
  const Vec3 n = Vec3(0.3, 0.3, 1).normalized();
  tri.normals = {n, n, n};
  tri.normalIndices = tri.triangles;
  const auto model = makeModel("pn", std::make_shared<const TriangleMesh>(tri));
  const Vec3 c[3] = {model->position(0, 0, 0), model->position(0, 1, 0), model->position(0, 0, 1)};
  double worst = 0.0, midpoint = 0.0;
  for (int i = 0; i <= 64; ++i)
    for (int j = 0; i + j <= 64; ++j) {
      const double u = i / 64.0, v = j / 64.0;
      const double d =
          (model->position(0, u, v) - ((1 - u - v) * c[0] + u * c[1] + v * c[2])).norm();
      worst = std::max(worst, d);
      if (i == 32 && j == 0) midpoint = d;
    }
  EXPECT_LT(midpoint, 1e-3 * worst);  // the edge is S-shaped: flat at its midpoint
  EXPECT_LT((model->position(0, 1 / 3.0, 1 / 3.0) - (c[0] + c[1] + c[2]) / 3.0).norm(),
            1e-3 * worst);
  EXPECT_GE(levelOneDeviation(*model), 0.75 * worst);  // 80% here: an estimate, not a bound
}

// For a quadratic patch (quadric-param) the estimate is a bound: every lattice triangle of the
// picked level lies within the tolerance of the surface, here checked at its edges' midpoints
// and its centroid, where a quadratic's distance from its flat interpolant peaks.
TEST(SurfaceTessellation, AutoLatticeOfAQuadraticModelStaysWithinItsTolerance) {
  for (const char* spec : {"ellipsoid:1,0.7,0.5,4", "torus:1,0.35,64,32", "icosphere:4", "genus2"})
    for (const double tolerance : {1e-3, 1e-4}) {
      SCOPED_TRACE(::testing::Message() << spec << " tolerance " << tolerance);
      const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh);
      const auto model = makeModel("quadric-param", mesh);
      const int n = resolveTessellation(*model, Tessellation::adaptive(tolerance)).level;
      // At the highest level the tolerance may be out of reach (genus2 at 1e-4).
      const bool highest = n == Tessellation::kMaxAdaptiveLevel;
      const Bounds3 box = mesh->bounds();
      const double allowed = tolerance * (box.hi - box.lo).norm();
      double worst = 0.0;
      const auto at = [&](size_t t, double u, double v) {
        return model->evaluate(t, u / n, v / n).position;
      };
      for (size_t t = 0; t < mesh->triangleCount(); ++t)
        for (int a = 0; a < n; ++a)
          for (int b = 0; a + b < n; ++b)
            for (int flip = 0; flip < 2 && (flip == 0 || a + b + 2 <= n); ++flip) {
              // Lattice triangle (upright, or flipped) with corners in lattice units.
              const double c[3][2] = {{double(a + flip), double(b + flip)},
                                      {double(a + 1 - flip), double(b + flip)},
                                      {double(a + flip), double(b + 1 - flip)}};
              const Vec3 p[3] = {at(t, c[0][0], c[0][1]), at(t, c[1][0], c[1][1]),
                                 at(t, c[2][0], c[2][1])};
              const double w[4][3] = {
                  {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}, {1 / 3.0, 1 / 3.0, 1 / 3.0}};
              for (const auto& s : w) {
                const double u = s[0] * c[0][0] + s[1] * c[1][0] + s[2] * c[2][0];
                const double v = s[0] * c[0][1] + s[1] * c[1][1] + s[2] * c[2][1];
                const Vec3 flat = s[0] * p[0] + s[1] * p[1] + s[2] * p[2];
                worst = std::max(worst, (at(t, u, v) - flat).norm());
              }
            }
      if (!highest) {
        EXPECT_LE(worst, allowed * (1.0 + 1e-9));
        EXPECT_GT(worst, 0.05 * allowed);  // and the level is not needlessly high
      }
      // The estimate bounds what the lattice does, not only after rounding the level up.
      EXPECT_LE(worst, levelOneDeviation(*model) / (n * n) * (1.0 + 1e-9));
    }
}

}  // namespace
}  // namespace quadtri
