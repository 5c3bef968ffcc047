#include <gtest/gtest.h>

#include "quadtri/analysis/tessellation_view.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/shapes.h"

namespace quadtri {
namespace {

bool isBlack(const Rgb& c) {
  return c[0] == 0 && c[1] == 0 && c[2] == 0;
}

// Pixels of the object: everything that is not the white background (title band excluded).
int objectPixels(const Canvas& canvas, const OrthoView& view) {
  int count = 0;
  for (int y = view.top; y < canvas.height(); ++y)
    for (int x = 0; x < canvas.width(); ++x) {
      const Rgb c = canvas.get(x, y);
      count += !(c[0] == 1 && c[1] == 1 && c[2] == 1);
    }
  return count;
}

struct Fixture {
  std::shared_ptr<const TriangleMesh> mesh =
      std::make_shared<TriangleMesh>(makeBuiltin("tetrahedron").mesh);
  std::unique_ptr<SurfaceModel> model = makeModel("quadric-param", mesh);
  // Face 0 seen head-on, from outside: its centre is yellow (1, 1, 0), far from the black lines.
  OrthoView view{*mesh, mesh->faceNormal(0), 200};
};

TEST(TessellationView, CornersOnlyColoursTheFaceCentreByTheInterpolatedNormal) {
  Fixture f;
  const Tessellation corners{Tessellation::Kind::Lattice, 1};
  const Canvas canvas = drawTessellationView(*f.model, corners, f.view, "t");
  // Corners-only is the input mesh with its vertex normals (constraints 1 and 2): at the
  // centroid the normal is the normalised mean of the three, coloured by the range of all
  // vertex normals of the tetrahedron (components ±1/√3).
  Vec3 lo = Vec3::Constant(kInfinity), hi = Vec3::Constant(-kInfinity);
  for (size_t t = 0; t < 4; ++t)
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(f.mesh->cornerNormal(t, k));
      hi = hi.cwiseMax(f.mesh->cornerNormal(t, k));
    }
  const Vec3 n =
      (f.mesh->cornerNormal(0, 0) + f.mesh->cornerNormal(0, 1) + f.mesh->cornerNormal(0, 2))
          .normalized();
  const Vec3 expected = (n - lo).cwiseQuotient(hi - lo).cwiseMax(0.0).cwiseMin(1.0);
  const Vec3 centre =
      f.view.project((f.mesh->corner(0, 0) + f.mesh->corner(0, 1) + f.mesh->corner(0, 2)) / 3.0);
  const Rgb c = canvas.get(int(centre.x()), int(centre.y()));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], expected[k], 0.02) << k;
  // The sphere's normal at a tetrahedron's face centre is the face normal, -vertex/|vertex|,
  // (1, 1, -1)/√3 for face 0, whose colour is then (1, 1, 0).
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], k < 2 ? 1.0 : 0.0, 0.02) << k;
}

TEST(TessellationView, PatchBoundariesAreBlackAndPatchInteriorsAreNot) {
  Fixture f;
  for (const Tessellation& tessellation :
       {Tessellation{Tessellation::Kind::Lattice, 1}, Tessellation::thesis()}) {
    const Canvas canvas = drawTessellationView(*f.model, tessellation, f.view, "t");
    const bool flat = tessellation.kind == Tessellation::Kind::Lattice;
    // Where the surface lies at (u, v) of face 0: on the flat triangle for corners-only, on the
    // curved patch for the 2500-point grid.
    auto pixelAt = [&](double u, double v) {
      return f.view.project(flat ? (1 - u - v) * f.mesh->corner(0, 0) + u * f.mesh->corner(0, 1) +
                                       v * f.mesh->corner(0, 2)
                                 : f.model->evaluate(0, u, v).position);
    };
    auto at = [&](double u, double v) {
      const Vec3 px = pixelAt(u, v);
      return canvas.get(int(px.x()), int(px.y()));
    };
    // Face 0 faces the camera and its sides are the silhouette: a black line within a pixel
    // of each side's mid-point.
    for (auto [u, v] : {std::pair{0.5, 0.0}, {0.5, 0.5}, {0.0, 0.5}}) {
      const Vec3 px = pixelAt(u, v);
      bool black = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          black = black || isBlack(canvas.get(int(px.x()) + dx, int(px.y()) + dy));
      EXPECT_TRUE(black) << "side at (" << u << ", " << v << "), " << (flat ? "corners" : "2500");
    }
    // The triangles inside the patch draw no lines.
    EXPECT_FALSE(isBlack(at(1.0 / 3, 1.0 / 3)));
    EXPECT_FALSE(isBlack(at(0.25, 0.25)));
    EXPECT_FALSE(isBlack(at(0.5, 0.25)));
  }
}

TEST(TessellationView, TheDenseTessellationBulgesBeyondTheInputMesh) {
  Fixture f;
  const int corners = objectPixels(
      drawTessellationView(*f.model, Tessellation{Tessellation::Kind::Lattice, 1}, f.view, ""),
      f.view);
  const int dense =
      objectPixels(drawTessellationView(*f.model, Tessellation::thesis(), f.view, ""), f.view);
  // Seen along a face normal the tetrahedron's silhouette is that face's triangle (side
  // 2√2/√3 in a 200-pixel square for the diameter 2.1): about 0.433 · (0.776 · 200)² pixels.
  const double side = 2.0 * std::sqrt(2.0 / 3.0) * f.view.pixelsPerUnit;
  EXPECT_NEAR(corners, 0.25 * std::sqrt(3.0) * side * side, 0.04 * corners);
  EXPECT_GT(dense, 1.1 * corners);
}

TEST(TessellationView, WritesTheCornersOnlyAndThe2500PointViews) {
  Fixture f;
  const auto dir = std::filesystem::temp_directory_path() / "quadtri-views-test";
  std::filesystem::remove_all(dir);
  const auto files = writeTessellationViews(*f.model, dir, 64);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].filename(), "quadric-param-view-corners.png");
  EXPECT_EQ(files[1].filename(), "quadric-param-view-2500.png");
  for (const auto& file : files) EXPECT_GT(std::filesystem::file_size(file), 500u) << file;
  std::filesystem::remove_all(dir);
  EXPECT_THROW(OrthoView(TriangleMesh{}, Vec3(0, 0, 1)), Error);
}

}  // namespace
}  // namespace quadtri
