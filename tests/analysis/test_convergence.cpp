// Convergence study: the power-law fit, the refinement sequences, and the observed orders that
// approximation theory predicts for each model.
#include <gtest/gtest.h>

#include <cmath>

#include "quadtri/analysis/convergence.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

TEST(Convergence, FitRecoversASyntheticPowerLawExactly) {
  std::vector<std::pair<double, double>> points;
  for (double h : {0.5, 0.21, 0.1, 0.037}) points.emplace_back(h, 3.5 * std::pow(h, 2.7));
  const PowerLawFit fit = fitPowerLaw(points);
  EXPECT_NEAR(fit.slope, 2.7, 1e-12);
  EXPECT_NEAR(fit.intercept, std::log(3.5), 1e-12);
  EXPECT_THROW(fitPowerLaw({{0.1, 1.0}}), Error);
  EXPECT_THROW(fitPowerLaw({{0.1, 1.0}, {0.1, 2.0}}), Error);  // one x
  EXPECT_THROW(fitPowerLaw({{0.1, 1.0}, {0.2, 0.0}}), Error);  // log 0
}

TEST(Convergence, OrdersComeFromTheFinestLevelsAndSkipRoundOff) {
  // Level 0 is off the power law; the finest three follow d = 2 h³; model "exact" sits at
  // round-off.
  std::vector<ConvergenceSample> samples;
  const double h[] = {1.0, 0.5, 0.25, 0.125};
  for (int level = 0; level < 4; ++level) {
    const double d = level == 0 ? 0.9 : 2.0 * std::pow(h[level], 3);
    samples.push_back({"s", "cubic", level, size_t(20) << (2 * level), h[level], d});
    samples.push_back({"s", "exact", level, size_t(20) << (2 * level), h[level], 1e-13});
    samples.push_back({"s", "failed", level, size_t(20) << (2 * level), h[level], std::nullopt});
  }
  const std::vector<ConvergenceOrder> orders = convergenceOrders(samples, 3, 1e-10);
  ASSERT_EQ(orders.size(), 2u);
  EXPECT_EQ(orders[0].model, "cubic");
  ASSERT_TRUE(orders[0].order);
  EXPECT_NEAR(*orders[0].order, 3.0, 1e-12);
  EXPECT_EQ(orders[0].pointsFitted, 3);
  EXPECT_NEAR(orders[0].finestDistance, 2.0 * std::pow(0.125, 3), 1e-15);
  EXPECT_EQ(orders[1].model, "exact");
  EXPECT_FALSE(orders[1].order);
  EXPECT_EQ(ordersMarkdown(orders),
            "| model | s |\n|---|---:|\n| cubic | 3.00 |\n| exact | exact |\n");
  const std::string csv = convergenceCsv(samples);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "shape,level,model,triangles,mean_edge_length,truth_distance");
  EXPECT_NE(csv.find("\"s\",3,failed,1280,0.125,\n"), std::string::npos);  // no distance: empty
}

TEST(Convergence, RefinementSequencesOfEachShape) {
  EXPECT_EQ(refinementSpecs("icosphere", 2),
            (std::vector<std::string>{"icosphere:0", "icosphere:1", "icosphere:2"}));
  EXPECT_EQ(refinementSpecs("ellipsoid:1,0.7,0.5", 1),
            (std::vector<std::string>{"ellipsoid:1,0.7,0.5,0", "ellipsoid:1,0.7,0.5,1"}));
  EXPECT_EQ(refinementSpecs("torus:1,0.35", 1),
            (std::vector<std::string>{"torus:1,0.35,8,4", "torus:1,0.35,16,8"}));
  EXPECT_EQ(refinementSpecs("genus2", 1), (std::vector<std::string>{"genus2:16", "genus2:32"}));
  EXPECT_THROW(refinementSpecs("icosphere:3", 2), Error);  // the refinement sets the level
  EXPECT_THROW(refinementSpecs("torus:1,0.35,8,4", 2), Error);
  EXPECT_THROW(refinementSpecs("tetrahedron", 2), Error);
  EXPECT_THROW(refinementSpecs("icosphere", 9), Error);
}

// Observed orders, fitted over the three finest of levels 0..4. Straight triangles through the
// vertices are second order. A quadratic patch whose edge control points come from the true
// tangent planes is third order on a general surface; on a sphere, every point umbilic, the
// cubic error term cancels by symmetry and it is fourth order (a parabola through two points of
// a circle with the circle's tangents misses it by O(h⁴)).
class ObservedOrders : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ConvergenceOptions options;
    options.levels = 4;
    const auto samples =
        convergenceStudy({"icosphere", "torus:1,0.35"},
                         {"flat", "shading", "quadric-param", "nagata", "pn"}, options);
    orders_ = convergenceOrders(samples, 3);
  }
  static double order(const std::string& shape, const std::string& model) {
    for (const ConvergenceOrder& o : orders_)
      if (o.shape == shape && o.model == model && o.order) return *o.order;
    ADD_FAILURE() << model << " has no order on " << shape;
    return 0;
  }
  static inline std::vector<ConvergenceOrder> orders_;
};

TEST_F(ObservedOrders, FlatTrianglesAreSecondOrder) {
  for (const char* shape : {"icosphere", "torus:1,0.35"}) {
    EXPECT_NEAR(order(shape, "flat"), 2.0, 0.2) << shape;
    EXPECT_NEAR(order(shape, "shading"), 2.0, 0.2) << shape;
  }
}

TEST_F(ObservedOrders, TangentPlaneQuadraticsAreFourthOrderOnSpheresThirdOnATorus) {
  EXPECT_NEAR(order("icosphere", "quadric-param"), 4.0, 0.2);
  EXPECT_NEAR(order("icosphere", "nagata"), 4.0, 0.2);
  EXPECT_NEAR(order("torus:1,0.35", "quadric-param"), 3.0, 0.2);
  EXPECT_NEAR(order("torus:1,0.35", "nagata"), 3.0, 0.25);
}

TEST_F(ObservedOrders, PnTrianglesAreAtLeastThirdOrder) {
  EXPECT_NEAR(order("icosphere", "pn"), 4.0, 0.2);
  EXPECT_GE(order("torus:1,0.35", "pn"), 3.0);
}

}  // namespace
}  // namespace quadtri
