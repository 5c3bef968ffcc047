// quadric-g1: exact corners, no folds at consistent corners, G1 across smooth edges and C0 across
// creases, on data sampled from random smooth surfaces at random rotations and scales.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "quadtri/analysis/metrics.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/g1_model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {
namespace {

// A grid of (nx+1)(ny+1) points over [−1, 1]² (interior points jittered by `jitter` of a cell)
// mapped by f, with normals from `normal`, each cell cut into two triangles.
template <class F, class N>
std::shared_ptr<TriangleMesh> gridMesh(int nx, int ny, double jitter, std::mt19937_64& rng, F f,
                                       N normal) {
  auto m = std::make_shared<TriangleMesh>();
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double x = -1.0 + 2.0 * i / nx, y = -1.0 + 2.0 * j / ny;
      if (i > 0 && i < nx && j > 0 && j < ny) {
        x += jitter * uni(rng) / nx;
        y += jitter * uni(rng) / ny;
      }
      m->positions.push_back(f(x, y));
      m->normals.push_back(normal(x, y));
    }
  auto id = [&](int i, int j) { return uint32_t(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m->triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m->triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m->normalIndices = m->triangles;
  return m;
}

// A rotation from four normal deviates (uniform over rotations).
Mat3 randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

// mesh moved by x → s R x + shift (normals rotated).
std::shared_ptr<const TriangleMesh> moved(const TriangleMesh& mesh, const Mat3& R, double s,
                                          const Vec3& shift) {
  auto out = std::make_shared<TriangleMesh>(mesh);
  for (Vec3& p : out->positions) p = s * (R * p) + shift;
  for (Vec3& n : out->normals) n = (R * n).normalized();
  return out;
}

// Random smooth surfaces: ellipsoids with random semi-axes, tori, saddles and wavy sheets on
// jittered and sliver grids, and the irregular marching-tetrahedra genus-2 surface.
std::vector<std::pair<std::string, std::shared_ptr<TriangleMesh>>> randomSurfaces(
    std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<std::pair<std::string, std::shared_ptr<TriangleMesh>>> out;
  ShapeParams ellipsoid;
  ellipsoid.level = 2;
  ellipsoid.radii = Vec3(0.3 + uni(rng), 0.3 + uni(rng), 0.3 + uni(rng));
  out.emplace_back("ellipsoid",
                   std::make_shared<TriangleMesh>(makeBuiltin("ellipsoid", ellipsoid).mesh));
  ShapeParams torus;
  torus.segments = 24;
  torus.rings = 12;
  torus.minor = 0.2 + 0.4 * uni(rng);
  out.emplace_back("torus", std::make_shared<TriangleMesh>(makeBuiltin("torus", torus).mesh));
  const double a = 0.2 + uni(rng), b = 0.2 + uni(rng);
  auto saddle = [&](double x, double y) { return Vec3(x, y, a * x * x - b * y * y); };
  auto saddleNormal = [&](double x, double y) {
    return Vec3(-2 * a * x, 2 * b * y, 1.0).normalized();
  };
  out.emplace_back("saddle", gridMesh(8, 8, 0.6, rng, saddle, saddleNormal));
  // Slivers: cells 12 times wider than tall, jittered.
  out.emplace_back("saddle-slivers", gridMesh(3, 36, 0.5, rng, saddle, saddleNormal));
  const double w = 1.0 + 2.0 * uni(rng);
  auto wave = [&](double x, double y) { return Vec3(x, y, 0.3 * std::sin(w * x) * std::cos(y)); };
  auto waveNormal = [&](double x, double y) {
    return Vec3(-0.3 * w * std::cos(w * x) * std::cos(y), 0.3 * std::sin(w * x) * std::sin(y), 1.0)
        .normalized();
  };
  out.emplace_back("wave", gridMesh(10, 7, 0.7, rng, wave, waveNormal));
  ShapeParams genus2;
  genus2.cells = 14;
  out.emplace_back("genus2", std::make_shared<TriangleMesh>(makeBuiltin("genus2", genus2).mesh));
  return out;
}

TEST(G1Model, ExactCornersNoFoldsAndG1OnRandomSmoothSurfaces) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int round = 0; round < 3; ++round)
    for (const auto& [name, surface] : randomSurfaces(rng))
      for (double scale : {1e-6, 1.0, 1e6}) {
        const Mat3 R = randomRotation(rng);
        const Vec3 shift = 3.0 * scale * Vec3(uni(rng), uni(rng), uni(rng));
        const auto mesh = moved(*surface, R, scale, shift);
        const G1Model model(mesh);
        const std::string what = name + " at scale " + std::to_string(scale);
        EXPECT_EQ(model.fallbackCount(), 0u) << what;
        EXPECT_LT(vertexPositionError(model), 1e-9) << what;
        const CornerStats corners = checkedCornerStats(model);
        ASSERT_TRUE(corners.maxConsistentNormalErrorDeg) << what;
        EXPECT_GT(corners.consistent(), corners.corners * 9 / 10) << what;
        EXPECT_LT(*corners.maxConsistentNormalErrorDeg, 1e-6) << what;
        EXPECT_EQ(corners.consistentFlips, 0u) << what;
        const MeshTopology topology(*mesh);
        const auto c = edgeContinuity(model, topology);
        ASSERT_TRUE(c && c->c1AngleSmoothDeg && c->g1EdgeShare) << what;
        EXPECT_LT(c->c0Gap, 1e-9) << what;
        EXPECT_LT(*c->c1AngleSmoothDeg, kG1ToleranceDeg) << what;
        EXPECT_EQ(*c->g1EdgeShare, 1.0) << what;
      }
}

TEST(G1Model, PiecesJoinC1InsideTheirTriangle) {
  // Across the internal edges (corner → centroid) the pieces' normals agree: sampled on
  // random triangles with random normals, where nothing else is smooth.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::normal_distribution<double> g;
  for (int i = 0; i < 200; ++i) {
    std::array<Vec3, 3> p, n;
    for (int k = 0; k < 3; ++k) p[k] = Vec3(uni(rng), uni(rng), 0.2 * uni(rng));
    const Vec3 face = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    for (int k = 0; k < 3; ++k) n[k] = (face + 0.5 * Vec3(g(rng), g(rng), g(rng))).normalized();
    const auto pieces = g1Pieces(p, n, nullptr);
    for (int k = 0; k < 3; ++k) {
      const BezierTriangle &a = pieces[size_t(k)], &b = pieces[size_t((k + 2) % 3)];
      // Piece k's edge (corner 0 → corner 2) is piece k−1's edge (corner 1 → corner 2).
      for (double s : {0.1, 0.3, 0.5, 0.7, 0.9}) {
        const Vec3 pa = a.position(0.0, s), pb = b.position(1.0 - s, s);
        EXPECT_LE((pa - pb).norm(), 1e-12);
        const Vec3 na = a.normal(0.0, s), nb = b.normal(1.0 - s, s);
        if (na.squaredNorm() > 0 && nb.squaredNorm() > 0) {
          EXPECT_LT(angleDegrees(na, nb), 1e-6);
        }
      }
    }
  }
}

TEST(G1Model, SplitNormalsStayWatertightAndSmoothEdgesStayG1) {
  for (const char* spec : {"cube", "cylinder:24,4"}) {
    const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh);
    const G1Model model(mesh);
    const MeshTopology topology(*mesh);
    const auto c = edgeContinuity(model, topology);
    ASSERT_TRUE(c) << spec;
    EXPECT_LT(c->c0Gap, 1e-9) << spec;
    if (c->c1AngleSmoothDeg) {
      EXPECT_LT(*c->c1AngleSmoothDeg, kG1ToleranceDeg) << spec;
    }
    const CornerStats corners = checkedCornerStats(model);
    ASSERT_TRUE(corners.maxConsistentNormalErrorDeg) << spec;
    EXPECT_LT(*corners.maxConsistentNormalErrorDeg, 1e-6) << spec;
    EXPECT_EQ(corners.consistentFlips, 0u) << spec;
  }
}

TEST(G1Model, FlatInputStaysFlat) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    std::array<Vec3, 3> p;
    for (Vec3& x : p) x = Vec3(uni(rng), uni(rng), uni(rng));
    const Vec3 face = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    for (const BezierTriangle& s : g1Pieces(p, {face, face, face}, nullptr))
      for (const Vec3& b : s.b) EXPECT_LE(std::abs((b - p[0]).dot(face)), 1e-12);
  }
}

TEST(G1Model, SimilarityTransformsCommuteWithConversion) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const auto base = std::make_shared<const TriangleMesh>(parseBuiltinSpec("icosphere:1")->mesh);
  const G1Model a(base);
  for (double scale : {1e-6, 1e3}) {
    const Mat3 R = randomRotation(rng);
    const Vec3 shift(scale, -2 * scale, 0.5 * scale);
    const G1Model b(moved(*base, R, scale, shift));
    for (size_t t = 0; t < base->triangleCount(); t += 7)
      for (int s = 0; s < 5; ++s) {
        const double u = uni(rng), v = uni(rng) * (1.0 - u);
        const SurfacePoint pa = a.evaluate(t, u, v), pb = b.evaluate(t, u, v);
        EXPECT_LE((scale * (R * pa.position) + shift - pb.position).norm(), 1e-12 * scale * 4);
        EXPECT_LE((R * pa.normal - pb.normal).norm(), 1e-9);
      }
  }
}

TEST(G1Model, ConvergesAtLeastCubicallyOnTheSphere) {
  // truth_distance on icospheres of 80 to 5120 triangles: halving the edge length divides the
  // error by 2^order.
  std::vector<double> errors;
  for (int level = 1; level <= 4; ++level) {
    const BuiltinMesh b = *parseBuiltinSpec("icosphere:" + std::to_string(level));
    const G1Model model(std::make_shared<const TriangleMesh>(b.mesh));
    errors.push_back(truthDistance(model, *b.truth, 6));
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log2(errors[i - 1] / errors[i]);
    EXPECT_GE(order, 3.0) << "levels " << i << " → " << i + 1 << ": " << errors[i - 1] << " → "
                          << errors[i];
  }
}

TEST(G1Model, TessellationIsWeldedWithTheModelsNormals) {
  const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec("icosphere:1")->mesh);
  const G1Model model(mesh);
  const int n = 4;
  const TriangleMesh out = tessellate(model, Tessellation{Tessellation::Kind::Lattice, n});
  const MeshTopology topology(*mesh);
  // Welded: each mesh vertex once, n − 1 points per edge, the interior points per patch.
  const size_t expected = mesh->positions.size() + topology.edges.size() * size_t(n - 1) +
                          mesh->triangleCount() * size_t((n - 1) * (n - 2) / 2);
  EXPECT_EQ(out.positions.size(), expected);
  // Every corner's normal is the model's normal there, which at mesh vertices is the vertex
  // normal.
  for (size_t t = 0; t < out.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = out.corner(t, k);
      const double r = p.norm();
      EXPECT_NEAR(r, 1.0, 0.02);
      EXPECT_LT(angleDegrees(out.cornerNormal(t, k), p), 5.0);
    }
  for (size_t v = 0; v < mesh->positions.size(); ++v) {
    bool found = false;
    for (size_t i = 0; i < out.positions.size() && !found; ++i)
      found = out.positions[i] == mesh->positions[v];
    EXPECT_TRUE(found) << "mesh vertex " << v << " is not a tessellation vertex";
  }
}

}  // namespace
}  // namespace quadtri
