#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "quadtri/analysis/crack_rate.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/robust_implicit_model.h"
#include "quadtri/surface/robust_quadric_fit.h"
#include "surface/robust_fixtures.h"

namespace quadtri {
namespace {

using namespace robust_test;

// An icosphere moved by a similarity transform, with the sphere it samples.
struct MovedSphere {
  std::shared_ptr<TriangleMesh> mesh;
  Vec3 centre;
  double radius;
};

MovedSphere movedIcosphere(int level, Rng& rng) {
  ShapeParams params;
  params.level = level;
  auto mesh = std::make_shared<TriangleMesh>(makeBuiltin("icosphere", params).mesh);
  const double scale = std::pow(10.0, uniform(rng, -6, 6));
  const Mat3 R = randomRotation(rng);
  const Vec3 shift = scale * uniform(rng, 0, 10) * randomUnit(rng);
  for (Vec3& p : mesh->positions) p = scale * R * p + shift;
  for (Vec3& n : mesh->normals) n = R * n;
  return {mesh, shift, scale};
}

TEST(RobustImplicitModel, IcospheresConvertToExactlyTheirSphere) {
  Rng rng(8);
  double worst = 0.0;
  for (int level = 0; level <= 3; ++level)
    for (int trial = 0; trial < 3; ++trial) {
      const MovedSphere s = movedIcosphere(level, rng);
      const RobustImplicitModel model(s.mesh);
      const QuadricCoeffs truth = sphere(s.centre, s.radius).coefficients;
      for (const QuadricPatch& p : model.quadricPatches())
        worst = std::max(worst, proportionalityError(p.q, truth));
    }
  // Exact up to rounding: each patch is a least-squares fit whose rounding is amplified by the
  // sphere's offset (up to 10 radii, so the constant term |c|² − r² is up to 100 times the
  // quadratic ones). Measured 4.6e-9 under clang -O1 with ASan, less under gcc -O3.
  EXPECT_LT(worst, 1e-8);
}

// A grid of (n+1)² vertices over [-1,1]² on z = x² − y², with the saddle's normals.
std::shared_ptr<TriangleMesh> saddleGrid(int n, double extent) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = extent * (2.0 * i / n - 1), y = extent * (2.0 * j / n - 1);
      mesh->positions.emplace_back(x, y, x * x - y * y);
      mesh->normals.push_back(Vec3(-2 * x, 2 * y, 1).normalized());
    }
  const auto id = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      mesh->triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh->triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  mesh->normalIndices = mesh->triangles;
  return mesh;
}

std::shared_ptr<TriangleMesh> builtin(const char* spec) {
  return std::make_shared<TriangleMesh>(parseBuiltinSpec(spec)->mesh);
}

double edgeScale(const TriangleMesh& m, size_t t) {
  return ((m.corner(t, 1) - m.corner(t, 0)).norm() + (m.corner(t, 2) - m.corner(t, 1)).norm() +
          (m.corner(t, 0) - m.corner(t, 2)).norm()) /
         3.0;
}

TEST(RobustImplicitModel, RaysAimedAtPatchPointsHitThem) {
  // Sheet selection: from outside, along the normal, the first hit of the whole model is the
  // point aimed at (near an edge the separator may hand it to the neighbour, which holds the
  // same point when the data come from a quadric).
  Rng rng(9);
  for (const auto& mesh :
       {builtin("icosphere:2"), builtin("torus:1,0.35,24,12"), saddleGrid(6, 1.0)}) {
    const RobustImplicitModel model(mesh);
    for (size_t t = 0; t < mesh->triangleCount(); ++t)
      for (int sample = 0; sample < 4; ++sample) {
        const double u = uniform(rng, 0.1, 0.8), v = uniform(rng, 0.1, 0.9 - u);
        const SurfacePoint sp = model.evaluate(t, u, v);
        const double h = edgeScale(*mesh, t);
        double nearest = kInfinity;
        for (const QuadricPatch& patch : model.quadricPatches()) {
          double hit = kInfinity;
          if (intersectQuadricPatch(patch, sp.position + 0.2 * h * sp.normal, -sp.normal, 0.0,
                                    kInfinity, hit))
            nearest = std::min(nearest, hit);
        }
        EXPECT_NEAR(nearest, 0.2 * h, 1e-9 * h) << "patch " << t << " of " << mesh->triangleCount();
      }
  }
}

// Rays from above a shared edge, counting the patches hit among the triangles around the edge
// (all that share a vertex with its two sides): exactly one where the model has no crack.
struct PartitionCount {
  size_t rays = 0, none = 0, several = 0;
};

// A ray from 0.3h above a random point of local edge ka of patch ta (edge parameter in
// [lo, hi]), aimed down its normal within ±0.3 rad: it crosses the surface near the edge.
std::pair<Vec3, Vec3> rayAcrossEdge(const RobustImplicitModel& model, uint32_t ta, int ka, double h,
                                    double lo, double hi, Rng& rng) {
  const Vec2 cornerUv[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  const Vec2 uv = cornerUv[ka] + uniform(rng, lo, hi) * (cornerUv[(ka + 1) % 3] - cornerUv[ka]);
  const SurfacePoint sp = model.evaluate(ta, uv.x(), uv.y());
  Vec3 s, t;
  orthonormalBasis(sp.normal, s, t);
  const Vec3 origin = sp.position + 0.3 * h * sp.normal + h * uniform(rng, -0.05, 0.05) * s +
                      h * uniform(rng, -0.05, 0.05) * t;
  const Vec3 dir =
      (-sp.normal + uniform(rng, -0.3, 0.3) * s + uniform(rng, -0.3, 0.3) * t).normalized();
  return {origin, dir};
}

PartitionCount crossSharedEdges(const RobustImplicitModel& model, int raysPerEdge, Rng& rng) {
  const TriangleMesh& m = model.mesh();
  const MeshTopology topo(m);
  std::vector<std::vector<uint32_t>> around(m.positions.size());
  for (uint32_t t = 0; t < m.triangleCount(); ++t)
    for (uint32_t v : m.triangles[t]) around[v].push_back(t);
  PartitionCount count;
  for (const Edge& edge : topo.edges) {
    if (edge.sides.size() != 2) continue;
    const auto [ta, ka] = edge.sides[0];
    std::vector<uint32_t> nearby;
    for (auto side : edge.sides)
      for (uint32_t v : m.triangles[side.first])
        nearby.insert(nearby.end(), around[v].begin(), around[v].end());
    std::sort(nearby.begin(), nearby.end());
    nearby.erase(std::unique(nearby.begin(), nearby.end()), nearby.end());
    const double h = edgeScale(m, ta);
    for (int r = 0; r < raysPerEdge; ++r) {
      const auto [origin, dir] = rayAcrossEdge(model, ta, ka, h, 0.2, 0.8, rng);
      // Every crossing within 0.6h: the surface is ~0.3h away and curves far less than that.
      int hits = 0;
      for (uint32_t n : nearby) {
        double hit = 0;
        hits += intersectQuadricPatch(model.quadricPatches()[n], origin, dir, 0.0, 0.6 * h, hit);
      }
      ++count.rays;
      count.none += hits == 0;
      count.several += hits > 1;
    }
  }
  return count;
}

TEST(RobustImplicitModel, NeighboursShareTheirEdgePlanesExactlyNegated) {
  const auto mesh = builtin("torus:1,0.35,24,12");
  const RobustImplicitModel model(mesh);
  const MeshTopology topo(*mesh);
  for (const Edge& edge : topo.edges) {
    ASSERT_EQ(edge.sides.size(), 2u);
    const auto [ta, ka] = edge.sides[0];
    const auto [tb, kb] = edge.sides[1];
    EXPECT_EQ(model.quadricPatches()[ta].planes[ka], Vec4(-model.quadricPatches()[tb].planes[kb]));
  }
}

TEST(RobustImplicitModel, SpherePatchesPartitionSpaceAlongEdges) {
  // Sphere data: one sphere, edge planes through its centre: no ray misses, none hits twice.
  Rng rng(10);
  const RobustImplicitModel model(builtin("icosphere:2"));
  const PartitionCount c = crossSharedEdges(model, 20, rng);
  EXPECT_EQ(c.none, 0u);
  EXPECT_EQ(c.several, 0u);
}

TEST(RobustImplicitModel, EllipsoidNeighboursMeetExactlyOnTheirSeparator) {
  // Data from a quadric other than a sphere: the fits differ by multiples of L², the
  // neighbours agree across edges and a − κb is a plane pair through each edge, one plane of
  // which separates them: both patches end on the same curve.
  Rng rng(13);
  const auto mesh = builtin("ellipsoid:1,0.7,0.5");
  const RobustImplicitModel model(mesh);
  const MeshTopology topo(*mesh);
  const Vec2 cornerUv[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  double worst = 0.0;
  for (const Edge& edge : topo.edges) {
    const auto [a, ka] = edge.sides[0];
    const auto [b, kb] = edge.sides[1];
    const bool sameWay = mesh->triangles[a][ka] == mesh->triangles[b][kb];
    for (double s : {0.25, 0.5, 0.75}) {
      const Vec2 ua = cornerUv[ka] + s * (cornerUv[(ka + 1) % 3] - cornerUv[ka]);
      const double sb = sameWay ? s : 1.0 - s;
      const Vec2 ub = cornerUv[kb] + sb * (cornerUv[(kb + 1) % 3] - cornerUv[kb]);
      worst = std::max(worst, (model.evaluate(a, ua.x(), ua.y()).position -
                               model.evaluate(b, ub.x(), ub.y()).position)
                                      .norm() /
                                  edgeScale(*mesh, a));
    }
  }
  EXPECT_LT(worst, 1e-12);
  const PartitionCount c = crossSharedEdges(model, 20, rng);
  EXPECT_EQ(c.none, 0u);
  EXPECT_EQ(c.several, 0u);
}

TEST(RobustImplicitModel, TorusNeighboursPartitionSpaceUpToASliver) {
  // Neighbouring quadrics of a torus meet each edge plane in slightly different conics; rays
  // through the sliver between them miss both patches or hit both (measured: 2 and 8 of
  // 69,120 rays aimed at the edges).
  Rng rng(11);
  const RobustImplicitModel model(builtin("torus:1,0.35,48,24"));
  const PartitionCount c = crossSharedEdges(model, 20, rng);
  RecordProperty("rays", int(c.rays));
  RecordProperty("none", int(c.none));
  RecordProperty("several", int(c.several));
  EXPECT_LT(double(c.none) / double(c.rays), 1e-3);
  EXPECT_LT(double(c.several) / double(c.rays), 1e-3);
}

// Every crossing of the ray segment with the patches and bridges of the model, as signed
// (entering: -1, leaving: +1) hits sorted along the ray.
std::vector<std::pair<double, int>> crossings(const RobustImplicitModel& model, const Vec3& o,
                                              const Vec3& d, double length) {
  const std::vector<QuadricPatch>& all = model.renderPatches();
  std::vector<std::pair<double, int>> out;
  for (size_t i = 0; i < all.size(); ++i) {
    double tmin = 0.0, t;
    while (intersectPrimitive(all, i, o, d, tmin, length, t)) {
      out.emplace_back(t, primitiveNormal(all, i, o + t * d).dot(d) < 0.0 ? -1 : 1);
      tmin = t;
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RobustImplicitModel, QuadricDataNeedsNoBridges) {
  for (const char* spec : {"icosphere:2", "ellipsoid:1,0.7,0.5"}) {
    const RobustImplicitModel model(builtin(spec));
    EXPECT_EQ(model.bridgeCount(), 0u) << spec;
    EXPECT_EQ(model.renderPatches().size(), model.quadricPatches().size()) << spec;
  }
}

TEST(RobustImplicitModel, BridgesJoinTheTwoSidesOfTheirEdge) {
  const auto mesh = builtin("torus:1,0.35,24,12");
  const RobustImplicitModel model(mesh);
  const MeshTopology topo(*mesh);
  // Generic data: most edges' sides miss each other by more than round-off.
  EXPECT_GT(model.bridgeCount(), topo.edges.size() / 2);
  EXPECT_LE(model.bridgeCount(), topo.edges.size());
  const auto& all = model.renderPatches();
  for (size_t i = model.quadricPatches().size(); i < all.size(); ++i) {
    const QuadricPatch& bridge = all[i];
    ASSERT_TRUE(bridge.isBridge());
    const auto a = size_t(bridge.joins[0]), b = size_t(bridge.joins[1]);
    // The two joined triangles share an edge, and the bridge's plane is theirs.
    int shared = 0;
    for (uint32_t va : mesh->triangles[a])
      for (uint32_t vb : mesh->triangles[b]) shared += va == vb;
    EXPECT_EQ(shared, 2) << i;
    const Vec4 plane(bridge.q[6], bridge.q[7], bridge.q[8], bridge.q[9]);
    bool found = false;
    for (int k = 0; k < 3; ++k) found |= all[a].planes[k] == plane;
    EXPECT_TRUE(found) << i;
  }
}

TEST(RobustImplicitModel, TorusRaysAcrossEdgesCrossPatchesAndBridgesOnce) {
  // The sliver of TorusNeighboursPartitionSpaceUpToASliver, closed: a ray from outside to
  // inside across an edge crosses the patches and bridges an odd number of times, and the
  // crossings alternate (enter, leave, enter...).
  Rng rng(11);
  const auto mesh = builtin("torus:1,0.35,24,12");
  const RobustImplicitModel model(mesh);
  const MeshTopology topo(*mesh);
  size_t rays = 0, odd = 0, alternating = 0;
  for (const Edge& edge : topo.edges) {
    const auto [ta, ka] = edge.sides[0];
    const double h = edgeScale(*mesh, ta);
    for (int r = 0; r < 8; ++r) {
      const auto [origin, dir] = rayAcrossEdge(model, ta, ka, h, 0.05, 0.95, rng);
      const auto hits = crossings(model, origin, dir, 0.6 * h);
      ++rays;
      odd += hits.size() % 2 == 1;
      bool alternate = !hits.empty() && hits.front().second == -1;
      for (size_t i = 1; i < hits.size(); ++i) alternate &= hits[i].second != hits[i - 1].second;
      alternating += alternate;
    }
  }
  EXPECT_EQ(odd, rays);
  EXPECT_EQ(alternating, rays);
}

TEST(RobustImplicitModel, TorusWithBridgesIsWatertight) {
  // Issue 5's target: crack_rate under 1e-5 on closed meshes. 100,000 lines (DESIGN §4).
  const auto mesh = builtin("torus:1,0.35,32,16");
  const RobustImplicitModel model(mesh);
  const ModelGeometry geometry = modelGeometry(model, Tessellation{});
  CrackRateOptions options;
  options.seed = 5;
  EXPECT_LT(crackRate(geometry, options), 1e-5);
}

TEST(RobustImplicitModel, CreaseKeepsEachSideAndSharesTheEdge) {
  // A roof: two faces folded at 90° along the x axis, each with its own face normal (split
  // normals at the shared vertices). Each side is its plane; the edge plane bisects the fold.
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -0.7, -0.7), Vec3(0.5, 0.7, -0.7)};
  mesh->triangles = {Tri{0, 2, 1}, Tri{0, 1, 3}};
  mesh->normals = {Vec3(0, -1, 1).normalized(), Vec3(0, 1, 1).normalized()};
  mesh->normalIndices = {Tri{0, 0, 0}, Tri{1, 1, 1}};
  const RobustImplicitModel model(mesh);
  const auto& patches = model.quadricPatches();
  for (size_t t = 0; t < 2; ++t) {
    const Vec3 n = mesh->normals[t];
    const QuadricCoeffs plane = {0, 0, 0, 0, 0, 0, n.x(), n.y(), n.z(), 0};
    EXPECT_LT(proportionalityError(patches[t].q, plane), 1e-12);
    EXPECT_LT(model.cornerNormalErrorDeg(t), 1e-9);
  }
  // Shared edge: local edge 2 of triangle 0 (corners 1→0) and edge 0 of triangle 1 (0→1).
  EXPECT_EQ(patches[0].planes[2], Vec4(-patches[1].planes[0]));
  EXPECT_LT(std::abs(patches[1].planes[0].head<3>().dot(Vec3(0, 1, 1).normalized() -
                                                        Vec3(0, -1, 1).normalized())) /
                std::sqrt(2.0),
            1.0);
  EXPECT_NEAR(std::abs(patches[1].planes[0].z()), 0.0, 1e-15);  // the bisector plane is y = 0
  for (double s : {0.1, 0.5, 0.9}) {
    const SurfacePoint a = model.evaluate(0, 0.0, 0.0);
    const SurfacePoint pa = model.evaluate(0, 0.0, s), pb = model.evaluate(1, s, 0.0);
    EXPECT_LT((pa.position - pb.position).norm(), 1e-12) << s;
    EXPECT_LT((a.position - mesh->positions[0]).norm(), 1e-15);
  }
  // Rays straight down onto the ridge, either side of it: exactly one face is hit.
  Rng rng(12);
  for (int r = 0; r < 1000; ++r) {
    const Vec3 origin(uniform(rng, 0.3, 0.7), uniform(rng, -0.05, 0.05), 1.0);
    double hit = 0;
    const bool a = intersectQuadricPatch(patches[0], origin, -Vec3::UnitZ(), 0.0, kInfinity, hit);
    const bool b = intersectQuadricPatch(patches[1], origin, -Vec3::UnitZ(), 0.0, kInfinity, hit);
    EXPECT_NE(a, b) << origin.transpose();
    EXPECT_EQ(a, origin.y() < 0) << origin.transpose();
  }
}

TEST(RobustImplicitModel, InconsistentNormalsStillCoverTheTriangle) {
  // Normals no quadric comes near (tilted up to ~65° at random): every line along the face
  // normal through the triangle still meets the patch's quadric, facing the normals' side.
  Rng rng(14);
  for (int trial = 0; trial < 200; ++trial) {
    auto mesh = std::make_shared<TriangleMesh>();
    for (int k = 0; k < 3; ++k)
      mesh->positions.emplace_back(uniform(rng, -1, 1), uniform(rng, -1, 1),
                                   uniform(rng, -0.2, 0.2));
    mesh->triangles = {Tri{0, 1, 2}};
    const Vec3 face = mesh->faceNormal(0);
    for (int k = 0; k < 3; ++k)
      mesh->normals.push_back((face + 0.9 * randomUnit(rng)).normalized());
    mesh->normalIndices = {Tri{0, 1, 2}};
    const RobustImplicitModel model(mesh);
    const QuadricPatch& patch = model.quadricPatches()[0];
    const QuadricCoeffs& q = patch.q;
    const Vec3 n = face * patch.orientation;
    const double a = q[0] * n.x() * n.x() + q[1] * n.y() * n.y() + q[2] * n.z() * n.z() +
                     q[3] * n.x() * n.y() + q[4] * n.x() * n.z() + q[5] * n.y() * n.z();
    for (double u : {0.2, 0.4, 0.6})
      for (double v : {0.2, 0.4 - 0.2 * (u > 0.5)}) {
        const Vec3 x =
            (1 - u - v) * mesh->positions[0] + u * mesh->positions[1] + v * mesh->positions[2];
        const double b = quadricGradient(q, x).dot(n), c = evalQuadric(q, x);
        EXPECT_GE(b * b - 4 * a * c, 0.0) << trial;
      }
  }
}

// A saddle whose normals are tilted at random by `amplitude` (folds, as around the teapot's
// knob); counts lines along face normals through the triangles that meet no patch or bridge.
struct FoldedSaddle {
  size_t flat = 0, blended = 0, lines = 0, missed = 0;
};

FoldedSaddle foldedSaddle(double amplitude, uint64_t seed) {
  Rng rng(seed);
  const auto mesh = saddleGrid(6, 1.0);
  for (Vec3& n : mesh->normals) n = (n + amplitude * randomUnit(rng)).normalized();
  for (Vec3& n : mesh->normals)
    if (n.z() < 0.05) n = (n + Vec3(0, 0, 0.2 - n.z())).normalized();
  const RobustImplicitModel model(mesh);
  FoldedSaddle out;
  out.flat = model.flatCount();
  out.blended = model.blendedCount();
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const Vec3 n = mesh->faceNormal(t);
    const double h = edgeScale(*mesh, t);
    for (int sample = 0; sample < 12; ++sample) {
      const double u = uniform(rng, 0.02, 0.96), v = uniform(rng, 0.02, 0.98 - u);
      const Vec3 x =
          (1 - u - v) * mesh->corner(t, 0) + u * mesh->corner(t, 1) + v * mesh->corner(t, 2);
      ++out.lines;
      out.missed += crossings(model, x - h * n, n, 2.0 * h).empty();
    }
    if (model.isFlat(t)) {  // the triangle's own plane
      const QuadricPatch& p = model.quadricPatches()[t];
      for (int k = 0; k < 3; ++k) EXPECT_LT(std::abs(evalQuadric(p.q, mesh->corner(t, k))), 1e-12);
      EXPECT_NEAR(quadricGradient(p.q, Vec3::Zero()).norm(), 1.0, 1e-12);
    }
  }
  return out;
}

TEST(RobustImplicitModel, FoldedNormalsLeaveFewHoles) {
  // Normals tilted at random by up to ~35° (amplitude 0.6) and ~80° (1.0) from a saddle's.
  // Where no member of the fit's pencil covers its triangle, the patch blends its normals
  // towards the face normal (and, where no blend passes either, becomes the triangle's plane).
  // Holes are rare but not gone: near an edge whose plane had to be turned
  // (keepAwayFromFaces), a line can leave the wedge before it meets the patch. Measured: 0, 1,
  // 2 of 864 lines at 0.6 and 1, 1, 3 at 1.0 (seeds 21-23), with 0, 0, 1 and 6, 3, 10 blended
  // patches and none flat (before the members q + μL², some of these patches were flat);
  // the smooth meshes' tests show none.
  size_t flat = 0, blended = 0, lines = 0, missed = 0;
  for (double amplitude : {0.6, 1.0})
    for (uint64_t seed : {21, 22, 23}) {
      const FoldedSaddle s = foldedSaddle(amplitude, seed);
      EXPECT_LT(double(s.missed) / double(s.lines), 0.012) << amplitude << " " << seed;
      flat += s.flat;
      blended += s.blended;
      lines += s.lines;
      missed += s.missed;
    }
  // Most patches that give up their normals keep a blend, not the plane (gcc's build: 20
  // blended, none flat; clang's sanitizer build rounds one of them to the plane).
  EXPECT_GT(blended, 0u);  // the holes are counted with patches that gave up their normals
  EXPECT_LT(flat, blended);
  EXPECT_LT(double(missed) / double(lines), 0.005);
}

TEST(RobustImplicitModel, SmoothMeshesNeedNoFlatFallback) {
  for (const char* spec : {"icosphere:2", "torus:1,0.35,24,12", "ellipsoid:1,0.7,0.5"})
    EXPECT_EQ(RobustImplicitModel(builtin(spec)).flatCount(), 0u) << spec;
}

TEST(QuadricPatch, NearestRootOfEitherSheetAndInsideByOrientation) {
  // z² − ε² = 0: two planes z = ±ε; the nearer one is hit from either side.
  const double eps = 0.1;
  QuadricPatch p;
  p.q = {0, 0, 1, 0, 0, 0, 0, 0, 0, -eps * eps};
  p.bounds.extend(Vec3(-1, -1, -1));
  p.bounds.extend(Vec3(1, 1, 1));
  double t = 0;
  ASSERT_TRUE(intersectQuadricPatch(p, Vec3(0, 0, -0.5), Vec3(0, 0, 1), 0.0, 1.0, t));
  EXPECT_NEAR(t, 0.5 - eps, 1e-15);
  ASSERT_TRUE(intersectQuadricPatch(p, Vec3(0, 0, 0.5), Vec3(0, 0, -1), 0.0, 1.0, t));
  EXPECT_NEAR(t, 0.5 - eps, 1e-15);
  // Past the box, no root counts.
  EXPECT_FALSE(intersectQuadricPatch(p, Vec3(2, 0, -0.5), Vec3(0, 0, 1), 0.0, 1.0, t));
  // Inside is where orientation·q < 0: between the planes, or outside them when turned over.
  for (double z : {-0.099, -0.05, 0.0, 0.05, 0.099})
    EXPECT_TRUE(insideQuadric(p, Vec3(0.3, -0.2, z))) << z;
  for (double z : {-0.5, -0.101, 0.101, 0.5})
    EXPECT_FALSE(insideQuadric(p, Vec3(0.3, -0.2, z))) << z;
  p.orientation = -1.0;
  EXPECT_FALSE(insideQuadric(p, Vec3(0.3, -0.2, 0.0)));
  EXPECT_TRUE(insideQuadric(p, Vec3(0.3, -0.2, 0.5)));
}

TEST(RobustImplicitModel, DegenerateTrianglesGiveFiniteOutput) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0),
                     Vec3(1e-13, 1e-13, 0)};
  mesh->triangles = {Tri{0, 1, 2}, Tri{0, 1, 3}, Tri{0, 0, 1}, Tri{0, 4, 3}};
  mesh->normals = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 0, -1)};
  mesh->normalIndices = {Tri{0, 1, 2}, Tri{0, 0, 0}, Tri{0, 1, 0}, Tri{0, 2, 1}};
  const RobustImplicitModel model(mesh);
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const QuadricPatch& p = model.quadricPatches()[t];
    for (double c : p.q) EXPECT_TRUE(std::isfinite(c)) << t;
    for (int i = 0; i < p.planeCount; ++i) EXPECT_TRUE(p.planes[i].allFinite()) << t;
    EXPECT_TRUE(allFinite(p.bounds.lo) && allFinite(p.bounds.hi)) << t;
    for (double u : {0.0, 0.3, 1.0}) {
      const SurfacePoint sp = model.evaluate(t, u, 0.5 * (1 - u));
      EXPECT_TRUE(allFinite(sp.position) && allFinite(sp.normal)) << t;
      EXPECT_NEAR(sp.normal.norm(), 1.0, 1e-12) << t;
    }
  }
}

TEST(RobustImplicitModel, IsRegisteredAndDescribesItsPatches) {
  auto mesh = std::make_shared<TriangleMesh>(makeBuiltin("icosahedron").mesh);
  const auto model = makeModel("quadric-implicit-robust", mesh);
  EXPECT_EQ(model->representation(), Representation::Implicit);
  ASSERT_EQ(model->quadricPatches().size(), mesh->triangleCount());
  const nlohmann::json j = model->patchJson(0);
  EXPECT_EQ(j["quadric"].size(), 10u);
  EXPECT_EQ(j["planes"].size(), 5u);
  EXPECT_EQ(j["orientation"].get<double>(), 1.0);
}

}  // namespace
}  // namespace quadtri
