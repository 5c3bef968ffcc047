// Convergence to the true surface under refinement: truth_distance (docs/DESIGN.md §4) of every
// model on a sequence of ever finer meshes of one built-in shape, and the observed order.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "quadtri/io/canvas.h"
#include "quadtri/mesh/normals.h"

namespace quadtri {

/// The built-in shape specs of refinement levels 0..levels of `shape`, whose arguments fix the
/// shape but not its resolution: icosphere → icosphere:L (20·4^L triangles),
/// ellipsoid[:a,b,c] → ellipsoid:a,b,c,L, torus[:R,r] and uv-sphere → segments 8·2^L and
/// rings 4·2^L, genus2 → genus2:16·2^L cells. Throws Error for a shape that has no refinement
/// or for arguments that set the resolution.
std::vector<std::string> refinementSpecs(std::string_view shape, int levels);

/// truth_distance of one model on one refinement level.
struct ConvergenceSample {
  std::string shape, model;
  int level = 0;
  size_t triangles = 0;
  double meanEdgeLength = 0;
  std::optional<double> truthDistance;  ///< none when the model could not be measured
};

struct ConvergenceOptions {
  int levels = 5;       ///< refinement levels 0..levels
  int truthLevel = 12;  ///< lattice level of truthDistance
  /// > 0: a shape's refinement stops at the first level with more triangles than this.
  size_t maxTriangles = 0;
  NormalOptions normals;  ///< File: the shapes' analytic normals
  /// Called after each sample (progress); may be empty.
  std::function<void(const ConvergenceSample&)> onSample;
  /// Called when a model fails on a level (the sample is kept without a distance).
  std::function<void(const ConvergenceSample&, const std::string& error)> onError;
};

/// Measures every model on every refinement level of every shape, in that nesting order.
std::vector<ConvergenceSample> convergenceStudy(const std::vector<std::string>& shapes,
                                                const std::vector<std::string>& models,
                                                const ConvergenceOptions& options);

/// Least-squares line through (log x, log y): y ≈ e^intercept · x^slope.
struct PowerLawFit {
  double slope = 0, intercept = 0;
};

/// Fits a power law to at least two points with positive, finite x and y and two distinct x;
/// throws Error otherwise.
PowerLawFit fitPowerLaw(const std::vector<std::pair<double, double>>& points);

/// The observed order p of truth_distance ≈ C h^p in the mean edge length h, fitted over the
/// finest `fitLevels` levels of one model on one shape. Distances below `floor` (round-off:
/// a model exact on this shape) are left out; nullopt when fewer than two remain.
struct ConvergenceOrder {
  std::string shape, model;
  std::optional<double> order;
  int pointsFitted = 0;
  double finestDistance = 0;  ///< truth_distance on the finest measured level
};

std::vector<ConvergenceOrder> convergenceOrders(const std::vector<ConvergenceSample>& samples,
                                                int fitLevels = 3, double floor = 1e-10);

/// CSV of the samples: shape,level,model,triangles,mean_edge_length,truth_distance.
std::string convergenceCsv(const std::vector<ConvergenceSample>& samples);

/// CSV of the orders: shape,model,order,points_fitted,finest_truth_distance.
std::string ordersCsv(const std::vector<ConvergenceOrder>& orders);

/// Markdown table: one row per model, one column per shape, the order to two decimals
/// ("exact" when every distance is below the floor, "-" when nothing was measured).
std::string ordersMarkdown(const std::vector<ConvergenceOrder>& orders);

/// truth_distance against triangles on log–log axes: one colour per model, one marker per
/// shape; distances below `floor` are not drawn (a log axis cannot show them).
Canvas convergencePlot(const std::vector<ConvergenceSample>& samples, double floor = 1e-10);

}  // namespace quadtri
