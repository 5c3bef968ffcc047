// What `quadtri convert` writes: the tessellated surface or the patch JSON, chosen by extension.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/convert_output.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/param_model.h"
#include "quadtri/surface/robust_implicit_model.h"

namespace quadtri {
namespace {

class ConvertOutput : public ::testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("quadtri-convert-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
       "-" + std::to_string(::getpid()));
  std::shared_ptr<const TriangleMesh> mesh =
      std::make_shared<const TriangleMesh>(makeBuiltin("icosahedron").mesh);
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(ConvertOutput, JsonHoldsEveryPatch) {
  const ParamModel model(mesh);
  const auto path = dir / "ico.json";
  EXPECT_EQ(writeConversion(model, Tessellation::thesis(), path), 0u);
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["model"], "quadric-param");
  EXPECT_EQ(j["triangles"], 20);
  EXPECT_EQ(j["tessellation"], "thesis");
  ASSERT_EQ(j["patches"].size(), 20u);
  for (size_t t = 0; t < 20; ++t) EXPECT_EQ(j["patches"][t], model.patchJson(t));
}

TEST_F(ConvertOutput, RobustJsonListsItsEdgeBridges) {
  const RobustImplicitModel model(
      std::make_shared<const TriangleMesh>(parseBuiltinSpec("torus:1,0.35,16,8")->mesh));
  ASSERT_GT(model.bridgeCount(), 0u);
  const nlohmann::json j = conversionJson(model, Tessellation{});
  ASSERT_EQ(j["patches"].size(), model.patchCount());
  ASSERT_EQ(j["bridges"].size(), model.bridgeCount());
  const auto& all = model.renderPatches();
  for (size_t i = 0; i < model.bridgeCount(); ++i) {
    const QuadricPatch& b = all[model.patchCount() + i];
    const nlohmann::json& jb = j["bridges"][i];
    EXPECT_EQ(jb["joins"][0].get<int>(), b.joins[0]);
    EXPECT_EQ(jb["joins"][1].get<int>(), b.joins[1]);
    EXPECT_EQ(jb["plane"][3].get<double>(), b.q[9]);
    EXPECT_EQ(jb["planes"].size(), size_t(b.planeCount));
    EXPECT_EQ(jb["bounds"]["max"][1].get<double>(), b.bounds.hi.y());
  }
}

TEST_F(ConvertOutput, EveryModelWritesThePatchCornersAsVertices) {
  for (const std::string& name : modelNames()) {
    const auto model = makeModel(name, mesh);
    const nlohmann::json j = conversionJson(*model, Tessellation{});
    ASSERT_EQ(j["patches"].size(), mesh->triangleCount()) << name;
    for (size_t t = 0; t < mesh->triangleCount(); ++t) {
      const nlohmann::json& v = j["patches"][t]["vertices"];
      ASSERT_EQ(v.size(), 3u) << name << " patch " << t;
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(v[k].size(), 3u) << name;
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(v[k][c].get<double>(), mesh->corner(t, k)[c]) << name << " patch " << t;
      }
    }
  }
}

TEST_F(ConvertOutput, RobustJsonWritesAnEmptyBridgesArrayOnASphere) {
  const RobustImplicitModel model(
      std::make_shared<const TriangleMesh>(makeBuiltin("icosphere").mesh));
  ASSERT_EQ(model.bridgeCount(), 0u);
  const nlohmann::json j = conversionJson(model, Tessellation{});
  ASSERT_TRUE(j.contains("bridges"));
  EXPECT_TRUE(j["bridges"].is_array());
  EXPECT_TRUE(j["bridges"].empty());
  // Only the robust model has bridges.
  EXPECT_FALSE(
      conversionJson(*makeModel("quadric-implicit", mesh), Tessellation{}).contains("bridges"));
}

TEST_F(ConvertOutput, MeshFilesHoldTheWeldedTessellation) {
  const auto model = makeModel("quadric-edges", mesh);
  // Extensions in any case, as the mesh readers and `quadtri mesh` take them.
  for (const char* ext : {".obj", ".ply", ".OBJ", ".Ply"}) {
    const auto path = dir / (std::string("ico") + ext);
    EXPECT_EQ(writeConversion(*model, Tessellation{Tessellation::Kind::Lattice, 3}, path), 20u * 9);
    const TriangleMesh back = loadMesh(path);
    EXPECT_EQ(back.triangleCount(), 20u * 9) << ext;
    // 12 vertices, 30 edges with 2 points each, 1 interior point per patch.
    EXPECT_EQ(back.positions.size(), 12u + 30u * 2 + 20u) << ext;
  }
}

TEST_F(ConvertOutput, PatchFilesTakeTheirExtensionInAnyCase) {
  const auto model = makeModel("quadric-param", mesh);
  const auto bytes = [](const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const auto& [upper, lower] : {std::pair{"ico.JSON", "ico.json"}, {"ico.Qtp", "ico.qtp"}}) {
    writeConversion(*model, Tessellation{}, dir / upper);
    writeConversion(*model, Tessellation{}, dir / lower);
    EXPECT_FALSE(bytes(dir / lower).empty()) << lower;
    EXPECT_EQ(bytes(dir / upper), bytes(dir / lower)) << upper;
  }
}

TEST_F(ConvertOutput, UnknownExtensionIsAnErrorAndWritesNothing) {
  const auto model = makeModel("quadric-param", mesh);
  const auto path = dir / "ico.stl";
  EXPECT_THROW(writeConversion(*model, Tessellation{}, path), Error);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace quadtri
