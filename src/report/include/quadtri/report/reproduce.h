// The thesis' chapter 5 reproduction (docs/RESULTS.md): the renders and measurements behind its
// figures and tables, the Markdown tables built from them, and the speed and memory targets
// checked against them. `quadtri reproduce` runs it.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/analysis/metrics.h"
#include "quadtri/report/figure.h"

namespace quadtri {

/// A Markdown table; the first column is left-aligned, the others right-aligned unless
/// rightAligned is false.
struct MarkdownTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  bool rightAligned = true;
};

/// `| a | b |` lines: the header, the alignment row, one line per row (a short row is padded
/// with empty cells).
std::string toMarkdown(const MarkdownTable& table);

/// The cell of (shape, model), or nullptr.
const FigureCell* findCell(const std::vector<FigureCell>& cells, const std::string& shape,
                           const std::string& model);

/// Rows = models, columns = shapes: `value` of each cell, formatted with the fmt format
/// `format` (e.g. "{:.2f}"); "-" where the cell is missing.
MarkdownTable figurePivot(const std::vector<FigureCell>& cells,
                          const std::vector<std::string>& models,
                          const std::vector<std::string>& shapes,
                          const std::function<double(const FigureCell&)>& value,
                          const std::string& format);

/// Rows = every model but `baseline`, columns = shapes: renderTimeRatioRange(model, baseline)
/// as "median (lo-hi)" to two decimals; "-" where either cell is missing.
MarkdownTable ratioTable(const std::vector<FigureCell>& cells,
                         const std::vector<std::string>& models,
                         const std::vector<std::string>& shapes,
                         const std::string& baseline = "shading");

/// The scaling scene's table: one row per shape holding a `numerator` cell, in cell order:
/// patches (the numerator's primitives), the median render seconds of `baseline`, `middle` and
/// `numerator`, and the ratios numerator / baseline and numerator / middle with their ranges.
MarkdownTable scalingTable(const std::vector<FigureCell>& cells,
                           const std::string& baseline = "shading",
                           const std::string& middle = "quadric-param",
                           const std::string& numerator = "quadric-implicit");

/// The column label of a metrics row's mesh: a file's stem (data/teapot.obj → teapot), a
/// built-in shape spec as it is.
std::string meshLabel(const std::string& mesh);

/// Rows = models, columns = meshes (meshLabel), both in order of first appearance; the value
/// of the metricKeys() key `key` formatted with `format`, "0" where it is exactly zero and "-"
/// where it is null or missing. `models`, when not empty, keeps only those rows, in that order.
MarkdownTable metricPivot(const std::vector<ModelMetrics>& rows, const std::string& key,
                          const std::string& format, const std::vector<std::string>& models = {});

/// Table 5.1: rows = `models`, columns = meshes: "primitives (memory KiB)".
MarkdownTable primitivesTable(const std::vector<ModelMetrics>& rows,
                              const std::vector<std::string>& models);

/// Every metricKeys() column but mesh and convert_seconds, one row per model: strings as they
/// are, integers in full, other numbers to 3 significant digits, null as "-".
MarkdownTable metricsMarkdown(const std::vector<ModelMetrics>& rows);

/// One checked target: what it demands, what was measured, and whether it holds.
struct TargetCheck {
  std::string target, measured;
  double value = 0, limit = 0;
  bool pass = false;
};

/// value <= limit (atMost) or value >= limit; a non-finite value fails.
TargetCheck checkAtMost(std::string target, double value, double limit, std::string measured);
TargetCheck checkAtLeast(std::string target, double value, double limit, std::string measured);

/// The thresholds of docs/RESULTS.md's speed and memory targets.
struct TargetLimits {
  double renderRatio = 1.5;      ///< quadric-implicit / shading render time, at most
  double flatScaling = 1.2;      ///< that ratio at large counts / at the first, at most
  size_t largePatches = 100000;  ///< "large": at least this many patches
  double memoryFactor = 100;     ///< quadric-param / quadric-implicit geometry bytes, at least
};

/// quadric-implicit / shading render time per shape of a setup ("a" or "b").
std::vector<TargetCheck> renderRatioTargets(const std::vector<FigureCell>& cells,
                                            const std::vector<std::string>& shapes,
                                            const std::string& setup,
                                            const TargetLimits& limits = {});

/// The scaling scene: for each shape with at least largePatches patches, the ratio
/// quadric-implicit / shading there over that of the first shape (flat scaling) and the ratio
/// itself; a FAIL when no shape is that large.
std::vector<TargetCheck> scalingTargets(const std::vector<FigureCell>& cells,
                                        const TargetLimits& limits = {});

/// Per mesh of table 5.1: quadric-param / quadric-implicit memory_bytes.
std::vector<TargetCheck> memoryTargets(const std::vector<ModelMetrics>& rows,
                                       const TargetLimits& limits = {});

/// | target | measured | result | with pass or FAIL.
MarkdownTable targetsTable(const std::vector<TargetCheck>& checks);

/// One "FAIL: TARGET: measured MEASURED" line per missed target.
std::vector<std::string> failLines(const std::vector<TargetCheck>& checks);

/// What to reproduce and where.
struct ReproduceOptions {
  bool full = false;  ///< the scenes' own settings (hours) instead of the quick ones (minutes)
  std::filesystem::path root = ".";              ///< the repository: scenes/thesis/, data/, docs/
  std::filesystem::path out = "docs";            ///< RESULTS.md, images/, results/
  std::filesystem::path work = "out/reproduce";  ///< intermediate files
  std::string command = "quadtri reproduce";     ///< how the run is named in RESULTS.md
  std::string commit = "unknown";                ///< the commit named in RESULTS.md
  int threads = 0;                               ///< render threads, 0: all
  size_t lines = 100000;  ///< random lines per crack rate of the models' measurements
  int levels = 5;         ///< refinement levels of the convergence study
  std::function<void(const std::string&)> log;  ///< progress lines; may be empty
};

struct ReproduceResult {
  std::vector<TargetCheck> targets;
  std::vector<std::filesystem::path> written;
};

/// Every model measured (the former scripts/measure-models.sh): constraint metrics on
/// icospheres 0-4, the torus, genus2 and the teapot, and the convergence study; writes
/// results/models_*.csv, images/convergence.png and results/models.md under options.out.
ReproduceResult measureModels(const ReproduceOptions& options);

/// The whole reproduction (the former scripts/reproduce.sh): figures 5.1-5.6 and 6.2, tables
/// 5.1-5.3, the scaling study, measureModels, every model on the teapot and the torus, the
/// targets; writes RESULTS.md and its images/ and results/ under options.out. Needs
/// data/teapot.obj under options.root (scripts/fetch-teapot.sh).
ReproduceResult reproduce(const ReproduceOptions& options);

}  // namespace quadtri
