#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "fixtures/sphere_patches.h"
#include "quadtri/analysis/metrics.h"
#include "quadtri/io/csv.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

// The unit-circumradius icosahedron: inradius sqrt((5 + 2√5)/15), dihedral angle
// acos(−√5/3), so adjacent face normals differ by acos(√5/3) = 41.81°.
const double kInradius = std::sqrt((5.0 + 2.0 * std::sqrt(5.0)) / 15.0);
const double kNormalJumpDeg = std::acos(std::sqrt(5.0) / 3.0) * 180.0 / kPi;

TEST(Metrics, FlatAndShadingOnTheIcosahedron) {
  const BuiltinMesh ico = makeBuiltin("icosahedron");
  const auto mesh = std::make_shared<const TriangleMesh>(ico.mesh);
  EXPECT_NEAR(kInradius, 0.7947, 1e-4);
  for (const char* name : {"flat", "shading"}) {
    const std::unique_ptr<SurfaceModel> model = makeModel(name, mesh);
    AnalysisOptions options;
    options.crack.lines = 20000;
    const ModelMetrics m = analyzeModel(*model, "icosahedron", ico.truth, 0.5, options);
    EXPECT_EQ(m.model, name);
    EXPECT_EQ(m.triangles, 20u);
    EXPECT_EQ(m.primitives, 20u);
    // 12 float3 positions and 20 uint3 triangles; `shading` adds its 12 float3 normals.
    EXPECT_EQ(m.memoryBytes, std::string(name) == "flat" ? 384u : 528u);
    EXPECT_EQ(m.convertSeconds, 0.5);
    EXPECT_EQ(m.vertexPositionError, 0.0);
    // The face normal points at the centroid; the vertex normal at the vertex.
    EXPECT_NEAR(m.vertexNormalErrorDeg, std::acos(kInradius) * 180.0 / kPi, 1e-9);
    ASSERT_TRUE(m.c0Gap && m.c1AngleDeg && m.crackRate && m.truthDistance);
    EXPECT_EQ(*m.c0Gap, 0.0);
    EXPECT_NEAR(*m.c1AngleDeg, kNormalJumpDeg, 1e-9);
    EXPECT_NEAR(*m.c1AngleDeg, 41.81, 0.005);
    EXPECT_EQ(*m.crackRate, 0.0);
    // The face centroids (on the lattice) are the points farthest inside the unit sphere.
    EXPECT_NEAR(*m.truthDistance, 1.0 - kInradius, 1e-12);
  }
}

// `shading-offset` only moves ray origins: it is shading's geometry, so every key but the
// model name (and the caller's conversion time) is shading's, bit for bit, through the JSON too.
TEST(Metrics, ShadingOffsetMeasuresExactlyAsShading) {
  ShapeParams p;
  p.level = 2;
  const BuiltinMesh sphere = makeBuiltin("icosphere", p);
  const auto mesh = std::make_shared<const TriangleMesh>(sphere.mesh);
  AnalysisOptions options;
  options.crack.lines = 5000;
  const ModelMetrics a =
      analyzeModel(*makeModel("shading", mesh), "icosphere:2", sphere.truth, 0.25, options);
  const ModelMetrics b =
      analyzeModel(*makeModel("shading-offset", mesh), "icosphere:2", sphere.truth, 0.25, options);
  EXPECT_EQ(b.model, "shading-offset");
  nlohmann::ordered_json ja = toJson(a), jb = toJson(b);
  EXPECT_EQ(jb["model"], "shading-offset");
  ja.erase("model");
  jb.erase("model");
  EXPECT_EQ(ja, jb);
  EXPECT_EQ(b.primitives, 320u);
  // 162 float3 positions, 320 uint3 triangles and 162 float3 normals.
  EXPECT_EQ(b.memoryBytes, (162u + 320u + 162u) * 12u);
  ASSERT_TRUE(b.c1AngleDeg && b.crackRate && b.truthDistance);
  EXPECT_GT(*b.c1AngleDeg, 5.0);
  EXPECT_EQ(*b.crackRate, 0.0);
}

TEST(Metrics, AnInflectionEdgeFoldsTheQuadraticPatchOverItsCorner) {
  // Two triangles of the plane z = 0 whose normals lean towards -x, by 0.1 at x = 0 and by 0.5
  // at x = 1. Along the x edges both tangent planes lean the same way (an inflection), so they
  // meet at x = 1.25, beyond the edge: the quadratic edge with those end tangents overshoots
  // x = 1 and turns back, and the patch's normal at such a corner is the exact opposite of the
  // vertex normal although its tangent plane is the vertex's.
  TriangleMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  mesh.triangles = {{0, 1, 3}, {0, 3, 2}};
  mesh.normals = {Vec3(-0.1, 0, 1).normalized(), Vec3(-0.5, 0, 1).normalized(),
                  Vec3(-0.1, 0, 1).normalized(), Vec3(-0.5, 0, 1).normalized()};
  mesh.normalIndices = mesh.triangles;
  const auto shared = std::make_shared<const TriangleMesh>(std::move(mesh));
  const std::unique_ptr<SurfaceModel> param = makeModel("quadric-param", shared);
  const double rate = vertexNormalFlipRate(*param);
  EXPECT_GT(rate, 0.0);
  EXPECT_LT(rate, 1.0);
  EXPECT_NEAR(vertexNormalErrorDeg(*param), 180.0, 1e-6);
  // Interpolated shading normals never fold.
  EXPECT_EQ(vertexNormalFlipRate(*makeModel("shading", shared)), 0.0);
  // On the icosahedron's convex corners nothing folds.
  const auto ico = std::make_shared<const TriangleMesh>(makeBuiltin("icosahedron").mesh);
  EXPECT_EQ(vertexNormalFlipRate(*makeModel("quadric-param", ico)), 0.0);
}

TEST(Metrics, EdgeSamplesMatchAcrossOppositeTraversals) {
  // Linear patches of a welded mesh agree along every shared edge only if each side maps the
  // edge parameter in its own direction; mixed windings exercise both mappings.
  ShapeParams p;
  p.level = 2;
  TriangleMesh mesh = makeBuiltin("icosphere", p).mesh;
  for (size_t t = 0; t < mesh.triangleCount(); t += 3)
    std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
  mesh.normalIndices = mesh.triangles;
  const auto shared = std::make_shared<const TriangleMesh>(std::move(mesh));
  const std::unique_ptr<SurfaceModel> model = makeModel("flat", shared);
  const std::optional<EdgeContinuity> c = edgeContinuity(*model, MeshTopology(*shared), 7);
  ASSERT_TRUE(c);
  // A reversed mapping would be off by up to a whole edge; rounding is all that remains.
  EXPECT_LT(c->c0Gap, 1e-14);
}

TEST(Metrics, ScaleInvariant) {
  ShapeParams p;
  p.level = 1;
  const BuiltinMesh sphere = makeBuiltin("icosphere", p);
  const auto unit = std::make_shared<const TriangleMesh>(sphere.mesh);
  TriangleMesh big = sphere.mesh;
  for (Vec3& x : big.positions) x *= 1e8;
  const auto scaled = std::make_shared<const TriangleMesh>(std::move(big));
  const std::unique_ptr<SurfaceModel> a = makeModel("shading", unit),
                                      b = makeModel("shading", scaled);
  EXPECT_EQ(vertexPositionError(*b), 0.0);
  EXPECT_NEAR(vertexNormalErrorDeg(*a), vertexNormalErrorDeg(*b), 1e-9);
  const MeshTopology topo(*unit);
  EXPECT_NEAR(edgeContinuity(*a, topo)->c1AngleDeg, edgeContinuity(*b, topo)->c1AngleDeg, 1e-9);
  const AnalyticSurface bigSphere{AnalyticSurface::Kind::Sphere, 1e8};
  EXPECT_NEAR(truthDistance(*a, *sphere.truth), truthDistance(*b, bigSphere), 1e-9);
}

// A model that meets every constraint on a mesh inscribed in the unit sphere with radial
// normals: each flat point projected onto the sphere. Rendered tessellated, or as the sphere's
// quadric patches, so both render paths of the analysis are exercised with known answers.
class SphereProjection final : public SurfaceModel {
 public:
  SphereProjection(std::shared_ptr<const TriangleMesh> mesh, Representation representation)
      : SurfaceModel(std::move(mesh)), representation_(representation) {
    if (representation == Representation::Implicit)
      patches_ = fixtures::spherePatches(this->mesh());
  }
  std::string_view name() const override { return "sphere-projection"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override {
    const TriangleMesh& m = mesh();
    const Vec3 p =
        ((1 - u - v) * m.corner(t, 0) + u * m.corner(t, 1) + v * m.corner(t, 2)).normalized();
    return {p, p};
  }
  Representation representation() const override { return representation_; }
  const std::vector<QuadricPatch>& renderPatches() const override { return patches_; }
  size_t patchMemoryBytes() const override { return patches_.size() * sizeof(QuadricPatch); }
  void patchRecord(size_t, PatchRecord&) const override {}

 private:
  Representation representation_;
  std::vector<QuadricPatch> patches_;
};

// The flat triangle, except at one corner of one patch, where it is not finite.
class NotFiniteAtOneCorner final : public SurfaceModel {
 public:
  NotFiniteAtOneCorner(std::shared_ptr<const TriangleMesh> mesh, size_t patch)
      : SurfaceModel(std::move(mesh)), patch_(patch) {}
  std::string_view name() const override { return "not-finite"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override {
    const TriangleMesh& m = mesh();
    Vec3 p = (1 - u - v) * m.corner(t, 0) + u * m.corner(t, 1) + v * m.corner(t, 2);
    if (t == patch_ && u == 1.0 && v == 0.0) p.y() = std::nan("");
    return {p, m.faceNormal(t)};
  }
  void patchRecord(size_t, PatchRecord&) const override {}

 private:
  size_t patch_;
};

TEST(Metrics, RefuseAPatchThatIsNotFiniteNamingThePoint) {
  // Each metric that evaluates patch points (several at a time) names the first that is not
  // finite, and reports no value.
  ShapeParams p;
  p.level = 1;
  const BuiltinMesh sphere = makeBuiltin("icosphere", p);
  const auto mesh = std::make_shared<const TriangleMesh>(sphere.mesh);
  const NotFiniteAtOneCorner model(mesh, 7);
  const std::string expected = "patch 7 is not finite at (u, v) = (1, 0)";
  const auto message = [](const auto& run) {
    try {
      run();
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { vertexPositionError(model); }).find(expected), std::string::npos);
  EXPECT_NE(message([&] { truthDistance(model, *sphere.truth, 4); }).find(expected),
            std::string::npos);
  EXPECT_NE(message([&] { edgeContinuity(model, MeshTopology(*mesh), 5); }).find(expected),
            std::string::npos);
  // Without the bad point every one of them has a value.
  const NotFiniteAtOneCorner fine(mesh, mesh->triangleCount());
  EXPECT_EQ(vertexPositionError(fine), 0.0);
  EXPECT_TRUE(edgeContinuity(fine, MeshTopology(*mesh), 5).has_value());
}

TEST(Metrics, TessellatedModelMeetingEveryConstraint) {
  ShapeParams p;
  p.level = 1;
  const BuiltinMesh sphere = makeBuiltin("icosphere", p);
  const auto mesh = std::make_shared<const TriangleMesh>(sphere.mesh);
  const SphereProjection model(mesh, Representation::Tessellated);
  AnalysisOptions options;
  options.tessellation = Tessellation::parse("4");
  options.crack.lines = 20000;
  const ModelMetrics m = analyzeModel(model, "icosphere:1", sphere.truth, 0.0, options);
  const size_t n = 4, T = mesh->triangleCount(), E = MeshTopology(*mesh).edges.size();
  EXPECT_EQ(m.primitives, T * n * n);
  // Welded lattice: mesh vertices, n-1 points per edge, (n-1)(n-2)/2 inside each patch; each
  // with a float3 position and a float3 normal, plus a uint3 per triangle.
  const size_t vertices = mesh->positions.size() + E * (n - 1) + T * (n - 1) * (n - 2) / 2;
  EXPECT_EQ(m.memoryBytes, 12 * (2 * vertices + T * n * n));
  EXPECT_LT(m.vertexPositionError, 1e-15);
  EXPECT_LT(m.vertexNormalErrorDeg, 1e-6);
  ASSERT_TRUE(m.c0Gap && m.c1AngleDeg && m.crackRate && m.truthDistance);
  EXPECT_LT(*m.c0Gap, 1e-15);
  EXPECT_LT(*m.c1AngleDeg, 1e-6);
  EXPECT_EQ(*m.crackRate, 0.0);
  EXPECT_LT(*m.truthDistance, 1e-15);
}

TEST(Metrics, ImplicitModelIsMeasuredThroughItsPatches) {
  const BuiltinMesh ico = makeBuiltin("icosahedron");
  const SphereProjection model(std::make_shared<const TriangleMesh>(ico.mesh),
                               Representation::Implicit);
  AnalysisOptions options;
  options.crack.lines = 20000;
  const ModelMetrics m = analyzeModel(model, "icosahedron", ico.truth, 0.0, options);
  EXPECT_EQ(m.primitives, 20u);
  EXPECT_EQ(m.memoryBytes, 20 * sizeof(QuadricPatch));
  ASSERT_TRUE(m.crackRate && m.truthDistance);
  // The patches' shared planes are exact opposites, so the sphere is watertight.
  EXPECT_EQ(*m.crackRate, 0.0);
  EXPECT_LT(*m.truthDistance, 1e-15);
}

TEST(Metrics, OpenMeshHasNoCrackRateAndLoneTriangleNoEdgeMetrics) {
  const BuiltinMesh tri = makeBuiltin("triangle");
  const std::unique_ptr<SurfaceModel> model =
      makeModel("flat", std::make_shared<const TriangleMesh>(tri.mesh));
  const ModelMetrics m = analyzeModel(*model, "triangle", std::nullopt, 0.0);
  EXPECT_FALSE(m.c0Gap || m.c1AngleDeg || m.crackRate || m.truthDistance);
  const nlohmann::ordered_json j = toJson(m);
  for (const char* key : {"c0_gap", "c1_angle_deg", "c1_angle_smooth_deg", "g1_edge_share",
                          "crack_rate", "truth_distance"})
    EXPECT_TRUE(j.at(key).is_null()) << key;
}

TEST(Metrics, JsonAndTableCarryEveryKey) {
  ModelMetrics m;
  m.model = "flat";
  m.mesh = "x.obj";
  m.triangles = 4;
  m.primitives = 4;
  m.memoryBytes = 96;
  m.c0Gap = 0.25;
  const nlohmann::ordered_json j = toJson(m);
  const std::vector<std::string> keys = {"model",
                                         "mesh",
                                         "triangles",
                                         "primitives",
                                         "memory_bytes",
                                         "convert_seconds",
                                         "vertex_position_error",
                                         "vertex_normal_error_deg",
                                         "vertex_normal_flip_rate",
                                         "inconsistent_corner_rate",
                                         "vertex_normal_error_consistent_deg",
                                         "vertex_normal_flip_rate_consistent",
                                         "fallback_rate",
                                         "c0_gap",
                                         "c1_angle_deg",
                                         "c1_angle_smooth_deg",
                                         "g1_edge_share",
                                         "crack_rate",
                                         "truth_distance",
                                         "crack_rate_undefined"};
  EXPECT_EQ(metricKeys(), keys);
  EXPECT_EQ(j.size(), keys.size());
  for (const std::string& key : keys) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(j.at("vertex_normal_flip_rate_consistent").is_null());
  EXPECT_EQ(j.at("c0_gap").get<double>(), 0.25);
  EXPECT_EQ(j.at("memory_bytes").get<size_t>(), 96u);
  const std::string table = metricsTable({m, m});
  // Header and two rows, all of one width; nulls print as "-".
  std::vector<std::string> lines;
  for (size_t start = 0, end; (end = table.find('\n', start)) != std::string::npos; start = end + 1)
    lines.push_back(table.substr(start, end - start));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].size(), lines[1].size());
  EXPECT_EQ(lines[1], lines[2]);
  EXPECT_NE(lines[1].find(" -"), std::string::npos);
  EXPECT_EQ(lines[1].rfind("flat", 0), 0u);
  // Every key but "mesh" and the crack rate's reason (a line under the table) is a column.
  for (const std::string& key : keys) {
    if (key == "crack_rate_undefined") continue;
    EXPECT_EQ(lines[0].find(key) != std::string::npos, key != "mesh") << key;
  }
}

TEST(Metrics, CsvFollowsTheKeysAndReadsBack) {
  ModelMetrics m;
  m.model = "nagata";
  m.mesh = "a, \"quoted\" mesh.obj";
  m.triangles = 7;
  m.convertSeconds = 0.1;
  m.vertexNormalErrorConsistentDeg = 12.5;
  m.crackRate = 0.0625;
  const CsvTable csv = parseCsv(metricsCsv({m}), "metrics.csv");
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0], metricKeys());
  const std::vector<std::string>& row = csv.rows[1];
  ASSERT_EQ(row.size(), metricKeys().size());
  auto field = [&](const std::string& key) {
    return row[size_t(std::find(metricKeys().begin(), metricKeys().end(), key) -
                      metricKeys().begin())];
  };
  EXPECT_EQ(field("mesh"), m.mesh);
  EXPECT_EQ(field("triangles"), "7");
  EXPECT_EQ(std::stod(field("convert_seconds")), 0.1);  // round-trips exactly
  EXPECT_EQ(field("vertex_normal_error_consistent_deg"), "12.5");
  EXPECT_EQ(field("vertex_normal_flip_rate_consistent"), "");  // null
  EXPECT_EQ(field("crack_rate"), "0.0625");
  EXPECT_EQ(field("truth_distance"), "");
  EXPECT_EQ(csvValue(nlohmann::ordered_json(std::nan(""))), "");
}

// Every model on an icosphere with its analytic normals: every corner is consistent, so the
// consistent-corner figures are the all-corner ones, and nothing falls back.
TEST(Metrics, ConsistentFiguresEqualTheAllCornerOnesWhenEveryCornerIsConsistent) {
  const BuiltinMesh sphere = makeBuiltin("icosphere", ShapeParams{2});
  const auto mesh = std::make_shared<const TriangleMesh>(sphere.mesh);
  AnalysisOptions options;
  options.crack.lines = 500;
  for (const std::string& name : modelNames()) {
    const ModelMetrics m = analyzeNamedModel(name, mesh, "icosphere:2", sphere.truth, options);
    EXPECT_EQ(m.inconsistentCornerRate, 0.0) << name;
    ASSERT_TRUE(m.vertexNormalErrorConsistentDeg && m.vertexNormalFlipRateConsistent) << name;
    EXPECT_EQ(*m.vertexNormalErrorConsistentDeg, m.vertexNormalErrorDeg) << name;
    EXPECT_EQ(*m.vertexNormalFlipRateConsistent, m.vertexNormalFlipRate) << name;
    EXPECT_EQ(m.fallbackRate, 0.0) << name;
  }
}

TEST(Metrics, OneFlippedVertexNormalGivesKInconsistentCornersOf3T) {
  TriangleMesh mesh = makeBuiltin("icosphere", ShapeParams{2}).mesh;
  const uint32_t flipped = mesh.normalIndices[7][1];
  mesh.normals[flipped] = -mesh.normals[flipped];
  size_t k = 0;
  for (const Tri& tri : mesh.normalIndices)
    for (uint32_t i : tri) k += i == flipped;
  const auto shared = std::make_shared<const TriangleMesh>(std::move(mesh));
  const double expected = double(k) / double(3 * shared->triangleCount());
  AnalysisOptions options;
  options.crack.lines = 500;
  for (const std::string& name : modelNames()) {
    const ModelMetrics m = analyzeNamedModel(name, shared, "flipped", std::nullopt, options);
    EXPECT_EQ(m.inconsistentCornerRate, expected) << name;
    EXPECT_EQ(toJson(m).at("inconsistent_corner_rate").get<double>(), expected) << name;
    ASSERT_TRUE(m.vertexNormalErrorConsistentDeg && m.vertexNormalFlipRateConsistent) << name;
    EXPECT_LE(*m.vertexNormalErrorConsistentDeg, m.vertexNormalErrorDeg) << name;
  }
  // The facets keep facing outwards: they fold at the k inconsistent corners and nowhere else.
  const ModelMetrics flat = analyzeNamedModel("flat", shared, "flipped", std::nullopt, options);
  EXPECT_EQ(flat.vertexNormalFlipRate, expected);
  EXPECT_EQ(*flat.vertexNormalFlipRateConsistent, 0.0);
  EXPECT_GT(flat.vertexNormalErrorDeg, 90.0);
  EXPECT_LT(*flat.vertexNormalErrorConsistentDeg, 90.0);
}

}  // namespace
}  // namespace quadtri
