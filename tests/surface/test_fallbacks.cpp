// Which patches give up a constraint (SurfaceModel::fellBack), the corner counts of
// corner_stats.h and the conversion warning built on both.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/corner_stats.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/nagata_model.h"
#include "quadtri/surface/robust_implicit_model.h"
#include "quadtri/surface/robust_quadric_fit.h"

namespace quadtri {
namespace {

// A 4×4 grid of unit squares in z = 0, each split along its (i, j)-(i+1, j+1) diagonal (32
// triangles facing +z), every normal +z, with vertex (2, 2) lifted to z = 0.3: a step between
// equal normals. Each edge at the lifted vertex joins two parallel tangent planes that do not
// hold it, so no edge curve can be tangent to both; every other edge lies in its planes.
std::shared_ptr<const TriangleMesh> liftedGrid() {
  TriangleMesh mesh;
  const int n = 4;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      mesh.positions.push_back(Vec3(i, j, (i == 2 && j == 2) ? 0.3 : 0.0));
  auto at = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  mesh.normals.assign(mesh.positions.size(), Vec3::UnitZ());
  mesh.normalIndices = mesh.triangles;
  return std::make_shared<const TriangleMesh>(std::move(mesh));
}

// Triangles that use the lifted vertex (2, 2): index 12.
size_t trianglesAtLiftedVertex(const TriangleMesh& mesh) {
  size_t count = 0;
  for (const Tri& tri : mesh.triangles) count += tri[0] == 12 || tri[1] == 12 || tri[2] == 12;
  return count;
}

TEST(Fallbacks, EdgeControlPointReportsWhenItLeavesTheTangentPlanes) {
  bool gaveUp = true;
  // A great-circle edge of the unit sphere: the tangent planes meet, nothing is given up.
  const Vec3 a = Vec3(1, 0, 0), b = Vec3(0, 1, 0);
  edgeControlPoint(a, a, b, b, &gaveUp);
  EXPECT_FALSE(gaveUp);
  // Normals leaning by 0.1 and 0.11 along the edge: the tangent planes z = 0.1x and
  // z = 0.11(x − 1) meet at x = 11, ten edge lengths away; the offset is clamped to one.
  const Vec3 n0 = Vec3(-0.1, 0, 1).normalized(), n1 = Vec3(-0.11, 0, 1).normalized();
  const Vec3 p = edgeControlPoint(Vec3(0, 0, 0), n0, Vec3(1, 0, 0), n1, &gaveUp);
  EXPECT_TRUE(gaveUp);
  EXPECT_NEAR((p - Vec3(0.5, 0, 0)).norm(), 1.0, 1e-12);
  // Equal normals across a step: the damped solve returns the chord midpoint, off both planes.
  const Vec3 q =
      edgeControlPoint(Vec3(0, 0, 0), Vec3::UnitZ(), Vec3(1, 0, 0.3), Vec3::UnitZ(), &gaveUp);
  EXPECT_TRUE(gaveUp);
  EXPECT_LT((q - Vec3(0.5, 0, 0.15)).norm(), 1e-12);
  // Equal normals on a flat edge: the straight edge is exact.
  edgeControlPoint(Vec3(0, 0, 0), Vec3::UnitZ(), Vec3(1, 0, 0), Vec3::UnitZ(), &gaveUp);
  EXPECT_FALSE(gaveUp);
}

TEST(Fallbacks, NagataZeroRuleGivesUpOnlyOffTheTangentPlanes) {
  bool gaveUp = true;
  nagataCurvature(Vec3(0, 0, 0), Vec3::UnitZ(), Vec3(1, 0, 0), Vec3::UnitZ(), &gaveUp);
  EXPECT_FALSE(gaveUp);  // parallel normals, chord in the plane: c = 0 is exact
  nagataCurvature(Vec3(0, 0, 0), Vec3::UnitZ(), Vec3(1, 0, 0.3), Vec3::UnitZ(), &gaveUp);
  EXPECT_TRUE(gaveUp);
  nagataCurvature(Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0), &gaveUp);
  EXPECT_FALSE(gaveUp);  // the formula's own case
}

TEST(Fallbacks, ExactCountOnAStepBetweenEqualNormals) {
  const auto mesh = liftedGrid();
  const size_t T = mesh->triangleCount(), k = trianglesAtLiftedVertex(*mesh);
  ASSERT_EQ(T, 32u);
  ASSERT_EQ(k, 6u);
  // One normal a vertex: quadric-implicit finds its fallbacks triangle by triangle.
  ASSERT_TRUE(edgeControlPointsAreLocal(*mesh));
  // Models whose edge curves must be tangent at both ends: exactly the six triangles at the
  // lifted vertex give up; the others have no edge there.
  for (const char* name :
       {"quadric-edges", "quadric-param", "quadric-implicit", "quadric-edges-eq42", "nagata"}) {
    const std::unique_ptr<SurfaceModel> model = makeModel(name, mesh);
    EXPECT_EQ(model->fallbackCount(), k) << name;
    EXPECT_EQ(fallbackRate(*model), 6.0 / 32.0) << name;
    for (size_t t = 0; t < T; ++t) {
      const Tri& tri = mesh->triangles[t];
      EXPECT_EQ(model->fellBack(t), tri[0] == 12 || tri[1] == 12 || tri[2] == 12) << name << t;
    }
  }
  // Models without a constraint to give up.
  for (const char* name : {"flat", "shading", "shading-offset", "phong", "pn"})
    EXPECT_EQ(makeModel(name, mesh)->fallbackCount(), 0u) << name;
  // The robust model's fallback is the flat patch (no triangle here lacks extent).
  const RobustImplicitModel robust(mesh);
  EXPECT_EQ(robust.fallbackCount(), robust.flatCount());
  for (size_t t = 0; t < T; ++t) EXPECT_EQ(robust.fellBack(t), robust.isFlat(t)) << t;
}

TEST(Fallbacks, SmoothMeshesGiveUpNothing) {
  for (const char* spec : {"icosphere:2", "torus:1,0.35,24,12", "ellipsoid:1,0.7,0.5"}) {
    const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh);
    for (const std::string& name : modelNames())
      EXPECT_EQ(makeModel(name, mesh)->fallbackCount(), 0u) << spec << " " << name;
  }
}

TEST(Fallbacks, RobustPointFallbackForATriangleWithoutExtent) {
  CornerData data;
  data.position = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  data.normal = {Vec3::UnitZ(), Vec3::UnitZ(), Vec3::UnitZ()};
  data.arcMidpoint = {Vec3(0.5, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0, 0.5, 0)};
  EXPECT_FALSE(fitQuadric(data).pointFallback);
  data.position = {Vec3(3, 3, 3), Vec3(3, 3, 3), Vec3(3, 3, 3)};
  data.arcMidpoint = data.position;
  EXPECT_TRUE(fitQuadric(data).pointFallback);
  // One proper triangle and one whose three corners coincide: only the second falls back.
  TriangleMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(3, 3, 3)};
  mesh.triangles = {{0, 1, 2}, {3, 3, 3}};
  mesh.normals = {Vec3::UnitZ()};
  mesh.normalIndices = {{0, 0, 0}, {0, 0, 0}};
  const RobustImplicitModel model(std::make_shared<const TriangleMesh>(std::move(mesh)));
  EXPECT_FALSE(model.fellBack(0));
  EXPECT_TRUE(model.fellBack(1));
  EXPECT_EQ(model.fallbackCount(), 1u);
}

TEST(CornerStats, OneFlippedNormalMakesItsCornersInconsistent) {
  // icosphere:1 with analytic normals, one vertex normal turned inside out: exactly the corners
  // that use it face away from their normal.
  TriangleMesh mesh = makeBuiltin("icosphere", ShapeParams{1}).mesh;
  const uint32_t flipped = mesh.normalIndices[0][0];
  mesh.normals[flipped] = -mesh.normals[flipped];
  size_t k = 0;
  for (const Tri& tri : mesh.normalIndices)
    for (uint32_t i : tri) k += i == flipped;
  ASSERT_GE(k, 5u);
  const auto shared = std::make_shared<const TriangleMesh>(std::move(mesh));
  const size_t corners = 3 * shared->triangleCount();
  const std::unique_ptr<SurfaceModel> flat = makeModel("flat", shared);
  const double unflippedErrorDeg =
      cornerStats(*makeModel("flat", std::make_shared<const TriangleMesh>(
                                         makeBuiltin("icosphere", ShapeParams{1}).mesh)))
          .maxNormalErrorDeg;
  const CornerStats s = cornerStats(*flat);
  EXPECT_EQ(s.corners, corners);
  EXPECT_EQ(s.inconsistent, k);
  EXPECT_EQ(s.inconsistentRate(), double(k) / double(corners));
  // The facet (oriented by its corners' normals, two of three outward) faces away from the
  // flipped normal only: every fold is at an inconsistent corner.
  EXPECT_EQ(s.flips, k);
  EXPECT_EQ(s.consistentFlips, 0u);
  EXPECT_EQ(s.consistentFlipRate(), 0.0);
  EXPECT_GT(s.maxNormalErrorDeg, 90.0);
  ASSERT_TRUE(s.maxConsistentNormalErrorDeg);
  // The consistent corners are corners of the unflipped mesh, with the same facets.
  EXPECT_GT(*s.maxConsistentNormalErrorDeg, 10.0);
  EXPECT_LE(*s.maxConsistentNormalErrorDeg, unflippedErrorDeg);
  EXPECT_EQ(s.nonFinite, 0u);
}

TEST(CornerStats, AWoundBackwardsTriangleIsConsistentAndPnMeetsItsCorners) {
  // icosphere:1 with one triangle's winding reversed: its corner normals all point to the other
  // side, the patch takes that side, and its corners stay consistent. PN's corner tangents are
  // its edges in the tangent planes, so it meets every consistent corner's normal exactly.
  TriangleMesh mesh = makeBuiltin("icosphere", ShapeParams{1}).mesh;
  std::swap(mesh.triangles[3][1], mesh.triangles[3][2]);
  std::swap(mesh.normalIndices[3][1], mesh.normalIndices[3][2]);
  const auto shared = std::make_shared<const TriangleMesh>(std::move(mesh));
  const CornerStats s = cornerStats(*makeModel("pn", shared));
  EXPECT_EQ(s.inconsistent, 0u);
  EXPECT_EQ(s.flips, 0u);
  ASSERT_TRUE(s.maxConsistentNormalErrorDeg);
  EXPECT_LT(*s.maxConsistentNormalErrorDeg, 1e-9);
}

TEST(CornerStats, PnMeetsEveryConsistentCornerOfSplitNormalShapes) {
  // Cube and capped cylinder with split normals: at a crease end PN's corner tangent is the
  // crease line both sides share. Corners whose tangents do not turn the triangle's way are
  // inconsistent; every other corner keeps its normal exactly.
  for (const char* shape : {"cube", "cylinder"}) {
    ShapeParams params;
    params.divisions = 3;
    const auto mesh = std::make_shared<const TriangleMesh>(makeBuiltin(shape, params).mesh);
    const CornerStats s = cornerStats(*makeModel("pn", mesh));
    EXPECT_GT(s.consistent(), 0u) << shape;
    EXPECT_EQ(s.consistentFlips, 0u) << shape;
    ASSERT_TRUE(s.maxConsistentNormalErrorDeg) << shape;
    EXPECT_LT(*s.maxConsistentNormalErrorDeg, 1e-9) << shape;
  }
}

TEST(CornerStats, NoConsistentCornerOnADegenerateTriangle) {
  TriangleMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  mesh.triangles = {{0, 1, 2}};
  mesh.normals = {Vec3::UnitZ()};
  mesh.normalIndices = {{0, 0, 0}};
  const CornerStats s =
      cornerStats(*makeModel("shading", std::make_shared<const TriangleMesh>(std::move(mesh))));
  EXPECT_EQ(s.inconsistent, 3u);
  EXPECT_EQ(s.consistent(), 0u);
  EXPECT_FALSE(s.consistentFlipRate());
  EXPECT_FALSE(s.maxConsistentNormalErrorDeg);
}

TEST(CornerStats, LargestErrorsAreTheLargestCornerAngles) {
  // cornerStats compares angles as (sine, cosine) pairs and takes one atan2 per block of patches:
  // its maxima must be the largest angleDegrees of any corner, bit for bit. The meshes give
  // exact zeros (the lifted grid's flat faces), a flipped normal near 180° and a corner whose
  // flat normal is exactly opposite its corner normal.
  TriangleMesh flipped = makeBuiltin("icosphere", ShapeParams{2}).mesh;
  flipped.normals[flipped.normalIndices[0][0]] *= -1.0;
  TriangleMesh opposite;
  opposite.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  opposite.triangles = {{0, 1, 2}};
  opposite.normals = {Vec3::UnitZ(), -Vec3::UnitZ()};
  opposite.normalIndices = {{0, 0, 1}};
  const std::vector<std::shared_ptr<const TriangleMesh>> meshes = {
      liftedGrid(), std::make_shared<const TriangleMesh>(std::move(flipped)),
      std::make_shared<const TriangleMesh>(std::move(opposite))};
  for (const auto& mesh : meshes)
    for (const char* name : {"flat", "shading", "pn", "quadric-param", "nagata"}) {
      const std::unique_ptr<SurfaceModel> model = makeModel(name, mesh);
      const EdgeEnds ends = edgeEnds(*mesh);
      double worst = 0.0;
      std::optional<double> worstConsistent;
      for (size_t t = 0; t < model->patchCount(); ++t)
        for (int k = 0; k < 3; ++k) {
          const double u = k == 1 ? 1.0 : 0.0, v = k == 2 ? 1.0 : 0.0;
          const double angle =
              angleDegrees(model->evaluate(t, u, v).normal, mesh->cornerNormal(t, k));
          worst = std::max(worst, angle);
          if (consistentCorner(*mesh, ends, t, k))
            worstConsistent = std::max(worstConsistent.value_or(0.0), angle);
        }
      const CornerStats s = cornerStats(*model);
      EXPECT_EQ(s.maxNormalErrorDeg, worst) << name;
      EXPECT_EQ(s.maxConsistentNormalErrorDeg, worstConsistent) << name;
    }
}

TEST(ConversionWarning, NamesTheMeshModelAndBothFigures) {
  const auto mesh = liftedGrid();
  const std::unique_ptr<SurfaceModel> param = makeModel("quadric-param", mesh);
  const CornerStats s = cornerStats(*param);
  const std::optional<std::string> warning = conversionWarning(*param, "grid.obj");
  ASSERT_TRUE(warning);
  EXPECT_EQ(*warning, fmt::format("grid.obj: quadric-param folds at {:.3g}% of consistent corners "
                                  "({} of {}) and falls back on 18.8% of patches (6 of 32)",
                                  100.0 * double(s.consistentFlips) / double(s.consistent()),
                                  s.consistentFlips, s.consistent()));
  // Nothing to say about a smooth mesh, nor about the models that keep their triangles.
  const auto sphere = std::make_shared<const TriangleMesh>(makeBuiltin("icosahedron").mesh);
  for (const std::string& name : modelNames())
    EXPECT_FALSE(conversionWarning(*makeModel(name, sphere), "ico")) << name;
  for (const char* name : {"flat", "shading", "shading-offset"})
    EXPECT_FALSE(conversionWarning(*makeModel(name, mesh), "grid.obj")) << name;
}

}  // namespace
}  // namespace quadtri
