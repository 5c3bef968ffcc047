#include "quadtri/analysis/metrics.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "quadtri/geometry/model_geometry.h"
#include "quadtri/io/csv.h"
#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"

namespace quadtri {
namespace {

// Barycentric (u, v) of corner k: (0,0), (1,0), (0,1).
const std::array<Vec2, 3> kCornerUv = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};

// The model's surface points at uv[0..count) of patch t (evaluateMany: the patch built once),
// refusing non-finite results so that no NaN reaches a metric.
void evaluateCheckedMany(const SurfaceModel& model, size_t t, const Vec2* uv, size_t count,
                         SurfacePoint* out) {
  model.evaluateMany(t, uv, count, out);
  for (size_t i = 0; i < count; ++i)
    if (!allFinite(out[i].position) || !allFinite(out[i].normal))
      fail("model '{}': patch {} is not finite at (u, v) = ({}, {})", model.name(), t, uv[i].x(),
           uv[i].y());
}

double meanEdgeLength(const SurfaceModel& model) {
  const double length = model.mesh().meanEdgeLength();
  if (!(length > 0.0)) fail("model '{}': the mesh has no edge of positive length", model.name());
  return length;
}

// Max of f(t) over patches t, in parallel.
template <typename F>
double maxOverPatches(const SurfaceModel& model, const F& f) {
  return parallelReduce(
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
    std::array<SurfacePoint, 3> corners;
    evaluateCheckedMany(model, t, kCornerUv.data(), 3, corners.data());
    double worst = 0.0;
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, (corners[size_t(k)].position - model.mesh().corner(t, k)).norm());
    return worst / scale;
  });
}

CornerStats checkedCornerStats(const SurfaceModel& model) {
  const CornerStats stats = cornerStats(model);
  if (stats.nonFinite) {
    const Vec2& uv = kCornerUv[stats.firstNonFiniteCorner];
    fail("model '{}': patch {} is not finite at (u, v) = ({}, {})", model.name(),
         stats.firstNonFinitePatch, uv.x(), uv.y());
  }
  return stats;
}

double vertexNormalErrorDeg(const SurfaceModel& model) {
  return checkedCornerStats(model).maxNormalErrorDeg;
}

double vertexNormalFlipRate(const SurfaceModel& model) {
  return checkedCornerStats(model).flipRate();
}

std::optional<EdgeContinuity> edgeContinuity(const SurfaceModel& model,
                                             const MeshTopology& topology, int samples) {
  if (samples < 2) fail("edge continuity: at least 2 samples per edge are needed, got {}", samples);
  const TriangleMesh& mesh = model.mesh();
  const double scale = meanEdgeLength(model);
  // Point at parameter s from the edge's first vertex `a`, on side (t, k): local edge k runs
  // from corner k to corner k+1, so a side that starts at the other vertex runs backwards.
  // The points of `samples` parameters s = j / (samples - 1) on side (t, k), evaluated
  // together into `points` (uv: a buffer for their (u, v)).
  auto sidePoints = [&](const Edge& e, std::pair<uint32_t, uint8_t> side, std::vector<Vec2>& uv,
                        std::vector<SurfacePoint>& points) {
    const auto [t, k] = side;
    for (int j = 0; j < samples; ++j) {
      const double s = double(j) / (samples - 1);
      const double local = mesh.triangles[t][k] == e.a ? s : 1.0 - s;
      uv[size_t(j)] = (1.0 - local) * kCornerUv[k] + local * kCornerUv[(k + 1) % 3];
    }
    evaluateCheckedMany(model, t, uv.data(), uv.size(), points.data());
  };
  // Per block: the continuity so far, plus the smooth edges seen and how many were G1.
  struct Partial {
    std::optional<EdgeContinuity> c;
    size_t smooth = 0, g1 = 0;
  };
  auto join = [](Partial a, const Partial& b) {
    a.smooth += b.smooth;
    a.g1 += b.g1;
    if (!a.c) {
      a.c = b.c;
      return a;
    }
    if (b.c) {
      a.c->c0Gap = std::max(a.c->c0Gap, b.c->c0Gap);
      a.c->c1AngleDeg = std::max(a.c->c1AngleDeg, b.c->c1AngleDeg);
      if (b.c->c1AngleSmoothDeg)
        a.c->c1AngleSmoothDeg =
            std::max(a.c->c1AngleSmoothDeg.value_or(0.0), *b.c->c1AngleSmoothDeg);
    }
    return a;
  };
  const EdgeEnds ends = edgeEnds(mesh, topology);
  // The corner normal of side (t, k) at mesh vertex v of the edge.
  auto sideNormal = [&](std::pair<uint32_t, uint8_t> side, uint32_t v) {
    const auto [t, k] = side;
    return mesh.cornerNormal(t, mesh.triangles[t][k] == v ? k : (k + 1) % 3);
  };
  Partial total = parallelReduce(
      tbb::blocked_range<size_t>(0, topology.edges.size()), Partial(),
      [&](const tbb::blocked_range<size_t>& range, Partial best) {
        const size_t count = static_cast<size_t>(samples);
        std::vector<Vec2> uv(count);
        std::vector<SurfacePoint> sideA(count), sideB(count);
        for (size_t i = range.begin(); i != range.end(); ++i) {
          const Edge& e = topology.edges[i];
          if (e.sides.size() != 2) continue;
          EdgeContinuity c;
          sidePoints(e, e.sides[0], uv, sideA);
          sidePoints(e, e.sides[1], uv, sideB);
          for (size_t j = 0; j < count; ++j) {
            const SurfacePoint &pa = sideA[j], &pb = sideB[j];
            c.c0Gap = std::max(c.c0Gap, (pa.position - pb.position).norm() / scale);
            c.c1AngleDeg = std::max(c.c1AngleDeg, angleDegrees(pa.normal, pb.normal));
          }
          Partial one;
          bool smooth =
              !mesh.hasNormals() || (sideNormal(e.sides[0], e.a) == sideNormal(e.sides[1], e.a) &&
                                     sideNormal(e.sides[0], e.b) == sideNormal(e.sides[1], e.b));
          for (auto [t, k] : e.sides)
            smooth = smooth && consistentCorner(mesh, ends, t, k) &&
                     consistentCorner(mesh, ends, t, (k + 1) % 3);
          if (smooth) {
            c.c1AngleSmoothDeg = c.c1AngleDeg;
            one.smooth = 1;
            one.g1 = c.c1AngleDeg < kG1ToleranceDeg;
          }
          one.c = c;
          best = join(best, one);
        }
        return best;
      },
      join);
  if (total.c && total.smooth > 0) total.c->g1EdgeShare = double(total.g1) / double(total.smooth);
  return total.c;
}

double truthDistance(const SurfaceModel& model, const AnalyticSurface& truth, int level) {
  if (level < 1) fail("truth distance: the lattice level must be at least 1, got {}", level);
  const double size = truth.size();
  std::vector<Vec2> lattice;
  for (int j = 0; j <= level; ++j)
    for (int i = 0; i + j <= level; ++i) lattice.emplace_back(double(i) / level, double(j) / level);
  return parallelReduce(
      tbb::blocked_range<size_t>(0, model.patchCount()), 0.0,
      [&](const tbb::blocked_range<size_t>& range, double worst) {
        std::vector<SurfacePoint> points(lattice.size());
        for (size_t t = range.begin(); t != range.end(); ++t) {
          evaluateCheckedMany(model, t, lattice.data(), lattice.size(), points.data());
          for (const SurfacePoint& p : points)
            worst = std::max(worst, truth.distance(p.position) / size);
        }
        return worst;
      },
      [](double a, double b) { return std::max(a, b); });
}

std::string crackRateUndefinedReason(const MeshTopology& topology) {
  std::vector<std::string> why;
  if (const size_t n = topology.nonManifoldEdgeCount())
    why.push_back(fmt::format(
        "{} edge{} three or more triangles: a line crossing one meets more than two sheets "
        "there, so the parity of its crossings no longer tells inside from outside",
        n, n == 1 ? " has" : "s have"));
  if (const size_t n = topology.boundaryEdgeCount())
    why.push_back(fmt::format(
        "{} boundary edge{}: the mesh is open, so it bounds no volume whose crossings a line "
        "could count",
        n, n == 1 ? "" : "s"));
  return fmt::format("{}", fmt::join(why, "; "));
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
  const CornerStats corners = checkedCornerStats(model);
  m.vertexNormalErrorDeg = corners.maxNormalErrorDeg;
  m.vertexNormalFlipRate = corners.flipRate();
  m.inconsistentCornerRate = corners.inconsistentRate();
  m.vertexNormalErrorConsistentDeg = corners.maxConsistentNormalErrorDeg;
  m.vertexNormalFlipRateConsistent = corners.consistentFlipRate();
  m.fallbackRate = fallbackRate(model);
  const MeshTopology& topology = model.mesh().topology();
  if (const std::optional<EdgeContinuity> c =
          edgeContinuity(model, topology, options.edgeSamples)) {
    m.c0Gap = c->c0Gap;
    m.c1AngleDeg = c->c1AngleDeg;
    m.c1AngleSmoothDeg = c->c1AngleSmoothDeg;
    m.g1EdgeShare = c->g1EdgeShare;
  }
  if (topology.isClosed()) {
    // The acceleration structure's refusals (a coordinate beyond what Embree traces) name the
    // vertex, not the mesh: say which.
    try {
      // Every model of the mesh on the same lines: those through the mesh's own box.
      CrackRateOptions crack = options.crack;
      if (!crack.lineBox) crack.lineBox = model.mesh().bounds();
      m.crackRate = crackRate(geometry, crack);
    } catch (const Error& e) {
      fail("{}: crack rate of {}: {}", meshName, m.model, e.what());
    }
  } else
    m.crackRateUndefined = crackRateUndefinedReason(topology);
  if (truth) m.truthDistance = truthDistance(model, *truth, options.truthLevel);
  return m;
}

namespace {

using Json = nlohmann::ordered_json;

Json nullable(const std::optional<double>& x) {
  return x ? Json(*x) : Json(nullptr);
}

// The one table of keys: name, whether the text table shows it, and its value.
struct MetricKey {
  const char* key;
  bool inTable;
  Json (*value)(const ModelMetrics&);
};

const std::vector<MetricKey>& keyTable() {
  static const std::vector<MetricKey> keys = {
      {"model", true, [](const ModelMetrics& m) { return Json(m.model); }},
      {"mesh", false, [](const ModelMetrics& m) { return Json(m.mesh); }},
      {"triangles", true, [](const ModelMetrics& m) { return Json(m.triangles); }},
      {"primitives", true, [](const ModelMetrics& m) { return Json(m.primitives); }},
      {"memory_bytes", true, [](const ModelMetrics& m) { return Json(m.memoryBytes); }},
      {"convert_seconds", true, [](const ModelMetrics& m) { return Json(m.convertSeconds); }},
      {"vertex_position_error", true,
       [](const ModelMetrics& m) { return Json(m.vertexPositionError); }},
      {"vertex_normal_error_deg", true,
       [](const ModelMetrics& m) { return Json(m.vertexNormalErrorDeg); }},
      {"vertex_normal_flip_rate", true,
       [](const ModelMetrics& m) { return Json(m.vertexNormalFlipRate); }},
      {"inconsistent_corner_rate", true,
       [](const ModelMetrics& m) { return Json(m.inconsistentCornerRate); }},
      {"vertex_normal_error_consistent_deg", true,
       [](const ModelMetrics& m) { return nullable(m.vertexNormalErrorConsistentDeg); }},
      {"vertex_normal_flip_rate_consistent", true,
       [](const ModelMetrics& m) { return nullable(m.vertexNormalFlipRateConsistent); }},
      {"fallback_rate", true, [](const ModelMetrics& m) { return Json(m.fallbackRate); }},
      {"c0_gap", true, [](const ModelMetrics& m) { return nullable(m.c0Gap); }},
      {"c1_angle_deg", true, [](const ModelMetrics& m) { return nullable(m.c1AngleDeg); }},
      {"c1_angle_smooth_deg", true,
       [](const ModelMetrics& m) { return nullable(m.c1AngleSmoothDeg); }},
      {"g1_edge_share", true, [](const ModelMetrics& m) { return nullable(m.g1EdgeShare); }},
      {"crack_rate", true, [](const ModelMetrics& m) { return nullable(m.crackRate); }},
      {"truth_distance", true, [](const ModelMetrics& m) { return nullable(m.truthDistance); }},
      {"crack_rate_undefined", false,
       [](const ModelMetrics& m) {
         return m.crackRateUndefined.empty() ? Json(nullptr) : Json(m.crackRateUndefined);
       }},
  };
  return keys;
}

}  // namespace

ModelMetrics analyzeNamedModel(const std::string& name,
                               const std::shared_ptr<const TriangleMesh>& mesh,
                               const std::string& meshName,
                               const std::optional<AnalyticSurface>& truth,
                               const AnalysisOptions& options,
                               const std::function<void(const SurfaceModel&)>& inspect) {
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<SurfaceModel> model = makeModel(name, mesh);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ModelMetrics metrics = analyzeModel(*model, meshName, truth, seconds, options);
  if (inspect) inspect(*model);
  return metrics;
}

const std::vector<std::string>& metricKeys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> out;
    for (const MetricKey& k : keyTable()) out.push_back(k.key);
    return out;
  }();
  return keys;
}

nlohmann::ordered_json toJson(const ModelMetrics& m) {
  Json j = Json::object();
  for (const MetricKey& k : keyTable()) j[k.key] = k.value(m);
  return j;
}

std::string csvValue(const nlohmann::ordered_json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return csvField(value.get<std::string>());
  if (value.is_number_float() && !std::isfinite(value.get<double>())) return "";
  return value.dump();
}

std::string metricsCsv(const std::vector<ModelMetrics>& rows) {
  std::string out = fmt::format("{}\n", fmt::join(metricKeys(), ","));
  for (const ModelMetrics& m : rows) {
    const Json j = toJson(m);
    std::vector<std::string> fields;
    for (const std::string& key : metricKeys()) fields.push_back(csvValue(j.at(key)));
    out += fmt::format("{}\n", fmt::join(fields, ","));
  }
  return out;
}

std::string metricsTable(const std::vector<ModelMetrics>& rows) {
  std::vector<std::string> keys;
  for (const MetricKey& k : keyTable())
    if (k.inTable) keys.push_back(k.key);
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
  if (!rows.empty() && !rows.front().crackRateUndefined.empty())
    out += fmt::format("crack_rate: not defined: {}\n", rows.front().crackRateUndefined);
  return out;
}

}  // namespace quadtri
