#include "quadtri/analysis/metrics.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <nlohmann/json.hpp>

#include "quadtri/geometry/model_geometry.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

// Barycentric (u, v) of corner k: (0,0), (1,0), (0,1).
const std::array<Vec2, 3> kCornerUv = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};

// The model's surface point, refusing non-finite results so that no NaN reaches a metric.
SurfacePoint evaluateChecked(const SurfaceModel& model, size_t t, const Vec2& uv) {
  const SurfacePoint p = model.evaluate(t, uv.x(), uv.y());
  if (!allFinite(p.position) || !allFinite(p.normal))
    fail("model '{}': patch {} is not finite at (u, v) = ({}, {})", model.name(), t, uv.x(),
         uv.y());
  return p;
}

double meanEdgeLength(const SurfaceModel& model) {
  const double length = model.mesh().meanEdgeLength();
  if (!(length > 0.0)) fail("model '{}': the mesh has no edge of positive length", model.name());
  return length;
}

// Max of f(t) over patches t, in parallel.
template <typename F>
double maxOverPatches(const SurfaceModel& model, const F& f) {
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, model.patchCount()), 0.0,
      [&](const tbb::blocked_range<size_t>& range, double best) {
        for (size_t t = range.begin(); t != range.end(); ++t) best = std::max(best, f(t));
        return best;
      },
      [](double a, double b) { return std::max(a, b); });
}

}  // namespace

double vertexPositionError(const SurfaceModel& model) {
  const double scale = meanEdgeLength(model);
  return maxOverPatches(model, [&](size_t t) {
    double worst = 0.0;
    for (int k = 0; k < 3; ++k)
      worst = std::max(
          worst,
          (evaluateChecked(model, t, kCornerUv[k]).position - model.mesh().corner(t, k)).norm());
    return worst / scale;
  });
}

double vertexNormalErrorDeg(const SurfaceModel& model) {
  return maxOverPatches(model, [&](size_t t) {
    double worst = 0.0;
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, angleDegrees(evaluateChecked(model, t, kCornerUv[k]).normal,
                                           model.mesh().cornerNormal(t, k)));
    return worst;
  });
}

double vertexNormalFlipRate(const SurfaceModel& model) {
  if (model.patchCount() == 0) return 0.0;
  const size_t flips = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, model.patchCount()), size_t(0),
      [&](const tbb::blocked_range<size_t>& range, size_t count) {
        for (size_t t = range.begin(); t != range.end(); ++t)
          for (int k = 0; k < 3; ++k)
            count += evaluateChecked(model, t, kCornerUv[k])
                         .normal.dot(model.mesh().cornerNormal(t, k)) < 0.0;
        return count;
      },
      [](size_t a, size_t b) { return a + b; });
  return double(flips) / double(3 * model.patchCount());
}

std::optional<EdgeContinuity> edgeContinuity(const SurfaceModel& model,
                                             const MeshTopology& topology, int samples) {
  if (samples < 2) fail("edge continuity: at least 2 samples per edge are needed, got {}", samples);
  const TriangleMesh& mesh = model.mesh();
  const double scale = meanEdgeLength(model);
  // Point at parameter s from the edge's first vertex `a`, on side (t, k): local edge k runs
  // from corner k to corner k+1, so a side that starts at the other vertex runs backwards.
  auto sidePoint = [&](const Edge& e, std::pair<uint32_t, uint8_t> side, double s) {
    const auto [t, k] = side;
    const double local = mesh.triangles[t][k] == e.a ? s : 1.0 - s;
    const Vec2 uv = (1.0 - local) * kCornerUv[k] + local * kCornerUv[(k + 1) % 3];
    return evaluateChecked(model, t, uv);
  };
  using Result = std::optional<EdgeContinuity>;
  auto join = [](Result a, const Result& b) {
    if (!a) return b;
    if (b) {
      a->c0Gap = std::max(a->c0Gap, b->c0Gap);
      a->c1AngleDeg = std::max(a->c1AngleDeg, b->c1AngleDeg);
    }
    return a;
  };
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, topology.edges.size()), Result(),
      [&](const tbb::blocked_range<size_t>& range, Result best) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
          const Edge& e = topology.edges[i];
          if (e.sides.size() != 2) continue;
          EdgeContinuity c;
          for (int j = 0; j < samples; ++j) {
            const double s = double(j) / (samples - 1);
            const SurfacePoint pa = sidePoint(e, e.sides[0], s), pb = sidePoint(e, e.sides[1], s);
            c.c0Gap = std::max(c.c0Gap, (pa.position - pb.position).norm() / scale);
            c.c1AngleDeg = std::max(c.c1AngleDeg, angleDegrees(pa.normal, pb.normal));
          }
          best = join(best, c);
        }
        return best;
      },
      join);
}

double truthDistance(const SurfaceModel& model, const AnalyticSurface& truth, int level) {
  if (level < 1) fail("truth distance: the lattice level must be at least 1, got {}", level);
  const double size = truth.size();
  return maxOverPatches(model, [&](size_t t) {
    double worst = 0.0;
    for (int j = 0; j <= level; ++j)
      for (int i = 0; i + j <= level; ++i) {
        const Vec2 uv(double(i) / level, double(j) / level);
        worst = std::max(worst, truth.distance(evaluateChecked(model, t, uv).position) / size);
      }
    return worst;
  });
}

ModelMetrics analyzeModel(const SurfaceModel& model, const std::string& meshName,
                          const std::optional<AnalyticSurface>& truth, double convertSeconds,
                          const AnalysisOptions& options) {
  ModelMetrics m;
  m.model = std::string(model.name());
  m.mesh = meshName;
  m.triangles = model.mesh().triangleCount();
  m.convertSeconds = convertSeconds;
  const ModelGeometry geometry = modelGeometry(model, options.tessellation);
  m.primitives = geometry.primitiveCount();
  m.memoryBytes = geometry.bytes();
  m.vertexPositionError = vertexPositionError(model);
  m.vertexNormalErrorDeg = vertexNormalErrorDeg(model);
  m.vertexNormalFlipRate = vertexNormalFlipRate(model);
  const MeshTopology topology(model.mesh());
  if (const std::optional<EdgeContinuity> c =
          edgeContinuity(model, topology, options.edgeSamples)) {
    m.c0Gap = c->c0Gap;
    m.c1AngleDeg = c->c1AngleDeg;
  }
  if (topology.isClosed()) m.crackRate = crackRate(geometry, options.crack);
  if (truth) m.truthDistance = truthDistance(model, *truth, options.truthLevel);
  return m;
}

nlohmann::ordered_json toJson(const ModelMetrics& m) {
  auto nullable = [](const std::optional<double>& x) {
    return x ? nlohmann::ordered_json(*x) : nlohmann::ordered_json(nullptr);
  };
  return nlohmann::ordered_json{
      {"model", m.model},
      {"mesh", m.mesh},
      {"triangles", m.triangles},
      {"primitives", m.primitives},
      {"memory_bytes", m.memoryBytes},
      {"convert_seconds", m.convertSeconds},
      {"vertex_position_error", m.vertexPositionError},
      {"vertex_normal_error_deg", m.vertexNormalErrorDeg},
      {"vertex_normal_flip_rate", m.vertexNormalFlipRate},
      {"c0_gap", nullable(m.c0Gap)},
      {"c1_angle_deg", nullable(m.c1AngleDeg)},
      {"crack_rate", nullable(m.crackRate)},
      {"truth_distance", nullable(m.truthDistance)},
  };
}

std::string metricsTable(const std::vector<ModelMetrics>& rows) {
  const std::vector<std::string> keys = {"model",
                                         "triangles",
                                         "primitives",
                                         "memory_bytes",
                                         "convert_seconds",
                                         "vertex_position_error",
                                         "vertex_normal_error_deg",
                                         "vertex_normal_flip_rate",
                                         "c0_gap",
                                         "c1_angle_deg",
                                         "crack_rate",
                                         "truth_distance"};
  std::vector<std::vector<std::string>> cells(1, keys);
  for (const ModelMetrics& m : rows) {
    const nlohmann::ordered_json j = toJson(m);
    std::vector<std::string> row;
    for (const std::string& key : keys) {
      const nlohmann::ordered_json& value = j.at(key);
      if (value.is_null())
        row.push_back("-");
      else if (value.is_string())
        row.push_back(value.get<std::string>());
      else if (value.is_number_integer() || value.is_number_unsigned())
        row.push_back(fmt::format("{}", value.get<size_t>()));
      else
        row.push_back(fmt::format("{:.4g}", value.get<double>()));
    }
    cells.push_back(std::move(row));
  }
  std::vector<size_t> width(keys.size(), 0);
  for (const auto& row : cells)
    for (size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  std::string out;
  for (const auto& row : cells) {
    for (size_t c = 0; c < row.size(); ++c) {
      // The model name reads left-aligned, numbers right-aligned.
      out += c == 0 ? fmt::format("{:<{}}", row[c], width[c])
                    : fmt::format("  {:>{}}", row[c], width[c]);
    }
    out += '\n';
  }
  return out;
}

}  // namespace quadtri
