#include "quadtri/report/study.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>

#include "quadtri/io/atomic_file.h"
#include "quadtri/io/csv.h"
#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

bool isMeshFile(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl";
}

// The message of whatever stopped a row.
std::string errorText(const std::exception& e, bool ours) {
  return ours ? std::string(e.what()) : fmt::format("internal error: {}", e.what());
}

// Every row of one mesh: loads it once and measures each model on it.
std::vector<StudyRow> studyMesh(const StudyMesh& entry, const std::vector<std::string>& models,
                                const StudyOptions& options) {
  std::shared_ptr<const TriangleMesh> mesh;
  std::optional<size_t> triangles;
  std::optional<bool> closed;
  std::string loadError;
  try {
    if (!fs::exists(entry.path)) fail("{}: no such file", entry.path.string());
    TriangleMesh loaded = loadMesh(entry.path, options.normals);
    triangles = loaded.triangleCount();
    closed = loaded.topology().isClosed();
    mesh = std::make_shared<const TriangleMesh>(std::move(loaded));
  } catch (const Error& e) {
    loadError = errorText(e, true);
  } catch (const std::exception& e) {
    loadError = errorText(e, false);
  }
  std::vector<StudyRow> rows;
  for (const std::string& model : models) {
    StudyRow row{entry.name, model, triangles, closed, std::nullopt, loadError};
    if (mesh) {
      try {
        row.metrics =
            analyzeNamedModel(model, mesh, entry.name, std::nullopt, options.analysis, {});
      } catch (const Error& e) {
        row.error = errorText(e, true);
      } catch (const std::exception& e) {
        row.error = errorText(e, false);
      }
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

// A number as the summary prints it ("-" if it is not finite, which no metric should be).
std::string number(double x) {
  return std::isfinite(x) ? fmt::format("{:.4g}", x) : "-";
}

// Text for a Markdown table cell: no line breaks, '|' escaped.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n' || c == '\r')
      out += ' ';
    else if (c == '|')
      out += "\\|";
    else
      out += c;
  }
  return out;
}

// "0.0123 (armadillo)", "0" when nothing exceeds zero, "-" when nothing was measured.
std::string worstCell(const std::optional<StudyWorst>& worst) {
  if (!worst) return "-";
  if (worst->value == 0.0) return "0";
  return fmt::format("{} ({})", number(worst->value), cell(worst->mesh));
}

// Keeps the largest finite value and the first mesh that has it.
void raise(std::optional<StudyWorst>& worst, double value, const std::string& mesh) {
  if (std::isfinite(value) && (!worst || value > worst->value)) worst = StudyWorst{value, mesh};
}

// Keeps the smallest finite value and the first mesh that has it.
void lower(std::optional<StudyWorst>& lowest, double value, const std::string& mesh) {
  if (std::isfinite(value) && (!lowest || value < lowest->value)) lowest = StudyWorst{value, mesh};
}

// A lowest share: "1" where every mesh has all of it, else the share and its mesh.
std::string lowestCell(const std::optional<StudyWorst>& lowest) {
  if (!lowest) return "-";
  if (lowest->value == 1.0) return "1";
  return fmt::format("{} ({})", number(lowest->value), cell(lowest->mesh));
}

}  // namespace

std::vector<StudyMesh> readCorpusManifest(const fs::path& manifest, const fs::path& corpus) {
  const CsvTable table = readCsvFile(manifest);
  const std::string where = manifest.string();
  if (table.rows.empty()) fail("{}: empty manifest: expected a header with name and path", where);
  const std::vector<std::string>& header = table.rows.front();
  auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end())
      fail("{}:{}: the header has no column '{}' (it has {})", where, table.line.front(), name,
           fmt::join(header, ", "));
    return size_t(it - header.begin());
  };
  const size_t nameColumn = column("name"), pathColumn = column("path");
  std::vector<StudyMesh> meshes;
  std::map<std::string, size_t> seen;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const std::vector<std::string>& row = table.rows[r];
    const size_t line = table.line[r];
    if (row.size() != header.size())
      fail("{}:{}: {} fields, but the header has {} columns", where, line, row.size(),
           header.size());
    const std::string& name = row[nameColumn];
    const std::string& path = row[pathColumn];
    if (name.empty()) fail("{}:{}: the name is empty", where, line);
    if (path.empty()) fail("{}:{}: mesh '{}' has an empty path", where, line, name);
    if (const auto it = seen.find(name); it != seen.end())
      fail("{}:{}: mesh '{}' is listed twice (first on line {})", where, line, name, it->second);
    seen[name] = line;
    meshes.push_back({name, corpus / path});
  }
  if (meshes.empty()) fail("{}: the manifest lists no mesh", where);
  return meshes;
}

std::vector<StudyMesh> meshesInFolder(const fs::path& folder) {
  if (!fs::is_directory(folder)) fail("{}: not a folder", folder.string());
  std::vector<StudyMesh> meshes;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file() && isMeshFile(it->path()))
      meshes.push_back({fs::relative(it->path(), folder).generic_string(), it->path()});
  if (ec) fail("{}: cannot list the folder ({})", folder.string(), ec.message());
  if (meshes.empty()) fail("{}: no .obj, .off, .ply or .stl file in the folder", folder.string());
  std::sort(meshes.begin(), meshes.end(),
            [](const StudyMesh& a, const StudyMesh& b) { return a.name < b.name; });
  return meshes;
}

std::vector<StudyRow> runStudy(const std::vector<StudyMesh>& meshes, const StudyOptions& options) {
  const std::vector<std::string> models = options.models.empty() ? modelNames() : options.models;
  for (const std::string& model : models)
    if (std::find(modelNames().begin(), modelNames().end(), model) == modelNames().end())
      fail("study: unknown model '{}': expected one of {}", model, fmt::join(modelNames(), ", "));
  if (options.threads < 0)
    fail("study: threads {}: expected 0 (all) or a positive count", options.threads);
  std::vector<size_t> chosen;
  for (size_t i = 0; i < meshes.size(); ++i)
    if (options.shard.holds(i)) chosen.push_back(i);

  std::vector<std::vector<StudyRow>> perMesh(chosen.size());
  std::mutex progressMutex;
  size_t done = 0;
  auto report = [&](const std::string& mesh, bool finished, size_t failed) {
    if (!options.onProgress) return;
    std::lock_guard<std::mutex> lock(progressMutex);
    if (finished) ++done;
    options.onProgress({done, chosen.size(), mesh, finished, failed});
  };
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    parallelForRange(
        tbb::blocked_range<size_t>(0, chosen.size(), 1),
        [&](const tbb::blocked_range<size_t>& range) {
          for (size_t i = range.begin(); i != range.end(); ++i) {
            const StudyMesh& mesh = meshes[chosen[i]];
            report(mesh.name, false, 0);
            perMesh[i] = studyMesh(mesh, models, options);
            const size_t failed =
                size_t(std::count_if(perMesh[i].begin(), perMesh[i].end(),
                                     [](const StudyRow& r) { return !r.error.empty(); }));
            report(mesh.name, true, failed);
          }
        },
        tbb::simple_partitioner());
  });
  std::vector<StudyRow> rows;
  for (std::vector<StudyRow>& r : perMesh)
    for (StudyRow& row : r) rows.push_back(std::move(row));
  return rows;
}

const std::vector<std::string>& studyColumns() {
  static const std::vector<std::string> columns = [] {
    std::vector<std::string> out = {"mesh", "model", "triangles", "closed"};
    for (const std::string& key : metricKeys())
      if (key != "mesh" && key != "model" && key != "triangles") out.push_back(key);
    out.push_back("error");
    return out;
  }();
  return columns;
}

std::string studyCsv(const std::vector<StudyRow>& rows) {
  std::string out = fmt::format("{}\n", fmt::join(studyColumns(), ","));
  for (const StudyRow& row : rows) {
    const nlohmann::ordered_json metrics =
        row.metrics ? toJson(*row.metrics) : nlohmann::ordered_json::object();
    std::vector<std::string> fields;
    for (const std::string& column : studyColumns()) {
      if (column == "mesh")
        fields.push_back(csvField(row.mesh));
      else if (column == "model")
        fields.push_back(csvField(row.model));
      else if (column == "triangles")
        fields.push_back(row.triangles ? std::to_string(*row.triangles) : "");
      else if (column == "closed")
        fields.push_back(row.closed ? (*row.closed ? "yes" : "no") : "");
      else if (column == "error")
        fields.push_back(csvField(row.error));
      else
        fields.push_back(metrics.contains(column) ? csvValue(metrics.at(column)) : "");
    }
    out += fmt::format("{}\n", fmt::join(fields, ","));
  }
  return out;
}

std::vector<ModelSummary> summarizeStudy(const std::vector<StudyRow>& rows) {
  std::vector<ModelSummary> out;
  std::map<std::string, size_t> index;
  std::vector<std::vector<double>> seconds;
  std::vector<double> fallbackSums;
  for (const StudyRow& row : rows) {
    auto [it, added] = index.emplace(row.model, out.size());
    if (added) {
      out.push_back(ModelSummary{});
      out.back().model = row.model;
      seconds.emplace_back();
      fallbackSums.push_back(0.0);
    }
    ModelSummary& s = out[it->second];
    ++s.rows;
    if (!row.metrics) continue;
    const ModelMetrics& m = *row.metrics;
    ++s.measured;
    if (m.crackRate) {
      ++s.closed;
      s.cracking += *m.crackRate > 0.0;
      raise(s.worstCrackRate, *m.crackRate, row.mesh);
    }
    if (m.vertexNormalFlipRateConsistent) {
      ++s.withConsistentCorners;
      s.folding += *m.vertexNormalFlipRateConsistent > 0.0;
      raise(s.worstFoldRate, *m.vertexNormalFlipRateConsistent, row.mesh);
    }
    if (m.vertexNormalErrorConsistentDeg)
      raise(s.worstNormalErrorConsistentDeg, *m.vertexNormalErrorConsistentDeg, row.mesh);
    raise(s.worstFallbackRate, m.fallbackRate, row.mesh);
    if (m.c1AngleSmoothDeg) raise(s.worstC1SmoothDeg, *m.c1AngleSmoothDeg, row.mesh);
    if (m.g1EdgeShare) {
      lower(s.lowestG1EdgeShare, *m.g1EdgeShare, row.mesh);
      s.notG1 += *m.g1EdgeShare < 1.0;
    }
    fallbackSums[it->second] += m.fallbackRate;
    seconds[it->second].push_back(m.convertSeconds);
  }
  for (size_t i = 0; i < out.size(); ++i) {
    ModelSummary& s = out[i];
    if (s.measured == 0) continue;
    s.meanFallbackRate = fallbackSums[i] / double(s.measured);
    std::vector<double>& t = seconds[i];
    std::sort(t.begin(), t.end());
    const size_t n = t.size();
    s.medianConvertSeconds = n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
  }
  return out;
}

std::string studySummaryMarkdown(const std::vector<ModelSummary>& summaries,
                                 const std::vector<StudyRow>& rows, const std::string& what) {
  std::set<std::string> meshes;
  for (const StudyRow& row : rows) meshes.insert(row.mesh);
  std::string out = fmt::format("# quadtri study\n\n{} meshes, {} models. {}\n\n", meshes.size(),
                                summaries.size(), what);
  out +=
      "Rates are fractions. *cracking*: closed meshes with `crack_rate` > 0; *folding*: meshes "
      "with `vertex_normal_flip_rate_consistent` > 0 (patches folding over consistent corners); "
      "a worst value names its mesh. Fallback: `fallback_rate`, the share of patches that gave "
      "up a constraint. G1: `c1_angle_smooth_deg`, the largest normal jump across edges whose "
      "two triangles share both end normals, and `g1_edge_share`, the share of those edges where "
      "it stays below 0.01 degrees.\n\n";
  out +=
      "| model | measured | cracking | worst crack_rate | folding | worst fold rate | worst "
      "fallback_rate | mean fallback_rate | worst vertex_normal_error_consistent_deg | worst "
      "c1_angle_smooth_deg | lowest g1_edge_share | median convert_seconds |\n";
  out += "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ModelSummary& s : summaries) {
    out += fmt::format(
        "| {} | {} of {} | {} of {} | {} | {} of {} | {} | {} | {} | {} | {} | {} | {} |\n",
        cell(s.model), s.measured, s.rows, s.cracking, s.closed, worstCell(s.worstCrackRate),
        s.folding, s.withConsistentCorners, worstCell(s.worstFoldRate),
        worstCell(s.worstFallbackRate), s.meanFallbackRate ? number(*s.meanFallbackRate) : "-",
        worstCell(s.worstNormalErrorConsistentDeg), worstCell(s.worstC1SmoothDeg),
        lowestCell(s.lowestG1EdgeShare),
        s.medianConvertSeconds ? number(*s.medianConvertSeconds) : "-");
  }
  // Failures, one line per mesh and error with the models it stopped.
  std::vector<std::pair<std::pair<std::string, std::string>, std::vector<std::string>>> failures;
  for (const StudyRow& row : rows) {
    if (row.error.empty()) continue;
    const auto key = std::make_pair(row.mesh, row.error);
    if (failures.empty() || failures.back().first != key) failures.push_back({key, {}});
    failures.back().second.push_back(row.model);
  }
  if (!failures.empty()) {
    out += fmt::format("\n## Failures\n\n");
    for (const auto& [key, models] : failures)
      out += fmt::format("- `{}` ({}): {}\n", key.first, fmt::join(models, ", "), cell(key.second));
  }
  return out;
}

std::vector<fs::path> writeStudy(const fs::path& dir, const std::vector<StudyRow>& rows,
                                 const std::string& what) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir))
    fail("{}: cannot create the folder{}", dir.string(), ec ? " (" + ec.message() + ")" : "");
  const fs::path csv = dir / "study.csv", summary = dir / "summary.md";
  writeTextFile(csv, studyCsv(rows));
  writeTextFile(summary, studySummaryMarkdown(summarizeStudy(rows), rows, what));
  return {csv, summary};
}

size_t mergeStudyShards(const std::vector<std::filesystem::path>& shards,
                        const std::filesystem::path& output) {
  if (shards.empty()) fail("merge: no study shards given");
  checkDistinctFiles(shards, output, "study shard");
  std::vector<CsvTable> tables;
  for (const auto& path : shards) {
    tables.push_back(readCsvFile(path));
    if (tables.back().rows.empty()) fail("{}: empty, expected a study.csv", path.string());
  }
  const std::vector<std::string>& header = tables.front().rows.front();
  if (header.empty() || header.front() != "mesh")
    fail("{}: the header does not start with 'mesh': not a study.csv", shards.front().string());
  std::map<std::string, size_t> meshShard;  // mesh -> index of the shard holding its rows
  std::string out = fmt::format("{}\n", fmt::join(header, ","));
  size_t rows = 0;
  for (size_t s = 0; s < tables.size(); ++s) {
    const CsvTable& table = tables[s];
    if (table.rows.front() != header)
      fail("{}: its header differs from {}'s: not shards of one study", shards[s].string(),
           shards.front().string());
    for (size_t r = 1; r < table.rows.size(); ++r) {
      const std::vector<std::string>& row = table.rows[r];
      if (row.size() != header.size())
        fail("{}:{}: {} fields, the header has {}", shards[s].string(), table.line[r], row.size(),
             header.size());
      const auto [it, inserted] = meshShard.emplace(row.front(), s);
      if (!inserted && it->second != s)
        fail("mesh {} has rows in {} and {}: the shards overlap", row.front(),
             shards[it->second].string(), shards[s].string());
      std::vector<std::string> fields;
      for (const std::string& f : row) fields.push_back(csvField(f));
      out += fmt::format("{}\n", fmt::join(fields, ","));
      ++rows;
    }
  }
  writeTextFile(output, out);
  return rows;
}

}  // namespace quadtri
