// Invariants shared by the models built on the closed-form edge curves: quadric-param and
// quadric-edges (and quadric-edges-eq42 where it holds).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <random>
#include <string>

#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/implicit_model.h"
#include "quadtri/surface/model.h"
#include "surface_fixtures.h"

namespace quadtri {
namespace {

const char* const kSmoothModels[] = {"quadric-param", "quadric-edges"};
const char* const kAllCurvedModels[] = {"quadric-param", "quadric-edges", "quadric-edges-eq42"};

std::vector<std::shared_ptr<const TriangleMesh>> builtinMeshes() {
  std::vector<std::shared_ptr<const TriangleMesh>> out;
  for (const char* spec : {"tetrahedron", "icosahedron", "icosphere:2", "uv-sphere:12,6",
                           "ellipsoid", "torus:1,0.35,16,8"})
    out.push_back(std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh));
  return out;
}

std::vector<std::shared_ptr<const TriangleMesh>> randomTriangleMeshes(int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::shared_ptr<const TriangleMesh>> out;
  for (int i = 0; i < count; ++i) out.push_back(test::triangleMesh(test::randomTriangle(rng)));
  return out;
}

double longestEdge(const TriangleMesh& m, size_t t) {
  double len = 0.0;
  for (int k = 0; k < 3; ++k)
    len = std::max(len, (m.corner(t, (k + 1) % 3) - m.corner(t, k)).norm());
  return len;
}

TEST(SmoothModels, CornersInterpolateVerticesAndShadingNormalsOnBuiltinMeshes) {
  for (const auto& mesh : builtinMeshes())
    for (const char* name : kAllCurvedModels) {
      const bool normalsHold = std::string(name) != "quadric-edges-eq42";
      const auto model = makeModel(name, mesh);
      for (size_t t = 0; t < mesh->triangleCount(); ++t) {
        const double len = longestEdge(*mesh, t);
        for (int k = 0; k < 3; ++k) {
          const Vec2 uv = test::cornerUv(k);
          const SurfacePoint p = model->evaluate(t, uv.x(), uv.y());
          EXPECT_LE((p.position - mesh->corner(t, k)).norm(), 1e-9 * len) << name << " t" << t;
          if (normalsHold) {
            EXPECT_LE((p.normal - mesh->cornerNormal(t, k)).norm(), 1e-9) << name << " t" << t;
          }
        }
      }
    }
}

TEST(SmoothModels, CornersOfRandomTrianglesInterpolateVerticesAndShadingNormals) {
  // Independent random normals often ask for S-shaped edges; the closed form then clamps the
  // control point and gives up tangency on that edge, and where the data fold the patch over
  // the normal is the shading normal's opposite. The constraint (thesis: the corner normal is
  // proportional to the shading normal) is asserted at corners whose two edges are unclamped.
  std::mt19937_64 rng(7);
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const test::TriangleData d = test::randomTriangle(rng);
    const auto mesh = test::triangleMesh(d);
    const bool wellPosed = test::edgeSystemSigmaMin(d) > 1e-3;
    for (const char* name : kAllCurvedModels) {
      const bool normalsHold = std::string(name) != "quadric-edges-eq42";
      const auto model = makeModel(name, mesh);
      const double len = longestEdge(*mesh, 0);
      for (int k = 0; k < 3; ++k) {
        const Vec2 uv = test::cornerUv(k);
        const SurfacePoint p = model->evaluate(0, uv.x(), uv.y());
        EXPECT_LE((p.position - d.v[k]).norm(), 1e-9 * len) << name;
        if (normalsHold && wellPosed && test::edgeUnclamped(d, k) &&
            test::edgeUnclamped(d, (k + 2) % 3)) {
          EXPECT_LE(p.normal.cross(d.n[k]).norm(), 1e-9) << name << " triangle " << i;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 400);
}

TEST(SmoothModels, NormalIsTheNormalisedCrossOfFiniteDifferenceTangents) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uni(0.05, 0.9);
  const double h = 1e-6;
  for (const char* name : kAllCurvedModels)
    for (const auto& mesh : randomTriangleMeshes(100, 13)) {
      const auto model = makeModel(name, mesh);
      for (int s = 0; s < 10; ++s) {
        const double u = uni(rng), v = uni(rng) * (0.95 - u);
        const Vec3 pu =
            (model->evaluate(0, u + h, v).position - model->evaluate(0, u - h, v).position) /
            (2 * h);
        const Vec3 pv =
            (model->evaluate(0, u, v + h).position - model->evaluate(0, u, v - h).position) /
            (2 * h);
        const Vec3 expected = patchOrientation(*mesh, 0) * pu.cross(pv).normalized();
        const Vec3 n = model->evaluate(0, u, v).normal;
        EXPECT_NEAR(n.norm(), 1.0, 1e-14);
        EXPECT_LE((n - expected).norm(), 1e-6) << name << " at " << u << "," << v;
      }
    }
}

TEST(SmoothModels, FlatInputStaysFlat) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    test::TriangleData d = test::randomTriangle(rng);
    const Vec3 face = (d.v[1] - d.v[0]).cross(d.v[2] - d.v[0]).normalized();
    d.n = {face, face, face};
    const auto mesh = test::triangleMesh(d);
    const double len = longestEdge(*mesh, 0);
    for (int k = 0; k < 3; ++k) {
      const Vec3 b = edgeControlPoints(*mesh)[0][k];
      EXPECT_LE((b - 0.5 * (d.v[k] + d.v[(k + 1) % 3])).norm(), 1e-12 * len);
    }
    for (const char* name : kAllCurvedModels) {
      const auto model = makeModel(name, mesh);
      for (int s = 0; s < 20; ++s) {
        const double u = uni(rng), v = uni(rng) * (1.0 - u);
        const SurfacePoint p = model->evaluate(0, u, v);
        EXPECT_LE(std::abs((p.position - d.v[0]).dot(face)), 1e-12 * len) << name;
        EXPECT_LE((p.normal - face).norm(), 1e-12) << name;
      }
    }
  }
}

TEST(SmoothModels, SimilarityTransformsCommuteWithConversion) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
    for (int i = 0; i < 30; ++i) {
      const test::TriangleData d = test::randomTriangle(rng);
      const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
      const Mat3 R = q.toRotationMatrix();
      const Vec3 shift = scale * 10.0 * Vec3(uni(rng), uni(rng), uni(rng));
      test::TriangleData moved;
      for (int k = 0; k < 3; ++k) {
        moved.v[k] = scale * (R * d.v[k]) + shift;
        moved.n[k] = (R * d.n[k]).normalized();
      }
      const auto a = test::triangleMesh(d);
      const auto b = test::triangleMesh(moved);
      // Positions are compared relative to the transformed frame's size (|shift| ≈ 10·scale).
      const double tolerance = 1e-9 * scale * 10.0;
      for (const char* name : kAllCurvedModels) {
        const auto ma = makeModel(name, a);
        const auto mb = makeModel(name, b);
        for (int s = 0; s < 15; ++s) {
          const double u = 0.5 * (uni(rng) + 1.0), v = 0.5 * (uni(rng) + 1.0) * (1.0 - u);
          const SurfacePoint pa = ma->evaluate(0, u, v);
          const SurfacePoint pb = mb->evaluate(0, u, v);
          EXPECT_LE((scale * (R * pa.position) + shift - pb.position).norm(), tolerance)
              << name << " scale " << scale;
          EXPECT_LE((R * pa.normal - pb.normal).norm(), 1e-9) << name << " scale " << scale;
        }
      }
    }
  }
}

TEST(SmoothModels, SharedEdgesAreIdenticalFromBothSides) {
  for (const char* spec : {"icosphere:3", "torus:1,0.35,24,12"}) {
    const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh);
    const MeshTopology topo(*mesh);
    const auto control = edgeControlPoints(*mesh);
    const double size = mesh->bounds().diagonal().norm();
    for (const char* name : kSmoothModels) {
      const auto model = makeModel(name, mesh);
      for (const Edge& e : topo.edges) {
        ASSERT_EQ(e.sides.size(), 2u);
        const auto [t0, k0] = e.sides[0];
        const auto [t1, k1] = e.sides[1];
        // The closed form itself is symmetric bit for bit, not only through topology.
        const Vec3 forward =
            edgeControlPoint(mesh->corner(t0, k0), mesh->cornerNormal(t0, k0),
                             mesh->corner(t0, (k0 + 1) % 3), mesh->cornerNormal(t0, (k0 + 1) % 3));
        const Vec3 backward =
            edgeControlPoint(mesh->corner(t1, k1), mesh->cornerNormal(t1, k1),
                             mesh->corner(t1, (k1 + 1) % 3), mesh->cornerNormal(t1, (k1 + 1) % 3));
        EXPECT_TRUE(forward == backward && control[t0][k0] == control[t1][k1]) << spec;
        for (double s : {0.1, 0.25, 0.5, 0.8}) {
          const Vec2 a = test::edgeUv(k0, s), b = test::edgeUv(k1, 1.0 - s);
          const Vec3 pa = model->evaluate(t0, a.x(), a.y()).position;
          const Vec3 pb = model->evaluate(t1, b.x(), b.y()).position;
          EXPECT_LE((pa - pb).norm(), 1e-12 * size) << name << " " << spec;
        }
      }
    }
  }
}

// Triangles whose edge systems are singular or whose normals make no sense.
std::vector<test::TriangleData> degenerateTriangles() {
  const Vec3 z(0, 0, 1);
  const Vec3 tilted = Vec3(0.5, 0.0, std::sqrt(0.75));
  std::vector<test::TriangleData> out;
  // Zero area: collinear corners.
  out.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}, {z, z, Vec3(0, 1, 0)}});
  // Coincident corners.
  out.push_back({{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 1, 0)}, {z, tilted, z}});
  out.push_back({{Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3)}, {z, tilted, -z}});
  // Parallel normals, tilted away from the face normal (inconsistent tangent planes).
  out.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {tilted, tilted, tilted}});
  // Opposite normals.
  out.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {z, -z, z}});
  out.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {tilted, -tilted, Vec3(0, 1, 0)}});
  // Normals tangent to the edges.
  out.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                 {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0)}});
  out.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                 {Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(std::sqrt(0.5), -std::sqrt(0.5), 0)}});
  return out;
}

TEST(SmoothModels, DegenerateTrianglesStayFiniteAndBounded) {
  for (const test::TriangleData& d : degenerateTriangles()) {
    const auto mesh = test::triangleMesh(d);
    const auto control = edgeControlPoints(*mesh);
    for (int k = 0; k < 3; ++k) {
      const Vec3 &a = d.v[k], &b = d.v[(k + 1) % 3];
      ASSERT_TRUE(allFinite(control[0][k]));
      EXPECT_LE((control[0][k] - 0.5 * (a + b)).norm(), (b - a).norm() * (1.0 + 1e-12));
    }
    for (const char* name : kAllCurvedModels) {
      const auto model = makeModel(name, mesh);
      for (int i = 0; i <= 10; ++i)
        for (int j = 0; i + j <= 10; ++j) {
          const SurfacePoint p = model->evaluate(0, i / 10.0, j / 10.0);
          EXPECT_TRUE(allFinite(p.position)) << name;
          ASSERT_TRUE(allFinite(p.normal)) << name;
          EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12) << name;
        }
    }
  }
}

TEST(SmoothModels, EvaluateManyIsEvaluateBitForBit) {
  // Every model's batch evaluation gives what one call per point gives, on a smooth mesh and
  // on one that splits normals (the models that rebuild a patch per call build it once).
  const std::array<Vec2, 6> uv = {Vec2(0, 0),     Vec2(1, 0),     Vec2(0, 1),
                                  Vec2(0.2, 0.3), Vec2(0.5, 0.5), Vec2(1.0 / 3, 1.0 / 3)};
  for (const char* spec : {"icosphere:1", "cube"}) {
    const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh);
    for (const std::string& name : modelNames()) {
      const auto model = makeModel(name, mesh);
      for (size_t t = 0; t < mesh->triangleCount(); ++t) {
        std::array<SurfacePoint, 6> many;
        model->evaluateMany(t, uv.data(), uv.size(), many.data());
        for (size_t i = 0; i < uv.size(); ++i) {
          const SurfacePoint one = model->evaluate(t, uv[i].x(), uv[i].y());
          EXPECT_TRUE(many[i].position == one.position && many[i].normal == one.normal)
              << spec << " " << name << " patch " << t << " point " << i;
        }
      }
    }
  }
}

// An open 6×6 grid with noisy heights and one random normal per vertex (up to about 80° from
// +z, so that some edges' control points give up their tangent planes), a triangle with a
// repeated corner and a fin on one of its edges (a non-manifold edge).
std::shared_ptr<const TriangleMesh> roughOpenMesh() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> height(-0.3, 0.3), tilt(-4.0, 4.0);
  TriangleMesh mesh;
  const int n = 6;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) mesh.positions.push_back(Vec3(i, j, height(rng)));
  const auto at = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  mesh.triangles.push_back({at(0, 0), at(0, 0), at(1, 0)});
  mesh.positions.push_back(Vec3(2.5, 2.0, 1.0));
  mesh.triangles.push_back({at(2, 2), at(3, 2), uint32_t(mesh.positions.size() - 1)});
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    mesh.normals.push_back(Vec3(tilt(rng), tilt(rng), 1.0).normalized());
  mesh.normalIndices = mesh.triangles;
  return std::make_shared<const TriangleMesh>(std::move(mesh));
}

// Checks quadric-implicit's control points and fallbacks against edgeControlPoints on `mesh`,
// and localEdgeControlPoints too where they are local; returns the triangles that gave up.
size_t checkControlPoints(const std::shared_ptr<const TriangleMesh>& mesh,
                          const std::string& label) {
  std::vector<uint8_t> gaveUp;
  const std::vector<std::array<Vec3, 3>> shared = edgeControlPoints(*mesh, &gaveUp);
  const ImplicitModel implicit(mesh);
  const bool local = edgeControlPointsAreLocal(*mesh);
  size_t gaveUpCount = 0;
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    gaveUpCount += gaveUp[t] != 0;
    const QuadraticPatch fp = implicit.parametricPatch(t);
    for (size_t k = 0; k < 3; ++k) EXPECT_TRUE(fp.b[k] == shared[t][k]) << label << t << k;
    EXPECT_EQ(implicit.fellBack(t), gaveUp[t] != 0) << label << t;
    if (!local) continue;
    bool localGaveUp = true;
    const std::array<Vec3, 3> b = localEdgeControlPoints(*mesh, t, &localGaveUp);
    for (size_t k = 0; k < 3; ++k) EXPECT_TRUE(b[k] == shared[t][k]) << label << t << k;
    EXPECT_EQ(localGaveUp, gaveUp[t] != 0) << label << t;
  }
  return gaveUpCount;
}

TEST(SmoothModels, LocalEdgeControlPointsAreTheSharedOnesBitForBit) {
  // Where no vertex splits its normals, each triangle computes its edges' control points
  // alone: the same bits, and the same give-ups, as solving each mesh edge once. A mesh that
  // splits normals (cube) or has none (each side would use its own face normal) needs the
  // adjacency, and quadric-implicit keeps those it solved.
  struct Case {
    const char* spec;
    bool dropNormals, local;
  };
  for (const Case c : {Case{"icosphere:2", false, true}, Case{"torus:1,0.35,24,12", false, true},
                       Case{"ellipsoid:1,0.7,0.5", false, true}, Case{"cube", false, false},
                       Case{"icosphere:1", true, false}}) {
    TriangleMesh made = parseBuiltinSpec(c.spec)->mesh;
    if (c.dropNormals) made.normals.clear(), made.normalIndices.clear();
    const auto mesh = std::make_shared<const TriangleMesh>(std::move(made));
    ASSERT_EQ(edgeControlPointsAreLocal(*mesh), c.local) << c.spec;
    checkControlPoints(mesh, c.spec);
  }
  // Boundary edges, a non-manifold fin, a repeated corner and edges that give up.
  const auto rough = roughOpenMesh();
  ASSERT_TRUE(edgeControlPointsAreLocal(*rough));
  const size_t gaveUp = checkControlPoints(rough, "rough");
  EXPECT_GT(gaveUp, 0u);
  EXPECT_LT(gaveUp, rough->triangleCount());
}

}  // namespace
}  // namespace quadtri
