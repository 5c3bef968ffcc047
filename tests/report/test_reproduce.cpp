// The reproduction's tables and targets on small, hand-made inputs with known cells.
#include <gtest/gtest.h>

#include <cmath>

#include "quadtri/math/error.h"
#include "quadtri/report/reproduce.h"

namespace quadtri::testing {
namespace {

FigureCell cell(const std::string& shape, const std::string& model, std::vector<double> times,
                size_t primitives = 20) {
  FigureCell c;
  c.shape = shape;
  c.model = model;
  c.renderTimes = std::move(times);
  c.renderSeconds = median(c.renderTimes);
  c.primitives = primitives;
  c.meanSamplesPerPixel = 32;
  return c;
}

ModelMetrics metrics(const std::string& model, const std::string& mesh, size_t primitives,
                     size_t bytes) {
  ModelMetrics m;
  m.model = model;
  m.mesh = mesh;
  m.triangles = 20;
  m.primitives = primitives;
  m.memoryBytes = bytes;
  return m;
}

TEST(ReproduceTables, MarkdownHasHeaderAlignmentAndRows) {
  MarkdownTable table{{"model", "a", "b"}, {{"x", "1", "2"}, {"y", "3"}}, true};
  EXPECT_EQ(toMarkdown(table), "| model | a | b |\n|---|---:|---:|\n| x | 1 | 2 |\n| y | 3 |  |\n");
  table.rightAligned = false;
  EXPECT_EQ(toMarkdown(table).substr(0, 31), "| model | a | b |\n|---|---|---|");
}

TEST(ReproduceTables, FigurePivotFormatsEachCellAndMarksMissingOnes) {
  const std::vector<FigureCell> cells = {cell("triangle", "shading", {0.2, 0.25, 0.3}),
                                         cell("triangle", "quadric-implicit", {0.5}),
                                         cell("teapot", "shading", {1.0})};
  const MarkdownTable t = figurePivot(
      cells, {"shading", "quadric-implicit"}, {"triangle", "teapot"},
      [](const FigureCell& c) { return c.renderSeconds; }, "{:.2f}");
  ASSERT_EQ(t.header, (std::vector<std::string>{"model", "triangle", "teapot"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"shading", "0.25", "1.00"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"quadric-implicit", "0.50", "-"}));
}

TEST(ReproduceTables, RatioTableIsTheMedianOfPerRoundRatiosWithTheirRange) {
  // Per-round ratios 2/1 = 2, 3/2 = 1.5, 3/1 = 3: median 2, range 1.5-3. The ratio of the
  // medians (3 / 1) would be 3, so the table takes the rounds side by side.
  const std::vector<FigureCell> cells = {cell("ico", "shading", {1, 2, 1}),
                                         cell("ico", "quadric-implicit", {2, 3, 3})};
  const MarkdownTable t = ratioTable(cells, {"shading", "quadric-implicit"}, {"ico"});
  ASSERT_EQ(t.rows.size(), 1u);  // the baseline has no row
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"quadric-implicit", "2.00 (1.50-3.00)"}));
  const RatioRange r = renderTimeRatioRange(cells[1], cells[0]);
  EXPECT_DOUBLE_EQ(r.median, renderTimeRatio(cells[1], cells[0]));
}

TEST(ReproduceTables, ScalingTableRowsFollowTheNumeratorsCells) {
  const std::vector<FigureCell> cells = {cell("icosphere-0", "shading", {1, 1}, 20),
                                         cell("icosphere-0", "quadric-param", {2, 2}, 1280),
                                         cell("icosphere-0", "quadric-implicit", {1.5, 1.1}, 20)};
  const MarkdownTable t = scalingTable(cells);
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"icosphere-0", "20", "1.000", "2.000", "1.300",
                                                 "1.30 (1.10-1.50)", "0.65 (0.55-0.75)"}));
}

TEST(ReproduceTables, MetricPivotTakesKeysFromTheMetricTable) {
  ModelMetrics a = metrics("shading", "icosphere:0", 20, 100);
  a.c0Gap = 0.0;
  ModelMetrics b = metrics("pn", "icosphere:0", 20, 100);
  b.c0Gap = 0.012345;
  ModelMetrics c = metrics("pn", "data/teapot.obj", 20, 100);  // no c0 gap: null
  const MarkdownTable t = metricPivot({a, b, c}, "c0_gap", "{:.2g}");
  EXPECT_EQ(t.header, (std::vector<std::string>{"model", "icosphere:0", "teapot"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"shading", "0", "-"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"pn", "0.012", "-"}));
  EXPECT_THROW(metricPivot({a}, "no_such_metric", "{}"), Error);
}

TEST(ReproduceTables, PrimitivesAndMetricsTables) {
  const std::vector<ModelMetrics> rows = {metrics("shading", "triangle", 1, 100),
                                          metrics("quadric-param", "triangle", 4802, 116429)};
  const MarkdownTable p = primitivesTable(rows, {"shading", "quadric-param"});
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"shading", "1 (0.1 KiB)"}));
  EXPECT_EQ(p.rows[1], (std::vector<std::string>{"quadric-param", "4802 (113.7 KiB)"}));
  const MarkdownTable m = metricsMarkdown(rows);
  // Every metric key but mesh and convert_seconds, in the key table's order.
  std::vector<std::string> keys;
  for (const std::string& k : metricKeys())
    if (k != "mesh" && k != "convert_seconds") keys.push_back(k);
  EXPECT_EQ(m.header, keys);
  EXPECT_EQ(m.rows[1][0], "quadric-param");
  EXPECT_EQ(m.rows[1][2], "4802");  // model, triangles, primitives
}

TEST(ReproduceTargets, AThresholdPassesJustInsideAndFailsJustPast) {
  EXPECT_TRUE(checkAtMost("t", 1.5, 1.5, "").pass);
  EXPECT_TRUE(checkAtMost("t", 1.4999, 1.5, "").pass);
  EXPECT_FALSE(checkAtMost("t", 1.5001, 1.5, "").pass);
  EXPECT_TRUE(checkAtLeast("t", 100.0, 100, "").pass);
  EXPECT_FALSE(checkAtLeast("t", 99.99, 100, "").pass);
  EXPECT_FALSE(checkAtMost("t", NAN, 1.5, "").pass);
}

TEST(ReproduceTargets, RenderRatioTargetFailsJustPastTheLimitAndNamesIt) {
  const std::vector<FigureCell> inside = {cell("ico", "shading", {1, 1, 1}),
                                          cell("ico", "quadric-implicit", {1.49, 1.49, 1.49})};
  const std::vector<FigureCell> past = {cell("ico", "shading", {1, 1, 1}),
                                        cell("ico", "quadric-implicit", {1.51, 1.51, 1.51})};
  const auto ok = renderRatioTargets(inside, {"ico"}, "a");
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_TRUE(ok[0].pass);
  EXPECT_TRUE(failLines(ok).empty());
  const auto missed = renderRatioTargets(past, {"ico", "teapot"}, "b");
  ASSERT_EQ(missed.size(), 2u);
  EXPECT_FALSE(missed[0].pass);
  EXPECT_FALSE(missed[1].pass);  // the teapot was not rendered
  const std::vector<std::string> lines = failLines(missed);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0],
            "FAIL: quadric-implicit / shading render time <= 1.5, setup (b), ico: measured 1.51 "
            "(1.51-1.51)");
}

TEST(ReproduceTargets, ScalingTargetsCompareTheLargeMeshWithTheFirst) {
  std::vector<FigureCell> cells = {cell("icosphere-0", "shading", {1}, 20),
                                   cell("icosphere-0", "quadric-implicit", {1.0}, 20),
                                   cell("icosphere-7", "shading", {1}, 327680),
                                   cell("icosphere-7", "quadric-implicit", {1.19}, 327680)};
  auto checks = scalingTargets(cells);
  ASSERT_EQ(checks.size(), 2u);
  EXPECT_TRUE(checks[0].pass) << checks[0].measured;  // 1.19 / 1.0 <= 1.2
  EXPECT_DOUBLE_EQ(checks[0].value, 1.19);
  EXPECT_TRUE(checks[1].pass);  // 1.19 <= 1.5
  cells[3].renderTimes = {1.21};
  checks = scalingTargets(cells);
  EXPECT_FALSE(checks[0].pass);
  // No mesh as large as the limit: a FAIL naming the largest count.
  checks = scalingTargets({cells[0], cells[1]});
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_FALSE(checks[0].pass);
  EXPECT_EQ(checks[0].measured, "largest icosphere has 20 patches");
}

TEST(ReproduceTargets, MemoryTargetIsTheParamOverImplicitBytes) {
  const auto pass = memoryTargets({metrics("quadric-param", "triangle", 4802, 10000),
                                   metrics("quadric-implicit", "triangle", 1, 100)});
  ASSERT_EQ(pass.size(), 1u);
  EXPECT_TRUE(pass[0].pass);  // exactly 100x
  const auto missed = memoryTargets({metrics("quadric-param", "triangle", 4802, 9999),
                                     metrics("quadric-implicit", "triangle", 1, 100)});
  EXPECT_FALSE(missed[0].pass);
  const MarkdownTable t = targetsTable(missed);
  EXPECT_EQ(t.rows[0][2], "FAIL");
}

TEST(ReproduceTables, MeshLabelIsAFilesStem) {
  EXPECT_EQ(meshLabel("data/teapot.obj"), "teapot");
  EXPECT_EQ(meshLabel("icosphere:3"), "icosphere:3");
  EXPECT_EQ(meshLabel("torus"), "torus");
}

}  // namespace
}  // namespace quadtri::testing
