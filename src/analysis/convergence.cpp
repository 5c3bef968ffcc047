#include "quadtri/analysis/convergence.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "quadtri/analysis/metrics.h"
#include "quadtri/io/line_plot.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/model.h"

namespace quadtri {
namespace {

// Distinct values of `key` over `items`, in order of first appearance.
template <typename T, typename Key>
std::vector<std::string> distinct(const std::vector<T>& items, Key key) {
  std::vector<std::string> out;
  for (const T& item : items)
    if (std::find(out.begin(), out.end(), key(item)) == out.end()) out.push_back(key(item));
  return out;
}

}  // namespace

std::vector<std::string> refinementSpecs(std::string_view shape, int levels) {
  if (levels < 0 || levels > 8)
    fail("convergence: {} refinement levels is out of range: expected 0 to 8", levels);
  const size_t colon = shape.find(':');
  const std::string name(shape.substr(0, colon));
  const std::string args =
      colon == std::string_view::npos ? "" : std::string(shape.substr(colon + 1));
  const size_t numbers = args.empty() ? 0 : size_t(std::count(args.begin(), args.end(), ',')) + 1;
  auto expect = [&](size_t allowed, const char* what) {
    if (numbers != 0 && numbers != allowed)
      fail("convergence: shape '{}': expected {} (the refinement sets the resolution)", shape,
           what);
  };
  std::vector<std::string> specs;
  for (int level = 0; level <= levels; ++level) {
    const int grid = 1 << level;
    if (name == "icosphere") {
      expect(0, "no arguments");
      specs.push_back(fmt::format("icosphere:{}", level));
    } else if (name == "ellipsoid") {
      expect(3, "ellipsoid or ellipsoid:a,b,c");
      specs.push_back(fmt::format("ellipsoid:{},{}", args.empty() ? "1,0.7,0.5" : args, level));
    } else if (name == "torus") {
      expect(2, "torus or torus:R,r");
      specs.push_back(
          fmt::format("torus:{},{},{}", args.empty() ? "1,0.35" : args, 8 * grid, 4 * grid));
    } else if (name == "uv-sphere") {
      expect(0, "no arguments");
      specs.push_back(fmt::format("uv-sphere:{},{}", 8 * grid, 4 * grid));
    } else if (name == "genus2") {
      expect(0, "no arguments");
      specs.push_back(fmt::format("genus2:{}", 16 * grid));
    } else {
      fail(
          "convergence: shape '{}' has no refinement sequence: expected icosphere, ellipsoid, "
          "torus, uv-sphere or genus2",
          shape);
    }
  }
  return specs;
}

std::vector<ConvergenceSample> convergenceStudy(const std::vector<std::string>& shapes,
                                                const std::vector<std::string>& models,
                                                const ConvergenceOptions& options) {
  std::vector<std::vector<std::string>> specs;
  for (const std::string& shape : shapes) specs.push_back(refinementSpecs(shape, options.levels));
  std::vector<ConvergenceSample> samples;
  for (size_t s = 0; s < shapes.size(); ++s)
    for (int level = 0; level <= options.levels; ++level) {
      BuiltinMesh input = loadMeshSpec(specs[s][size_t(level)], options.normals);
      if (!input.truth) fail("convergence: '{}' has no true surface", specs[s][size_t(level)]);
      if (options.maxTriangles > 0 && input.mesh.triangleCount() > options.maxTriangles) break;
      const auto mesh = std::make_shared<const TriangleMesh>(std::move(input.mesh));
      for (const std::string& name : models) {
        ConvergenceSample sample{
            shapes[s], name, level, mesh->triangleCount(), mesh->meanEdgeLength(), std::nullopt};
        try {
          const std::unique_ptr<SurfaceModel> model = makeModel(name, mesh);
          sample.truthDistance = truthDistance(*model, *input.truth, options.truthLevel);
        } catch (const Error& e) {
          if (options.onError) options.onError(sample, e.what());
        }
        samples.push_back(sample);
        if (options.onSample) options.onSample(sample);
      }
    }
  return samples;
}

PowerLawFit fitPowerLaw(const std::vector<std::pair<double, double>>& points) {
  if (points.size() < 2) fail("power-law fit: expected at least 2 points, got {}", points.size());
  double mx = 0, my = 0;
  for (const auto& [x, y] : points) {
    if (!(x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y)))
      fail("power-law fit: point ({}, {}) is not positive and finite", x, y);
    mx += std::log(x);
    my += std::log(y);
  }
  mx /= double(points.size());
  my /= double(points.size());
  double sxx = 0, sxy = 0;
  for (const auto& [x, y] : points) {
    sxx += (std::log(x) - mx) * (std::log(x) - mx);
    sxy += (std::log(x) - mx) * (std::log(y) - my);
  }
  if (!(sxx > 0)) fail("power-law fit: every point has the same x = {}", points.front().first);
  const double slope = sxy / sxx;
  return {slope, my - slope * mx};
}

std::vector<ConvergenceOrder> convergenceOrders(const std::vector<ConvergenceSample>& samples,
                                                int fitLevels, double floor) {
  if (fitLevels < 2)
    fail("convergence order: expected at least 2 levels to fit, got {}", fitLevels);
  std::map<std::pair<std::string, std::string>, std::vector<ConvergenceSample>> groups;
  std::vector<std::pair<std::string, std::string>> order;
  for (const ConvergenceSample& s : samples) {
    if (!s.truthDistance) continue;
    const auto key = std::make_pair(s.shape, s.model);
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(s);
  }
  std::vector<ConvergenceOrder> out;
  for (const auto& key : order) {
    std::vector<ConvergenceSample>& g = groups[key];
    std::sort(g.begin(), g.end(), [](const auto& a, const auto& b) { return a.level < b.level; });
    ConvergenceOrder o{key.first, key.second, std::nullopt, 0, *g.back().truthDistance};
    std::vector<std::pair<double, double>> points;
    for (size_t i = g.size() > size_t(fitLevels) ? g.size() - size_t(fitLevels) : 0; i < g.size();
         ++i)
      if (*g[i].truthDistance >= floor)
        points.emplace_back(g[i].meanEdgeLength, *g[i].truthDistance);
    o.pointsFitted = int(points.size());
    if (points.size() >= 2) o.order = fitPowerLaw(points).slope;
    out.push_back(o);
  }
  return out;
}

std::string convergenceCsv(const std::vector<ConvergenceSample>& samples) {
  std::string csv = "shape,level,model,triangles,mean_edge_length,truth_distance\n";
  for (const ConvergenceSample& s : samples)
    csv += fmt::format("\"{}\",{},{},{},{:.9g},{}\n", s.shape, s.level, s.model, s.triangles,
                       s.meanEdgeLength,
                       s.truthDistance ? fmt::format("{:.9g}", *s.truthDistance) : "");
  return csv;
}

std::string ordersCsv(const std::vector<ConvergenceOrder>& orders) {
  std::string csv = "shape,model,order,points_fitted,finest_truth_distance\n";
  for (const ConvergenceOrder& o : orders)
    csv += fmt::format("\"{}\",{},{},{},{:.9g}\n", o.shape, o.model,
                       o.order ? fmt::format("{:.4f}", *o.order) : "", o.pointsFitted,
                       o.finestDistance);
  return csv;
}

std::string ordersMarkdown(const std::vector<ConvergenceOrder>& orders) {
  const auto shapes = distinct(orders, [](const ConvergenceOrder& o) { return o.shape; });
  const auto models = distinct(orders, [](const ConvergenceOrder& o) { return o.model; });
  std::string md = "| model |";
  for (const std::string& s : shapes) md += " " + s + " |";
  md += "\n|---|";
  for (size_t i = 0; i < shapes.size(); ++i) md += "---:|";
  md += "\n";
  for (const std::string& m : models) {
    md += "| " + m + " |";
    for (const std::string& s : shapes) {
      const auto it = std::find_if(orders.begin(), orders.end(), [&](const ConvergenceOrder& o) {
        return o.shape == s && o.model == m;
      });
      if (it == orders.end())
        md += " - |";
      else if (!it->order)
        md += " exact |";
      else
        md += fmt::format(" {:.2f} |", *it->order);
    }
    md += "\n";
  }
  return md;
}

Canvas convergencePlot(const std::vector<ConvergenceSample>& samples, double floor) {
  static const Rgb palette[] = {
      {0.12f, 0.47f, 0.71f}, {1.00f, 0.50f, 0.05f}, {0.17f, 0.63f, 0.17f}, {0.84f, 0.15f, 0.16f},
      {0.58f, 0.40f, 0.74f}, {0.55f, 0.34f, 0.29f}, {0.89f, 0.47f, 0.76f}, {0.50f, 0.50f, 0.50f},
      {0.74f, 0.74f, 0.13f}, {0.09f, 0.75f, 0.81f}, {0.00f, 0.00f, 0.00f}, {0.40f, 0.20f, 0.00f}};
  const Marker markers[] = {Marker::Square, Marker::Circle, Marker::Triangle, Marker::Cross};
  const auto shapes = distinct(samples, [](const ConvergenceSample& s) { return s.shape; });
  const auto models = distinct(samples, [](const ConvergenceSample& s) { return s.model; });
  std::vector<PlotSeries> series;
  PlotOptions options;
  std::vector<bool> labelled(models.size(), false);
  for (size_t i = 0; i < shapes.size(); ++i) {
    options.markerLegend.emplace_back(shapes[i], markers[i % 4]);
    for (size_t m = 0; m < models.size(); ++m) {
      PlotSeries ps{"", palette[m % 12], {}, markers[i % 4]};
      for (const ConvergenceSample& s : samples)
        if (s.shape == shapes[i] && s.model == models[m] && s.truthDistance &&
            *s.truthDistance >= floor)
          ps.points.emplace_back(double(s.triangles), *s.truthDistance);
      if (ps.points.empty()) continue;
      if (!labelled[m]) ps.label = models[m];
      labelled[m] = true;
      series.push_back(std::move(ps));
    }
  }
  options.width = 980;
  options.height = 620;
  options.legendWidth = 250;
  options.logY = true;
  options.title = "Distance to the true surface under refinement";
  options.xLabel = "triangles";
  options.yLabel = "truth_distance";
  return linePlot(series, options);
}

}  // namespace quadtri
