#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "quadtri/analysis/heatmaps.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {
namespace {

// The exact unit sphere as the quadric of every patch: the implicit fields then measure only
// how far the thesis' parametric patch f_p strays from the sphere it samples.
class SphereQuadricModel final : public SurfaceModel {
 public:
  explicit SphereQuadricModel(std::shared_ptr<const TriangleMesh> mesh)
      : SurfaceModel(std::move(mesh)) {
    QuadricPatch p;
    p.q = {1, 1, 1, 0, 0, 0, 0, 0, 0, -1};
    patches_.assign(patchCount(), p);
  }
  std::string_view name() const override { return "sphere"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override {
    const Vec3 p =
        ((1 - u - v) * mesh().corner(t, 0) + u * mesh().corner(t, 1) + v * mesh().corner(t, 2))
            .normalized();
    return {p, p};
  }
  Representation representation() const override { return Representation::Implicit; }
  const std::vector<QuadricPatch>& renderPatches() const override { return patches_; }
  void patchRecord(size_t, PatchRecord&) const override {}

 private:
  std::vector<QuadricPatch> patches_;
};

class FlatFaces final : public SurfaceModel {
 public:
  using SurfaceModel::SurfaceModel;
  std::string_view name() const override { return "faces"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override {
    return {(1 - u - v) * mesh().corner(t, 0) + u * mesh().corner(t, 1) + v * mesh().corner(t, 2),
            mesh().faceNormal(t)};
  }
  void patchRecord(size_t, PatchRecord&) const override {}
};

TEST(Heatmaps, LayoutMapsPixelsBackToTheirPatch) {
  const PatchLayout layout(20);
  for (size_t t = 0; t < 20; ++t) {
    const Vec2 px = layout.pixel(t, 0.3, 0.4);
    const auto at = layout.patchAt(int(px.x()), int(px.y()));
    ASSERT_TRUE(at);
    EXPECT_EQ(std::get<0>(*at), t);
    const double pixelInUv = 2.0 / (0.88 * layout.cell);
    EXPECT_NEAR(std::get<1>(*at), 0.3, pixelInUv);
    EXPECT_NEAR(std::get<2>(*at), 0.4, pixelInUv);
  }
  EXPECT_FALSE(layout.patchAt(0, 0));
  // The teapot's 992 patches in 32 columns: 640 / 32 = 20-pixel cells, floored at 12.
  EXPECT_EQ(PatchLayout(992, 640).cell, 20);
  EXPECT_EQ(PatchLayout(992, 100).cell, 12);
  EXPECT_EQ(PatchLayout(20).cell, 200);
}

TEST(Heatmaps, NormalMapColoursEachFaceByItsNormalRange) {
  const auto mesh = std::make_shared<TriangleMesh>(makeBuiltin("icosahedron").mesh);
  FlatFaces model(mesh);
  const PatchLayout layout(model.patchCount());
  const Canvas canvas = drawNormalMap(layout, model, "faces");
  Vec3 lo = Vec3::Constant(kInfinity), hi = Vec3::Constant(-kInfinity);
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    lo = lo.cwiseMin(mesh->faceNormal(t));
    hi = hi.cwiseMax(mesh->faceNormal(t));
  }
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const Vec2 px = layout.pixel(t, 1.0 / 3, 1.0 / 3);
    const Rgb c = canvas.get(int(px.x()), int(px.y()));
    const Vec3 expected = (mesh->faceNormal(t) - lo).cwiseQuotient(hi - lo);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], expected[k], 1e-5) << "face " << t;
  }
}

TEST(Heatmaps, ImplicitFieldsVanishAtCornersOfTheSampledSphere) {
  const auto mesh = std::make_shared<TriangleMesh>(makeBuiltin("icosahedron").mesh);
  SphereQuadricModel model(mesh);
  const PatchField residual = implicitResidualField(model), misfit = normalMisfitField(model);
  for (size_t t = 0; t < model.patchCount(); ++t) {
    for (auto [u, v] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}) {
      EXPECT_NEAR(*residual(t, u, v), 0.0, 1e-12);
      EXPECT_NEAR(*misfit(t, u, v), 0.0, 1e-12);
    }
    // Inside the patch the quadratic patch leaves the sphere, and by the same amount on every
    // face of a regular icosahedron.
    EXPECT_GT(std::abs(*residual(t, 1.0 / 3, 1.0 / 3)), 1e-3);
    EXPECT_NEAR(*residual(t, 1.0 / 3, 1.0 / 3), *residual(0, 1.0 / 3, 1.0 / 3), 1e-12);
  }
  EXPECT_FALSE(implicitResidualField(FlatFaces(mesh)));
}

TEST(Heatmaps, HeatmapSpansTheColourMapOverTheFieldRange) {
  const PatchLayout layout(4);
  const Canvas canvas = drawHeatmap(
      layout, [](size_t, double u, double) { return u; }, "u");
  const Vec2 lowPx = layout.pixel(2, 0.02, 0.02), highPx = layout.pixel(2, 0.96, 0.02);
  const Rgb low = canvas.get(int(lowPx.x()), int(lowPx.y())),
            high = canvas.get(int(highPx.x()), int(highPx.y()));
  // The drawn range is [min u, max u] over pixel centres, within a pixel of [0, 1].
  const Rgb v0 = viridis(0.02), v1 = viridis(0.96);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(low[k], v0[k], 0.03);
    EXPECT_NEAR(high[k], v1[k], 0.03);
  }
}

TEST(Heatmaps, WritesOneImagePerFieldTheModelHas) {
  const auto dir = std::filesystem::temp_directory_path() / "quadtri-heatmaps-test";
  std::filesystem::remove_all(dir);
  const auto mesh = std::make_shared<TriangleMesh>(makeBuiltin("tetrahedron").mesh);
  EXPECT_EQ(writeHeatmaps(FlatFaces(mesh), dir, "tetrahedron").size(), 1u);
  const auto files = writeHeatmaps(SphereQuadricModel(mesh), dir, "tetrahedron");
  ASSERT_EQ(files.size(), 3u);
  for (const auto& f : files) EXPECT_GT(std::filesystem::file_size(f), 1000u) << f;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace quadtri
