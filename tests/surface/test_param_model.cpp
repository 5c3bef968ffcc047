// quadric-param: the thesis' §4.2 parametric quadric triangle.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/param_model.h"
#include "surface_fixtures.h"

namespace quadtri {
namespace {

Vec3 jsonPoint(const nlohmann::json& j) {
  return Vec3(j[0], j[1], j[2]);
}

TEST(ParamModel, PatchJsonCoefficientsReproduceTheSurface) {
  // f(u,v) = u²c5 + v²c4 + uv c3 + u c2 + v c1 + c0 (eq. 4.6) from the JSON alone.
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const auto mesh = test::triangleMesh(test::randomTriangle(rng));
    const ParamModel model(mesh);
    const nlohmann::json j = model.patchJson(0);
    std::array<Vec3, 6> c;
    for (int k = 0; k < 6; ++k)
      c[k] = jsonPoint(j["coefficients"][std::string(1, 'c') + char('0' + k)]);
    const QuadraticPatch p = model.patch(0);
    EXPECT_EQ(jsonPoint(j["control_points"]["b01"]), p.b[0]);
    EXPECT_EQ(jsonPoint(j["control_points"]["b12"]), p.b[1]);
    EXPECT_EQ(jsonPoint(j["control_points"]["b20"]), p.b[2]);
    for (int s = 0; s < 10; ++s) {
      const double u = uni(rng), v = uni(rng) * (1.0 - u);
      const Vec3 f = u * u * c[5] + v * v * c[4] + u * v * c[3] + u * c[2] + v * c[1] + c[0];
      EXPECT_LE((f - model.evaluate(0, u, v).position).norm(), 1e-14 * 16);
    }
  }
}

TEST(ParamModel, StaysCloseToTheSphereOnTheIcosahedron) {
  // docs/DESIGN.md: radial deviation 1.3% of the radius on an icosahedron.
  const ParamModel model(std::make_shared<const TriangleMesh>(makeBuiltin("icosahedron").mesh));
  double worst = 0.0;
  for (size_t t = 0; t < model.patchCount(); ++t)
    for (int i = 0; i <= 32; ++i)
      for (int j = 0; i + j <= 32; ++j)
        worst =
            std::max(worst, std::abs(model.evaluate(t, i / 32.0, j / 32.0).position.norm() - 1.0));
  EXPECT_NEAR(worst, 0.013, 0.001);
}

TEST(ParamModel, DegenerateTriangleNormalFallsBackToTheCornerNormals) {
  // All corners coincide: p_u × p_v = 0 everywhere, so the normal is the mix of corner normals.
  const Vec3 n0(0, 0, 1), n1 = Vec3(1, 0, 1).normalized(), n2(0, 1, 0);
  const auto mesh =
      test::triangleMesh({{Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)}, {n0, n1, n2}});
  const ParamModel model(mesh);
  const SurfacePoint p = model.evaluate(0, 0.25, 0.5);
  EXPECT_EQ(p.position, Vec3(1, 1, 1));
  EXPECT_LE((p.normal - (0.25 * n0 + 0.25 * n1 + 0.5 * n2).normalized()).norm(), 1e-15);
}

}  // namespace
}  // namespace quadtri
