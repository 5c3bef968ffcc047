// The real-mesh corpus subset that CI runs (docs/REAL_MESHES.md): six closed, manifold meshes of
// CGAL's data set and npm's bunny, mechanical parts included, with the default crease-split
// normals. Needs the corpus (scripts/fetch-corpus.sh; .ci/run fetches it and sets
// QUADTRI_CORPUS); skipped when QUADTRI_CORPUS is unset.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "fixtures/tight_bounds.h"
#include "quadtri/analysis/metrics.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/implicit_model.h"
#include "quadtri/surface/robust_implicit_model.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

// Closed and manifold (data/corpus-manifest.csv), 446 to 3,674 triangles.
constexpr const char* kSubset[] = {"cgal/joint.off", "cgal/anchor.off", "cgal/pinion.off",
                                   "cgal/hand.off",  "cgal/eight.off",  "npm/bunny.obj"};

std::optional<fs::path> corpus() {
  const char* dir = std::getenv("QUADTRI_CORPUS");
  if (!dir || !*dir) return std::nullopt;
  return fs::path(dir);
}

class CorpusSubset : public ::testing::TestWithParam<const char*> {
 protected:
  std::shared_ptr<const TriangleMesh> load() {
    const std::optional<fs::path> root = corpus();
    if (!root) return nullptr;
    const fs::path file = *root / GetParam();
    if (!fs::exists(file)) ADD_FAILURE() << file << " is missing: run scripts/fetch-corpus.sh";
    return std::make_shared<const TriangleMesh>(loadMesh(file));
  }
};

// Every model whose geometry is welded is watertight on the subset: not one of 1,000,000
// random lines crosses it an odd number of times (crease-split normals included).
TEST_P(CorpusSubset, WeldedModelsDoNotCrackOnAMillionLines) {
  if (!corpus()) GTEST_SKIP() << "QUADTRI_CORPUS is not set";
  const auto mesh = load();
  ASSERT_TRUE(mesh);
  AnalysisOptions options;
  options.crack.lines = 1000000;
  for (const char* model :
       {"flat", "shading-offset", "quadric-edges", "quadric-param", "phong", "pn", "nagata"}) {
    const ModelMetrics m = analyzeNamedModel(model, mesh, GetParam(), std::nullopt, options);
    ASSERT_TRUE(m.crackRate.has_value()) << model << " on " << GetParam();
    EXPECT_EQ(*m.crackRate, 0.0) << model << " on " << GetParam();
  }
}

// The robust implicit model is closed by construction (edge bridges): not one of 1,000,000
// random lines cracks it on the subset, mechanical parts with creases included.
TEST_P(CorpusSubset, RobustImplicitModelDoesNotCrackOnAMillionLines) {
  if (!corpus()) GTEST_SKIP() << "QUADTRI_CORPUS is not set";
  const auto mesh = load();
  ASSERT_TRUE(mesh);
  AnalysisOptions options;
  options.crack.lines = 1000000;
  const ModelMetrics m =
      analyzeNamedModel("quadric-implicit-robust", mesh, GetParam(), std::nullopt, options);
  ASSERT_TRUE(m.crackRate.has_value()) << GetParam();
  EXPECT_EQ(*m.crackRate, 0.0) << GetParam();
}

// quadric-implicit's exact boxes on real meshes, whose slivers and nearly flat patches make thin
// and long cells and quadrics that double precision places roughly: every patch keeps every hit
// it has with its sampled box (no gain asked: a long or unclosed cell keeps the sampled box).
TEST_P(CorpusSubset, ImplicitModelsExactBoxesKeepEveryHit) {
  if (!corpus()) GTEST_SKIP() << "QUADTRI_CORPUS is not set";
  fixtures::expectExactBoxesChangeNoHit(load(), 0.0);
}

// PN's corner tangents are what both sides of its edges share, so it folds at no consistent
// corner and meets each one's normal exactly (crease-split normals included).
TEST_P(CorpusSubset, PnMeetsEveryConsistentCorner) {
  if (!corpus()) GTEST_SKIP() << "QUADTRI_CORPUS is not set";
  const auto mesh = load();
  ASSERT_TRUE(mesh);
  AnalysisOptions options;
  options.crack.lines = 1000;
  const ModelMetrics m = analyzeNamedModel("pn", mesh, GetParam(), std::nullopt, options);
  ASSERT_TRUE(m.vertexNormalFlipRateConsistent.has_value()) << GetParam();
  EXPECT_EQ(*m.vertexNormalFlipRateConsistent, 0.0) << GetParam();
  ASSERT_TRUE(m.vertexNormalErrorConsistentDeg.has_value()) << GetParam();
  EXPECT_LT(*m.vertexNormalErrorConsistentDeg, 1e-6) << GetParam();
}

// quadric-g1 holds the G1 model's targets on the subset, traced directly: exact positions,
// normals and no fold at every consistent corner, no fallback, no cracked line, C0 across every
// edge (creases included) and G1 across every smooth one. 200,000 lines here, to keep CI's
// time: the subdivision tracer costs 30 to 160 s per mesh at 1,000,000 lines on these cores.
// At 1,000,000 lines one line on `hand` (line 602001) counts as cracked: it passes within the
// merge distance of two of the three sheets that fold at vertex 590, where the sliver triangle
// 2125 makes a corner inconsistent (docs/REAL_MESHES.md).
TEST_P(CorpusSubset, G1ModelHoldsItsTargets) {
  if (!corpus()) GTEST_SKIP() << "QUADTRI_CORPUS is not set";
  const auto mesh = load();
  ASSERT_TRUE(mesh);
  AnalysisOptions options;
  options.crack.lines = 200000;
  const ModelMetrics m = analyzeNamedModel("quadric-g1", mesh, GetParam(), std::nullopt, options);
  EXPECT_LT(m.vertexPositionError, 1e-9) << GetParam();
  ASSERT_TRUE(m.vertexNormalFlipRateConsistent && m.vertexNormalErrorConsistentDeg) << GetParam();
  EXPECT_EQ(*m.vertexNormalFlipRateConsistent, 0.0) << GetParam();
  EXPECT_LT(*m.vertexNormalErrorConsistentDeg, 1e-6) << GetParam();
  EXPECT_EQ(m.fallbackRate, 0.0) << GetParam();
  ASSERT_TRUE(m.crackRate && m.c0Gap && m.c1AngleSmoothDeg) << GetParam();
  EXPECT_EQ(*m.crackRate, 0.0) << GetParam();
  EXPECT_LT(*m.c0Gap, 1e-9) << GetParam();
  EXPECT_LT(*m.c1AngleSmoothDeg, kG1ToleranceDeg) << GetParam();
}

// npm's teapot (992 triangles, no file normals: crease-split at 30°). Its rim is a ring of
// slivers along a crease, cone data that the fits meet to within 0.08°. Each sliver's sheet follows
// its own side's normals and so crosses the crease's edge plane (the two sides' arcs lie across
// it), where lines along the face normal near that edge meet the crease's bridge rather than the
// sheet: 12 rim patches fell back for the coverage check before it counted such lines (30 of 992
// patches, 3.0%; 17 after, 1.7%, under the 2% the organic meshes are held to).
TEST(CorpusTeapot, RimSliversAlongTheCreaseKeepTheirFits) {
  const std::optional<fs::path> root = corpus();
  if (!root) GTEST_SKIP() << "QUADTRI_CORPUS is not set";
  const fs::path file = *root / "npm/teapot.obj";
  ASSERT_TRUE(fs::exists(file)) << file << " is missing: run scripts/fetch-corpus.sh";
  const auto mesh = std::make_shared<const TriangleMesh>(loadMesh(file));
  ASSERT_EQ(mesh->triangleCount(), 992u);
  const RobustImplicitModel model(mesh);
  for (size_t t : {26, 27, 34, 35, 42, 43, 50, 51, 58, 59, 66, 67}) {
    EXPECT_FALSE(model.fellBack(t)) << t;
    EXPECT_LT(model.cornerNormalErrorDeg(t), 0.1) << t;
  }
  EXPECT_LT(double(model.fallbackCount()), 0.02 * double(mesh->triangleCount()));
}

INSTANTIATE_TEST_SUITE_P(Meshes, CorpusSubset, ::testing::ValuesIn(kSubset),
                         [](const ::testing::TestParamInfo<const char*>& param) {
                           std::string name = fs::path(param.param).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace quadtri
