// How well a model meets the four constraints and what it costs (docs/DESIGN.md §4): free functions
// over a SurfaceModel, and the per-model record that `quadtri analyze` prints.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/analysis/crack_rate.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/corner_stats.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

/// max over patches t and corners k of |evaluate(t, corner k) − v_k| / mean edge length
/// (constraint 1).
double vertexPositionError(const SurfaceModel& model);

/// max over patches and corners of the angle (degrees) between evaluate(t, corner k).normal
/// and the corner's shading normal (constraint 2).
double vertexNormalErrorDeg(const SurfaceModel& model);

/// The share of patch corners whose normal points away from the corner's shading normal
/// (n·n_k < 0): where a patch meets the tangent plane of constraint 2 but folds back over it,
/// e.g. a quadratic edge whose end tangents must reverse because the normals lean the same way
/// along it (an inflection), or a shading normal more than 90° from its own face's normal.
double vertexNormalFlipRate(const SurfaceModel& model);

/// cornerStats (corner_stats.h: consistent corners, folds, normal errors) of every patch
/// corner; throws Error naming the first patch whose corner is not finite.
CornerStats checkedCornerStats(const SurfaceModel& model);

/// Continuity across shared edges (constraints 3 and 4).
struct EdgeContinuity {
  double c0Gap = 0;       ///< max |P_a(s) − P_b(s)| / mean edge length
  double c1AngleDeg = 0;  ///< max angle between n_a(s) and n_b(s)
  /// c1AngleDeg over smooth edges only: those whose two sides carry the same corner normals
  /// at both ends and whose four corners are consistent (CornerStats), where a G1 surface must
  /// be tangent-continuous; nullopt when there is none.
  std::optional<double> c1AngleSmoothDeg;
  /// Share of smooth edges whose normal jump stays below kG1ToleranceDeg (G1 edges).
  std::optional<double> g1EdgeShare;
};

/// The largest normal jump (degrees) across an edge that still counts as tangent-continuous.
inline constexpr double kG1ToleranceDeg = 0.01;

/// Samples `samples` points s = i/(samples−1) along every edge with exactly two sides, each
/// side evaluating its own patch at the same point of the edge (the sides traverse the edge in
/// opposite directions, so each maps s from the edge's first vertex). nullopt when the mesh
/// has no such edge.
std::optional<EdgeContinuity> edgeContinuity(const SurfaceModel& model,
                                             const MeshTopology& topology, int samples = 9);

/// max over a lattice of level `level` on every patch ((level+1)(level+2)/2 points, corners and
/// centroid included when level is a multiple of 3) of truth.distance(P) / truth.size().
double truthDistance(const SurfaceModel& model, const AnalyticSurface& truth, int level = 12);

/// Everything `quadtri analyze` reports for one model; nullopt prints as null.
struct ModelMetrics {
  std::string model, mesh;
  size_t triangles = 0;
  size_t primitives = 0;
  size_t memoryBytes = 0;
  double convertSeconds = 0;
  double vertexPositionError = 0;
  double vertexNormalErrorDeg = 0;
  double vertexNormalFlipRate = 0;
  /// Share of corners whose triangle faces away from their shading normal (CornerStats).
  double inconsistentCornerRate = 0;
  /// vertexNormalErrorDeg and vertexNormalFlipRate over consistent corners only; nullopt when
  /// no corner is consistent.
  std::optional<double> vertexNormalErrorConsistentDeg, vertexNormalFlipRateConsistent;
  /// Share of patches that fell back (SurfaceModel::fellBack).
  double fallbackRate = 0;
  std::optional<double> c0Gap, c1AngleDeg, c1AngleSmoothDeg, g1EdgeShare, crackRate, truthDistance;
  /// Why crackRate is not defined (the mesh is open or non-manifold); empty when it is.
  std::string crackRateUndefined;
};

/// Why crack_rate is not defined on a mesh that is not closed: its non-manifold and its
/// boundary edges, counted, each with the reason.
std::string crackRateUndefinedReason(const MeshTopology& topology);

struct AnalysisOptions {
  Tessellation tessellation;
  CrackRateOptions crack;
  int edgeSamples = 9;
  int truthLevel = 12;
};

/// Measures `model`: builds its render geometry (and, for a closed mesh, a robust Embree scene
/// for the crack rate); `truth` is the analytic surface when the mesh is a built-in shape.
/// `convertSeconds` is the caller's measured wall time of makeModel.
ModelMetrics analyzeModel(const SurfaceModel& model, const std::string& meshName,
                          const std::optional<AnalyticSurface>& truth, double convertSeconds,
                          const AnalysisOptions& options = {});

/// Converts `mesh` with the named model (makeModel), timing the conversion, and measures it
/// with analyzeModel; `inspect`, when given, then sees the model (heatmaps, ...). What
/// `quadtri analyze` and `quadtri study` measure, one model at a time.
ModelMetrics analyzeNamedModel(const std::string& name,
                               const std::shared_ptr<const TriangleMesh>& mesh,
                               const std::string& meshName,
                               const std::optional<AnalyticSurface>& truth,
                               const AnalysisOptions& options = {},
                               const std::function<void(const SurfaceModel&)>& inspect = {});

/// Every key of toJson, in order: "model", "mesh", then the docs/DESIGN.md §4 keys and the corner
/// and fallback keys. The one list the table, the JSON and every CSV follow.
const std::vector<std::string>& metricKeys();

/// One JSON value per metricKeys() key; null where a key does not apply.
nlohmann::ordered_json toJson(const ModelMetrics& metrics);

/// A text table: one row per model, one column per key but "mesh", null as "-", columns
/// aligned.
std::string metricsTable(const std::vector<ModelMetrics>& rows);

/// A CSV field for one toJson value: strings quoted where needed (RFC 4180), numbers as JSON
/// writes them (the shortest text that reads back to the same double), null and non-finite
/// numbers empty.
std::string csvValue(const nlohmann::ordered_json& value);

/// CSV: a header of metricKeys(), one row per model.
std::string metricsCsv(const std::vector<ModelMetrics>& rows);

}  // namespace quadtri
