// quadric-edges reproduces its edge curves on the boundary; quadric-edges-eq42 (the thesis'
// eq. 4.2 as printed) does not, and cracks.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/edges_model.h"
#include "surface_fixtures.h"

namespace quadtri {
namespace {

std::shared_ptr<const TriangleMesh> builtin(const char* spec) {
  return std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh);
}

TEST(EdgesModel, TransfiniteBoundaryIsTheEdgeCurve) {
  std::mt19937_64 rng(17);
  for (int i = 0; i < 200; ++i) {
    const auto mesh = test::triangleMesh(test::randomTriangle(rng));
    const EdgesModel model(mesh, EdgesModel::Blend::Transfinite);
    const QuadraticPatch p = model.edges(0);
    for (int k = 0; k < 3; ++k)
      for (double s = 0.0; s <= 1.0; s += 0.125) {
        const Vec2 uv = test::edgeUv(k, s);
        EXPECT_LE((model.evaluate(0, uv.x(), uv.y()).position - p.edgePoint(k, s)).norm(),
                  1e-14 * 4.0);
      }
  }
}

TEST(EdgesModel, Eq42BoundaryIsTheChordPlusAnotherEdgesBulge) {
  // As derived in edges_model.h: edge k carries the bulge 2s(1-s)(b − m) of edge k+2.
  std::mt19937_64 rng(19);
  for (int i = 0; i < 200; ++i) {
    const auto mesh = test::triangleMesh(test::randomTriangle(rng));
    const EdgesModel model(mesh, EdgesModel::Blend::ThesisEq42);
    const QuadraticPatch p = model.edges(0);
    for (int k = 0; k < 3; ++k) {
      const int other = (k + 2) % 3;
      const Vec3 bulge = p.b[other] - 0.5 * (p.v[other] + p.v[(other + 1) % 3]);
      for (double s = 0.0; s <= 1.0; s += 0.125) {
        const Vec2 uv = test::edgeUv(k, s);
        const Vec3 expected = (1 - s) * p.v[k] + s * p.v[(k + 1) % 3] + 2 * s * (1 - s) * bulge;
        EXPECT_LE((model.evaluate(0, uv.x(), uv.y()).position - expected).norm(), 1e-14 * 8.0);
      }
    }
  }
}

// Over every face boundary, divided by the edge length: the largest distance between the
// model's boundary point and the edge curve's point at the same parameter (`sameParameter`),
// and the largest distance from a boundary point to the nearest point of the curve (`nearest`).
struct BoundaryMiss {
  double sameParameter = 0.0, nearest = 0.0;
};

BoundaryMiss boundaryMiss(const EdgesModel& model) {
  BoundaryMiss miss;
  for (size_t t = 0; t < model.patchCount(); ++t) {
    const QuadraticPatch p = model.edges(t);
    for (int k = 0; k < 3; ++k) {
      const double len = (p.v[(k + 1) % 3] - p.v[k]).norm();
      for (int i = 0; i <= 32; ++i) {
        const double s = i / 32.0;
        const Vec2 uv = test::edgeUv(k, s);
        const Vec3 q = model.evaluate(t, uv.x(), uv.y()).position;
        // Coarse search over the curve, then a fine one around the best coarse sample.
        double best = 0.0, nearest = kInfinity;
        for (int c = 0; c <= 256; ++c) {
          const double dist = (q - p.edgePoint(k, c / 256.0)).norm();
          if (dist < nearest) nearest = dist, best = c / 256.0;
        }
        for (int c = -256; c <= 256; ++c)
          nearest = std::min(nearest,
                             (q - p.edgePoint(k, std::clamp(best + c / 65536.0, 0.0, 1.0))).norm());
        miss.sameParameter = std::max(miss.sameParameter, (q - p.edgePoint(k, s)).norm() / len);
        miss.nearest = std::max(miss.nearest, nearest / len);
      }
    }
  }
  return miss;
}

TEST(EdgesModel, Eq42MissesTheEdgeCurveOnTheIcosahedron) {
  // Unit icosahedron, radial normals: every bulge has length |d| = |m|(1/|m|² − 1) with |m| the
  // edge midpoint's radius, and two bulges of a face differ by |d|·(L/2)/|m|. At s = ½ the
  // boundary misses its curve by half that: (|d| L / (4|m|)) / L = 9.55% of the edge. The
  // difference is partly along the edge, so the distance to the nearest curve point is smaller:
  // 8.25%, the "8%" docs/DESIGN.md quotes.
  const auto mesh = builtin("icosahedron");
  const double L = (mesh->corner(0, 1) - mesh->corner(0, 0)).norm();
  const double m = std::sqrt(1.0 - 0.25 * L * L);
  const double expected = m * (1.0 / (m * m) - 1.0) / (4.0 * m);
  const BoundaryMiss eq42 = boundaryMiss(EdgesModel(mesh, EdgesModel::Blend::ThesisEq42));
  const BoundaryMiss transfinite = boundaryMiss(EdgesModel(mesh, EdgesModel::Blend::Transfinite));
  EXPECT_NEAR(eq42.sameParameter, expected, 1e-12);
  EXPECT_NEAR(eq42.sameParameter, 0.0955, 1e-4);
  EXPECT_NEAR(eq42.nearest, 0.0825, 0.0005);
  EXPECT_LE(transfinite.sameParameter, 1e-15);
}

TEST(EdgesModel, Eq42CornerNormalsMissTheShadingNormals) {
  // Its corner tangents follow other edges' bulges, so constraint (2) fails even on the
  // icosahedron (measured: 13.28°).
  const auto mesh = builtin("icosahedron");
  const EdgesModel model(mesh, EdgesModel::Blend::ThesisEq42);
  double worst = 0.0;
  for (size_t t = 0; t < mesh->triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec2 uv = test::cornerUv(k);
      worst = std::max(
          worst, angleDegrees(model.evaluate(t, uv.x(), uv.y()).normal, mesh->cornerNormal(t, k)));
    }
  EXPECT_NEAR(worst, 13.2825, 0.001);
}

TEST(EdgesModel, Eq42CracksAcrossSharedEdges) {
  // On the icosphere the bulges of a face's edges differ, so the two sides of an edge disagree.
  const auto mesh = builtin("icosphere:2");
  const MeshTopology topo(*mesh);
  for (auto blend : {EdgesModel::Blend::Transfinite, EdgesModel::Blend::ThesisEq42}) {
    const EdgesModel model(mesh, blend);
    double gap = 0.0;
    for (const Edge& e : topo.edges) {
      const auto [t0, k0] = e.sides[0];
      const auto [t1, k1] = e.sides[1];
      const Vec2 a = test::edgeUv(k0, 0.5), b = test::edgeUv(k1, 0.5);
      gap = std::max(gap, (model.evaluate(t0, a.x(), a.y()).position -
                           model.evaluate(t1, b.x(), b.y()).position)
                              .norm());
    }
    gap /= mesh->meanEdgeLength();
    if (blend == EdgesModel::Blend::Transfinite)
      EXPECT_LE(gap, 1e-14);
    else
      EXPECT_GT(gap, 1e-3);
    EXPECT_EQ(model.sharesEdges(), blend == EdgesModel::Blend::Transfinite);
  }
}

// quadric-edges is C0 to the bit: both triangles of an edge compute its points with the same
// bits (the weighted sum adds the edge's two corners in the order of their positions), on a
// smooth mesh and on one with jittered vertices and normals.
TEST(EdgesModel, TransfiniteNeighboursMeetToTheBit) {
  std::mt19937_64 rng(23);
  std::normal_distribution<double> g;
  TriangleMesh rough = parseBuiltinSpec("icosphere:2")->mesh;
  for (Vec3& p : rough.positions) p += 0.02 * Vec3(g(rng), g(rng), g(rng));
  for (Vec3& n : rough.normals) n = (n + 0.3 * Vec3(g(rng), g(rng), g(rng))).normalized();
  for (const auto& mesh : {builtin("icosphere:2"), std::make_shared<const TriangleMesh>(rough)}) {
    const MeshTopology topo(*mesh);
    const EdgesModel model(mesh, EdgesModel::Blend::Transfinite);
    size_t compared = 0;
    for (const Edge& e : topo.edges) {
      const auto [t0, k0] = e.sides[0];
      const auto [t1, k1] = e.sides[1];
      for (int i = 0; i <= 16; ++i) {
        // The sides run the edge in opposite directions: s on one is 1 − s on the other.
        const Vec2 a = test::edgeUv(k0, i / 16.0), b = test::edgeUv(k1, 1.0 - i / 16.0);
        const Vec3 pa = model.evaluate(t0, a.x(), a.y()).position;
        const Vec3 pb = model.evaluate(t1, b.x(), b.y()).position;
        ASSERT_EQ(pa, pb) << "edge " << e.a << "-" << e.b << " at " << i << "/16";
        Vec3 viaPositions;
        model.positions(t0, &a, 1, &viaPositions);
        ASSERT_EQ(viaPositions, pa);
        ++compared;
      }
    }
    EXPECT_EQ(compared, 17 * topo.edges.size());
  }
}

// Max |(|P| − 1)| over a lattice on every face: the unit sphere is the icosahedron's truth.
double maxRadialDeviation(const SurfaceModel& model) {
  double worst = 0.0;
  for (size_t t = 0; t < model.patchCount(); ++t)
    for (int i = 0; i <= 32; ++i)
      for (int j = 0; i + j <= 32; ++j)
        worst =
            std::max(worst, std::abs(model.evaluate(t, i / 32.0, j / 32.0).position.norm() - 1.0));
  return worst;
}

TEST(EdgesModel, TransfiniteBulgesOnTheIcosahedron) {
  // docs/DESIGN.md: 6.4% of the radius (the cubic blend overshoots the sphere).
  const EdgesModel model(builtin("icosahedron"), EdgesModel::Blend::Transfinite);
  EXPECT_NEAR(maxRadialDeviation(model), 0.064, 0.001);
}

TEST(EdgesModel, PatchJsonHoldsTheThesisEdgeCurves) {
  const auto mesh = builtin("icosphere:1");
  const EdgesModel model(mesh, EdgesModel::Blend::Transfinite);
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const nlohmann::json j = model.patchJson(t);
    const QuadraticPatch p = model.edges(t);
    // f_u runs along local edge 0 forwards, f_w along edge 1, f_v along edge 2 (eq. 4.3).
    const std::pair<const char*, int> curves[] = {{"f_u", 0}, {"f_w", 1}, {"f_v", 2}};
    for (const auto& [key, edge] : curves) {
      std::array<Vec3, 3> c;
      for (int m = 0; m < 3; ++m)
        c[m] = Vec3(j["edge_curves"][key][m][0], j["edge_curves"][key][m][1],
                    j["edge_curves"][key][m][2]);
      for (double s : {0.0, 0.3, 0.5, 1.0})
        EXPECT_LE((s * s * c[2] + s * c[1] + c[0] - p.edgePoint(edge, s)).norm(), 1e-15 * 8) << key;
    }
  }
}

}  // namespace
}  // namespace quadtri
