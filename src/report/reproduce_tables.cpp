// The reproduction's Markdown tables and target checks (reproduce.h).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "quadtri/math/error.h"
#include "quadtri/report/reproduce.h"

namespace quadtri {
namespace {

std::string formatValue(const std::string& format, double value) {
  return fmt::vformat(format, fmt::make_format_args(value));
}

std::string ratioText(const RatioRange& r) {
  return fmt::format("{:.2f} ({:.2f}-{:.2f})", r.median, r.lo, r.hi);
}

/// Appends `item` to `order` unless it is there already.
void appendOnce(std::vector<std::string>& order, const std::string& item) {
  if (std::find(order.begin(), order.end(), item) == order.end()) order.push_back(item);
}

TargetCheck makeCheck(std::string target, double value, double limit, std::string measured,
                      bool atMost) {
  TargetCheck check;
  check.target = std::move(target);
  check.measured = std::move(measured);
  check.value = value;
  check.limit = limit;
  check.pass = std::isfinite(value) && (atMost ? value <= limit : value >= limit);
  return check;
}

}  // namespace

std::string toMarkdown(const MarkdownTable& table) {
  const size_t columns = table.header.size();
  auto line = [columns](const std::vector<std::string>& cells) {
    std::string out = "|";
    for (size_t i = 0; i < columns; ++i) out += " " + (i < cells.size() ? cells[i] : "") + " |";
    return out + "\n";
  };
  std::string out = line(table.header) + "|";
  for (size_t i = 0; i < columns; ++i) out += i == 0 || !table.rightAligned ? "---|" : "---:|";
  out += "\n";
  for (const auto& row : table.rows) out += line(row);
  return out;
}

const FigureCell* findCell(const std::vector<FigureCell>& cells, const std::string& shape,
                           const std::string& model) {
  for (const FigureCell& c : cells)
    if (c.shape == shape && c.model == model) return &c;
  return nullptr;
}

MarkdownTable figurePivot(const std::vector<FigureCell>& cells,
                          const std::vector<std::string>& models,
                          const std::vector<std::string>& shapes,
                          const std::function<double(const FigureCell&)>& value,
                          const std::string& format) {
  MarkdownTable table;
  table.header.push_back("model");
  table.header.insert(table.header.end(), shapes.begin(), shapes.end());
  for (const std::string& model : models) {
    std::vector<std::string> row{model};
    for (const std::string& shape : shapes) {
      const FigureCell* cell = findCell(cells, shape, model);
      row.push_back(cell ? formatValue(format, value(*cell)) : "-");
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

MarkdownTable ratioTable(const std::vector<FigureCell>& cells,
                         const std::vector<std::string>& models,
                         const std::vector<std::string>& shapes, const std::string& baseline) {
  MarkdownTable table;
  table.header.push_back("model");
  table.header.insert(table.header.end(), shapes.begin(), shapes.end());
  for (const std::string& model : models) {
    if (model == baseline) continue;
    std::vector<std::string> row{model};
    for (const std::string& shape : shapes) {
      const FigureCell* num = findCell(cells, shape, model);
      const FigureCell* den = findCell(cells, shape, baseline);
      row.push_back(num && den ? ratioText(renderTimeRatioRange(*num, *den)) : "-");
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

MarkdownTable scalingTable(const std::vector<FigureCell>& cells, const std::string& baseline,
                           const std::string& middle, const std::string& numerator) {
  MarkdownTable table;
  table.header = {"mesh",
                  "patches",
                  baseline + " (s)",
                  middle + " (s)",
                  numerator + " (s)",
                  "implicit / shading",
                  "implicit / param"};
  for (const FigureCell& num : cells) {
    if (num.model != numerator) continue;
    const FigureCell* base = findCell(cells, num.shape, baseline);
    const FigureCell* mid = findCell(cells, num.shape, middle);
    auto seconds = [](const FigureCell* c) {
      return c ? fmt::format("{:.3f}", c->renderSeconds) : std::string("-");
    };
    auto ratio = [&num](const FigureCell* den) {
      return den ? ratioText(renderTimeRatioRange(num, *den)) : std::string("-");
    };
    table.rows.push_back({num.shape, fmt::format("{}", num.primitives), seconds(base), seconds(mid),
                          seconds(&num), ratio(base), ratio(mid)});
  }
  return table;
}

std::string meshLabel(const std::string& mesh) {
  const std::filesystem::path path(mesh);
  return path.has_parent_path() ? path.stem().string() : mesh;
}

MarkdownTable metricPivot(const std::vector<ModelMetrics>& rows, const std::string& key,
                          const std::string& format, const std::vector<std::string>& models) {
  if (std::find(metricKeys().begin(), metricKeys().end(), key) == metricKeys().end())
    fail("metricPivot: '{}' is not a metric key", key);
  std::vector<std::string> order = models, meshes;
  for (const ModelMetrics& m : rows) {
    if (models.empty()) appendOnce(order, m.model);
    appendOnce(meshes, meshLabel(m.mesh));
  }
  MarkdownTable table;
  table.header.push_back("model");
  table.header.insert(table.header.end(), meshes.begin(), meshes.end());
  for (const std::string& model : order) {
    std::vector<std::string> row{model};
    for (const std::string& mesh : meshes) {
      std::string text = "-";
      for (const ModelMetrics& m : rows)
        if (m.model == model && meshLabel(m.mesh) == mesh) {
          const nlohmann::ordered_json value = toJson(m).at(key);
          if (value.is_number()) {
            const double x = value.get<double>();
            text = x == 0 ? "0" : formatValue(format, x);
          }
        }
      row.push_back(std::move(text));
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

MarkdownTable primitivesTable(const std::vector<ModelMetrics>& rows,
                              const std::vector<std::string>& models) {
  std::vector<std::string> meshes;
  for (const ModelMetrics& m : rows) appendOnce(meshes, meshLabel(m.mesh));
  MarkdownTable table;
  table.header.push_back("model");
  table.header.insert(table.header.end(), meshes.begin(), meshes.end());
  for (const std::string& model : models) {
    std::vector<std::string> row{model};
    for (const std::string& mesh : meshes) {
      std::string text = "-";
      for (const ModelMetrics& m : rows)
        if (m.model == model && meshLabel(m.mesh) == mesh)
          text = fmt::format("{} ({:.1f} KiB)", m.primitives, double(m.memoryBytes) / 1024);
      row.push_back(std::move(text));
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

MarkdownTable metricsMarkdown(const std::vector<ModelMetrics>& rows) {
  MarkdownTable table;
  table.rightAligned = false;
  for (const std::string& key : metricKeys())
    if (key != "mesh" && key != "convert_seconds") table.header.push_back(key);
  for (const ModelMetrics& m : rows) {
    const nlohmann::ordered_json j = toJson(m);
    std::vector<std::string> row;
    for (const std::string& key : table.header) {
      const nlohmann::ordered_json& value = j.at(key);
      if (value.is_string())
        row.push_back(value.get<std::string>());
      else if (value.is_number_integer() || value.is_number_unsigned())
        row.push_back(value.dump());
      else if (value.is_number_float() && std::isfinite(value.get<double>()))
        row.push_back(fmt::format("{:.3g}", value.get<double>()));
      else
        row.push_back("-");
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

TargetCheck checkAtMost(std::string target, double value, double limit, std::string measured) {
  return makeCheck(std::move(target), value, limit, std::move(measured), true);
}

TargetCheck checkAtLeast(std::string target, double value, double limit, std::string measured) {
  return makeCheck(std::move(target), value, limit, std::move(measured), false);
}

std::vector<TargetCheck> renderRatioTargets(const std::vector<FigureCell>& cells,
                                            const std::vector<std::string>& shapes,
                                            const std::string& setup, const TargetLimits& limits) {
  std::vector<TargetCheck> checks;
  for (const std::string& shape : shapes) {
    const std::string target =
        fmt::format("quadric-implicit / shading render time <= {}, setup ({}), {}",
                    limits.renderRatio, setup, shape);
    const FigureCell* num = findCell(cells, shape, "quadric-implicit");
    const FigureCell* den = findCell(cells, shape, "shading");
    if (!num || !den) {
      checks.push_back(checkAtMost(target, NAN, limits.renderRatio, "not rendered"));
      continue;
    }
    const RatioRange r = renderTimeRatioRange(*num, *den);
    checks.push_back(checkAtMost(target, r.median, limits.renderRatio, ratioText(r)));
  }
  return checks;
}

std::vector<TargetCheck> scalingTargets(const std::vector<FigureCell>& cells,
                                        const TargetLimits& limits) {
  std::vector<const FigureCell*> implicit;
  for (const FigureCell& c : cells)
    if (c.model == "quadric-implicit") implicit.push_back(&c);
  std::vector<TargetCheck> checks;
  auto ratioOf = [&cells](const FigureCell& num) {
    const FigureCell* den = findCell(cells, num.shape, "shading");
    return den ? renderTimeRatioRange(num, *den) : RatioRange{NAN, NAN, NAN};
  };
  if (implicit.empty() || implicit.back()->primitives < limits.largePatches) {
    const size_t largest = implicit.empty() ? 0 : implicit.back()->primitives;
    checks.push_back(checkAtLeast(
        fmt::format("flat scaling up to {}+ patches", limits.largePatches), double(largest),
        double(limits.largePatches), fmt::format("largest icosphere has {} patches", largest)));
    if (implicit.empty()) return checks;
  }
  const FigureCell& first = *implicit.front();
  const double base = ratioOf(first).median;
  for (size_t i = 1; i < implicit.size(); ++i) {
    const FigureCell& cell = *implicit[i];
    if (cell.primitives < limits.largePatches) continue;
    const RatioRange r = ratioOf(cell);
    const double growth = base > 0 ? r.median / base : NAN;
    checks.push_back(checkAtMost(
        fmt::format("flat scaling: implicit / shading at {} patches <= {} x that at {} patches",
                    cell.primitives, limits.flatScaling, first.primitives),
        growth, limits.flatScaling,
        fmt::format("{:.2f} / {:.2f} = {:.2f}", r.median, base, growth)));
    checks.push_back(checkAtMost(
        fmt::format("quadric-implicit / shading render time <= {}, also in the scaling scene "
                    "(not a thesis scene), {} patches",
                    limits.renderRatio, cell.primitives),
        r.median, limits.renderRatio, ratioText(r)));
  }
  return checks;
}

std::vector<TargetCheck> memoryTargets(const std::vector<ModelMetrics>& rows,
                                       const TargetLimits& limits) {
  std::vector<std::string> meshes;
  for (const ModelMetrics& m : rows) appendOnce(meshes, m.mesh);
  std::vector<TargetCheck> checks;
  for (const std::string& mesh : meshes) {
    const ModelMetrics *param = nullptr, *implicit = nullptr;
    for (const ModelMetrics& m : rows)
      if (m.mesh == mesh && m.model == "quadric-param")
        param = &m;
      else if (m.mesh == mesh && m.model == "quadric-implicit")
        implicit = &m;
    const std::string target = fmt::format(
        "quadric-implicit geometry >= {}x smaller than the 4802-triangle tessellation "
        "(quadric-param), {}",
        limits.memoryFactor, meshLabel(mesh));
    if (!param || !implicit || implicit->memoryBytes == 0) {
      checks.push_back(checkAtLeast(target, NAN, limits.memoryFactor, "not measured"));
      continue;
    }
    const double factor = double(param->memoryBytes) / double(implicit->memoryBytes);
    checks.push_back(checkAtLeast(
        target, factor, limits.memoryFactor,
        fmt::format("{:.0f}x ({:.1f} KiB against {:.1f} KiB)", factor,
                    double(implicit->memoryBytes) / 1024, double(param->memoryBytes) / 1024)));
  }
  return checks;
}

MarkdownTable targetsTable(const std::vector<TargetCheck>& checks) {
  MarkdownTable table;
  table.header = {"target", "measured: median (range over rounds)", "result"};
  table.rightAligned = false;
  for (const TargetCheck& c : checks)
    table.rows.push_back({c.target, c.measured, c.pass ? "pass" : "FAIL"});
  return table;
}

std::vector<std::string> failLines(const std::vector<TargetCheck>& checks) {
  std::vector<std::string> lines;
  for (const TargetCheck& c : checks)
    if (!c.pass) lines.push_back(fmt::format("FAIL: {}: measured {}", c.target, c.measured));
  return lines;
}

}  // namespace quadtri
