// `quadtri study`: every model on every mesh of a corpus, measured as `quadtri analyze`
// measures one mesh, with a CSV of every (mesh, model) and a Markdown summary per model.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/analysis/metrics.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/report/shard.h"

namespace quadtri {

/// One mesh of a study: its name in the outputs and its file.
struct StudyMesh {
  std::string name;
  std::filesystem::path path;
};

/// Reads a corpus manifest: CSV with a header naming at least the columns `name` and `path`
/// (data/corpus-manifest.csv also has source, licence, triangles, vertices, closed, manifold,
/// file_normals and kind, which the study does not need). Paths are relative to `corpus`. Throws
/// Error naming the manifest and line for a missing column, a row with another number of fields
/// than the header, an empty name or path, or a name given twice. Files are not opened here: a
/// missing one becomes its rows' error.
std::vector<StudyMesh> readCorpusManifest(const std::filesystem::path& manifest,
                                          const std::filesystem::path& corpus);

/// Every .obj, .off, .ply and .stl file (extension in any case) under `folder`, its subfolders
/// included, named by its path relative to `folder` ('/'-separated) and sorted by that name.
/// Throws Error when the folder cannot be read or holds no such file.
std::vector<StudyMesh> meshesInFolder(const std::filesystem::path& folder);

/// Part I of N of a mesh list: the meshes whose 0-based index i has i % N == I − 1, so that N
/// machines running 1/N ... N/N together measure every mesh once.
using StudyShard = Shard;

/// Reported when a mesh starts and when it is finished; `done` counts finished meshes of
/// `total` (the shard's).
struct StudyProgress {
  size_t done = 0, total = 0;
  std::string mesh;
  bool finished = false;
  size_t failedModels = 0;  ///< when finished: rows of this mesh with an error
};

struct StudyOptions {
  std::vector<std::string> models;  ///< empty: modelNames()
  AnalysisOptions analysis;
  NormalOptions normals;  ///< as --normals and --crease-angle
  int threads = 0;        ///< worker threads over meshes and inside each analysis; 0: all cores
  StudyShard shard;
  /// Called from worker threads, one call at a time.
  std::function<void(const StudyProgress&)> onProgress;
};

/// One (mesh, model): its metrics, or the error that stopped it (loading the mesh, converting
/// it or measuring the model). `triangles` and `closed` are the loaded mesh's (absent when it
/// did not load).
struct StudyRow {
  std::string mesh, model;
  std::optional<size_t> triangles;
  std::optional<bool> closed;
  std::optional<ModelMetrics> metrics;
  std::string error;  ///< empty when measured
};

/// Measures every model on every mesh of the shard, meshes in parallel (each analysis is
/// parallel too; `threads` bounds both). Rows come in the meshes' order, each mesh's in the
/// models' order, whatever the thread count; a mesh or model that fails is a row with its
/// error, never an abort. Throws Error only for an unknown model name, before any work.
std::vector<StudyRow> runStudy(const std::vector<StudyMesh>& meshes, const StudyOptions& options);

/// The columns of study.csv: mesh, model, triangles, closed, the metricKeys() but model, mesh
/// and triangles (convert_seconds is the conversion time), and error.
const std::vector<std::string>& studyColumns();

/// study.csv: a header of studyColumns(), one line per row. closed is yes or no; a value that
/// does not apply (null in analyze's JSON), every metric of a failed row and any non-finite
/// number are empty; fields are quoted where CSV needs it.
std::string studyCsv(const std::vector<StudyRow>& rows);

/// The worst value of a metric over a model's meshes and the (first) mesh that has it.
struct StudyWorst {
  double value = 0.0;
  std::string mesh;
};

/// One model's figures over the meshes it was measured on.
struct ModelSummary {
  std::string model;
  size_t rows = 0;      ///< meshes tried
  size_t measured = 0;  ///< meshes measured (rows without an error)
  size_t closed = 0;    ///< measured meshes with a crack rate (closed ones)
  size_t cracking = 0;  ///< of those, crack_rate > 0
  std::optional<StudyWorst> worstCrackRate;
  size_t withConsistentCorners = 0;         ///< measured meshes with a consistent corner
  size_t folding = 0;                       ///< of those, vertex_normal_flip_rate_consistent > 0
  std::optional<StudyWorst> worstFoldRate;  ///< of vertex_normal_flip_rate_consistent
  std::optional<StudyWorst> worstFallbackRate;
  std::optional<double> meanFallbackRate;
  std::optional<StudyWorst> worstNormalErrorConsistentDeg;
  /// Of c1_angle_smooth_deg (the normal jump across edges whose sides share both normals).
  std::optional<StudyWorst> worstC1SmoothDeg;
  /// The lowest g1_edge_share (share of those edges that are G1), and the meshes below 1.
  std::optional<StudyWorst> lowestG1EdgeShare;
  size_t notG1 = 0;
  std::optional<double> medianConvertSeconds;
};

/// One summary per model, in the order the models first appear in `rows`.
std::vector<ModelSummary> summarizeStudy(const std::vector<StudyRow>& rows);

/// summary.md: what was run (`what`, e.g. the command's settings), one table row per model of
/// `summaries`, and every failed (mesh, model) with its error.
std::string studySummaryMarkdown(const std::vector<ModelSummary>& summaries,
                                 const std::vector<StudyRow>& rows, const std::string& what);

/// Writes DIR/study.csv and DIR/summary.md (creating DIR), each atomically; returns their
/// paths.
std::vector<std::filesystem::path> writeStudy(const std::filesystem::path& dir,
                                              const std::vector<StudyRow>& rows,
                                              const std::string& what);

/// `quadtri merge SHARD.csv... -o study.csv`: the study.csv files of `--shard I/N` runs as one
/// file, written atomically: every shard's header must be the first's (an Error names the
/// shard), no mesh may have rows in two shards (an Error names the mesh and both files), and
/// the rows follow in the order the files are given. Returns the number of rows.
size_t mergeStudyShards(const std::vector<std::filesystem::path>& shards,
                        const std::filesystem::path& output);

}  // namespace quadtri
