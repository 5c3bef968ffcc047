// The thesis' chapter 5 reproduction (reproduce.h): renders, measurements, RESULTS.md.
#include "quadtri/report/reproduce.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include "quadtri/analysis/convergence.h"
#include "quadtri/analysis/heatmaps.h"
#include "quadtri/analysis/tessellation_view.h"
#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/model.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

/// The four models of the thesis' tables, checked against the model list.
const std::vector<std::string>& thesisModels() {
  static const std::vector<std::string> models = [] {
    std::vector<std::string> out = {"shading", "quadric-edges", "quadric-param",
                                    "quadric-implicit"};
    for (const std::string& m : out)
      if (std::find(modelNames().begin(), modelNames().end(), m) == modelNames().end())
        fail("reproduce: the thesis model '{}' is not a model", m);
    return out;
  }();
  return models;
}

/// One `quadtri figure` run: a setup's scenes with its settings.
struct FigureRun {
  std::string setup;
  std::vector<std::string> shapes, models;
  int res = 0, spp = 0, repeats = 1;
  SceneDefines defines;

  /// The settings as `quadtri figure` flags, for the text of RESULTS.md.
  std::string flags() const {
    std::string out;
    if (res > 0) out += fmt::format(" --res {}", res);
    if (spp > 0) out += fmt::format(" --spp {}", spp);
    for (const auto& [k, v] : defines) out += fmt::format(" -D {}={}", k, v);
    if (repeats > 1) out += fmt::format(" --repeat {}", repeats);
    return out.empty() ? out : out.substr(1);
  }
};

class Reproduction {
 public:
  explicit Reproduction(const ReproduceOptions& options) : opt_(options) {
    fs::create_directories(opt_.out / "images");
    fs::create_directories(opt_.out / "results");
    fs::create_directories(opt_.work);
    fs::create_directories(opt_.root / "data");
  }

  void log(const std::string& line) const {
    if (opt_.log) opt_.log(line);
  }

  fs::path image(const std::string& name) const { return opt_.out / "images" / name; }
  fs::path result(const std::string& name) const { return opt_.out / "results" / name; }

  void write(const fs::path& path, const std::string& text) {
    writeTextFile(path, text);
    written_.push_back(path);
  }
  void copy(const fs::path& from, const fs::path& to) {
    fs::copy_file(from, to, fs::copy_options::overwrite_existing);
    written_.push_back(to);
  }
  void savePng(const Canvas& canvas, const fs::path& path) {
    canvas.savePng(path);
    written_.push_back(path);
  }

  std::vector<FigureCell> figure(const FigureRun& run, const fs::path& grid, const fs::path& csv) {
    FigureRequest request;
    request.shapes = run.shapes;
    request.models = run.models;
    request.settings.defines = run.defines;
    if (run.spp > 0) {
      request.settings.defines["spp"] = std::to_string(run.spp);
      request.settings.samplesPerPixel = run.spp;
    }
    if (run.res > 0) request.settings.defines["res"] = std::to_string(run.res);
    request.repeats = run.repeats;
    request.settings.threads = opt_.threads;
    const fs::path folder = opt_.root / "scenes" / "thesis";
    const std::string setup = run.setup;
    request.sceneFor = [folder, setup](const std::string& shape) {
      const fs::path perShape = folder / fmt::format("{}-{}.xml", setup, shape);
      const fs::path shared = folder / fmt::format("{}.xml", setup);
      if (fs::is_regular_file(perShape)) return perShape;
      if (fs::is_regular_file(shared)) return shared;
      fail("reproduce: neither {} nor {} exists", perShape.string(), shared.string());
    };
    request.onCell = [this, setup](const FigureCell& c) {
      log(fmt::format("setup {} {:<12} {:<24} render {:.3f} s ({} runs), {} primitives", setup,
                      c.shape, c.model, c.renderSeconds, c.renderTimes.size(), c.primitives));
    };
    std::vector<FigureCell> cells = renderFigureCells(request);
    std::vector<Image> images;
    for (const FigureCell& c : cells) images.push_back(c.image);
    savePng(composeGrid(request.shapes, request.models, images), grid);
    write(csv, figureCsv(setup, cells));
    return cells;
  }

  /// Every model in `models` on one mesh spec or file (a file relative to the root, named as
  /// given); `inspect` sees each model.
  std::vector<ModelMetrics> analyze(
      const std::string& mesh, NormalSource normals, const std::vector<std::string>& models,
      const AnalysisOptions& analysis,
      const std::function<void(const SurfaceModel&, const std::string&)>& inspect = {}) const {
    const bool isFile = fs::path(mesh).has_parent_path();
    const BuiltinMesh input =
        loadMeshSpec(isFile ? (opt_.root / mesh).string() : mesh, NormalOptions(normals));
    const auto shared = std::make_shared<const TriangleMesh>(input.mesh);
    std::vector<ModelMetrics> rows;
    for (const std::string& name : models) {
      std::function<void(const SurfaceModel&)> hook;
      if (inspect) hook = [&](const SurfaceModel& m) { inspect(m, input.description); };
      rows.push_back(analyzeNamedModel(name, shared, mesh, input.truth, analysis, hook));
      log(fmt::format("analyze {} {}", mesh, name));
    }
    return rows;
  }

  const ReproduceOptions& options() const { return opt_; }
  std::vector<fs::path>& written() { return written_; }

 private:
  ReproduceOptions opt_;
  std::vector<fs::path> written_;
};

std::string today() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[16];
  std::strftime(text, sizeof text, "%Y-%m-%d", &utc);
  return text;
}

std::string cpuName() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(": ");
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  return "unknown CPU";
}

unsigned cores() {
  return std::max(1u, std::thread::hardware_concurrency());
}

std::string readFileOr(const fs::path& path, const std::string& fallback) {
  std::ifstream in(path);
  if (!in) return fallback;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

const char* kThesisTable51 = R"(| model | triangle | tetrahedron | icosahedron |
|---|---:|---:|---:|
| shading | 1 | 4 | 20 |
| quadric-edges | 4802 | 19208 | 96040 |
| quadric-param | 4802 | 19208 | 96040 |
| quadric-implicit | 1 | 4 | 20 |
)";

const char* kThesisTable52 = R"(| model | triangle | tetrahedron | icosahedron |
|---|---:|---:|---:|
| shading | 40.17 (1.00) | 43.97 (1.00) | 52.11 (1.00) |
| quadric-edges | 67.46 (1.68) | 93.82 (2.13) | 100.30 (1.92) |
| quadric-param | 72.50 (1.80) | 90.62 (2.06) | 112.14 (2.15) |
| quadric-implicit | 50.21 (1.25) | 71.62 (1.63) | 165.32 (3.17) |
)";

const char* kThesisTable53 = R"(| model | triangle | tetrahedron | icosahedron |
|---|---:|---:|---:|
| shading | 0.2882 (1.00) | 0.6134 (1.00) | 2.0992 (1.00) |
| quadric-edges | 1.6140 (5.60) | 5.3269 (8.68) | 7.7267 (3.68) |
| quadric-param | 1.7650 (6.12) | 3.5300 (5.75) | 6.6993 (3.19) |
| quadric-implicit | 1.4336 (4.97) | 3.4404 (5.61) | 10.6203 (5.06) |
)";

std::string modelsMarkdown(const ReproduceOptions& o, const std::vector<ModelMetrics>& metrics,
                           const std::string& convShapes, const std::string& orders,
                           double seconds) {
  std::string triangles;
  std::vector<std::string> seen;
  for (const ModelMetrics& m : metrics)
    if (std::find(seen.begin(), seen.end(), m.mesh) == seen.end()) {
      seen.push_back(m.mesh);
      triangles +=
          fmt::format("{}{} {}", triangles.empty() ? "" : ", ", meshLabel(m.mesh), m.triangles);
    }
  auto pivot = [&metrics](const char* key, const char* format) {
    return toMarkdown(metricPivot(metrics, key, format));
  };
  std::string md = fmt::format(
      R"(## Every model measured

Generated by `{} --lines {} --levels {}` on {}
at commit `{}` in {:.0f} s on
{} cores. CSVs: [models_metrics.csv](results/models_metrics.csv) (`quadtri analyze MESH
--csv`), [models_convergence.csv](results/models_convergence.csv) and
[models_orders.csv](results/models_orders.csv) (`quadtri convergence`).

Meshes (triangles): {}. Icospheres, torus (32×16) and genus2 (the built-in genus-2
pretzel, marching tetrahedra on 24 cells: irregular triangles, slivers, saddles) carry their true
surface's normals; the teapot (npm `teapot`, open) carries thesis eq. 2.8 normals
(`--normals average`) and has no crack rate. Metrics as docs/DESIGN.md §4 defines them; distances
are relative to the mean edge length, 0 where a value is exactly zero.

)",
      o.command, o.lines, o.levels, today(), o.commit, seconds, cores(), triangles);
  md += fmt::format("### crack_rate ({} random lines; closed meshes only)\n\n{}\n", o.lines,
                    pivot("crack_rate", "{:.2g}"));
  md += fmt::format(
      "### c0_gap (max gap between the two patches of an edge / mean edge length)\n\n{}\n",
      pivot("c0_gap", "{:.2g}"));
  md += fmt::format(
      "### c1_angle_deg (max angle between the two patches' normals along an edge)\n\n{}\n",
      pivot("c1_angle_deg", "{:.3g}"));
  md += fmt::format("### vertex_position_error (max corner miss / mean edge length)\n\n{}\n",
                    pivot("vertex_position_error", "{:.2g}"));
  md += fmt::format("### vertex_normal_error_deg (max corner normal miss, degrees)\n\n{}\n",
                    pivot("vertex_normal_error_deg", "{:.3g}"));
  md += fmt::format(
      "### truth_distance (max distance to the true surface / the shape's size)\n\n{}\n",
      pivot("truth_distance", "{:.2g}"));
  md += fmt::format(
      R"(### Convergence to the true surface

truth_distance against triangles under refinement (`quadtri convergence --shapes {}
--levels {}`: icosphere levels 0-{}, the ellipsoid's subdivision levels 0-{},
torus 8·2^L × 4·2^L, genus2 on 16·2^L cells; a shape stops at its first level over 45,000
triangles: `--max-triangles 45000`), every model:

![convergence](images/convergence.png)

Observed order p of truth_distance ≈ C h^p in the mean edge length h (least squares over the
three finest levels; "exact": every distance below 1e-10, round-off):

{})",
      convShapes, o.levels, o.levels, o.levels, orders);
  return md;
}

/// Both runs measure the teapot, which only scripts/fetch-teapot.sh (node/npm) writes.
void requireTeapot(const fs::path& root) {
  if (!fs::is_regular_file(root / "data" / "teapot.obj"))
    fail("reproduce: {} is missing (scripts/fetch-teapot.sh writes it)",
         (root / "data" / "teapot.obj").string());
}

}  // namespace

ReproduceResult measureModels(const ReproduceOptions& options) {
  requireTeapot(options.root);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  Reproduction r(options);
  AnalysisOptions analysis;
  analysis.crack.lines = options.lines;
  std::vector<ModelMetrics> metrics;
  for (const char* mesh : {"icosphere:0", "icosphere:1", "icosphere:2", "icosphere:3",
                           "icosphere:4", "torus", "genus2", "data/teapot.obj"}) {
    const bool teapot = std::string(mesh) == "data/teapot.obj";
    for (ModelMetrics& m : r.analyze(mesh, teapot ? NormalSource::Average : NormalSource::File,
                                     modelNames(), analysis))
      metrics.push_back(std::move(m));
  }
  r.write(r.result("models_metrics.csv"), metricsCsv(metrics));

  const std::vector<std::string> shapes = {"icosphere", "ellipsoid:1,0.7,0.5", "torus:1,0.35",
                                           "genus2"};
  ConvergenceOptions convergence;
  convergence.levels = options.levels;
  convergence.maxTriangles = 45000;
  convergence.onError = [&r](const ConvergenceSample& s, const std::string& error) {
    r.log(fmt::format("warning: {} level {}, model {}: not measured: {}", s.shape, s.level, s.model,
                      error));
  };
  const std::vector<ConvergenceSample> samples =
      convergenceStudy(shapes, modelNames(), convergence);
  const std::vector<ConvergenceOrder> orders = convergenceOrders(samples);
  r.savePng(convergencePlot(samples), r.image("convergence.png"));
  r.write(r.result("models_convergence.csv"), convergenceCsv(samples));
  r.write(r.result("models_orders.csv"), ordersCsv(orders));
  std::string convShapes;
  for (const std::string& s : shapes) convShapes += (convShapes.empty() ? "" : ",") + s;
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  r.write(r.result("models.md"),
          modelsMarkdown(options, metrics, convShapes, ordersMarkdown(orders), seconds));
  return {{}, r.written()};
}

ReproduceResult reproduce(const ReproduceOptions& options) {
  requireTeapot(options.root);
  Reproduction r(options);
  const fs::path& root = options.root;
  const int levels = 7;
  for (int l = 0; l <= levels; ++l) {
    const fs::path path = root / "data" / fmt::format("icosphere-{}.obj", l);
    if (!fs::exists(path) || fs::file_size(path) == 0)
      saveMesh(loadMeshSpec(fmt::format("icosphere:{}", l)).mesh, path);
  }
  const std::vector<std::string>& models = thesisModels();
  const std::vector<std::string> shapes = {"triangle", "tetrahedron", "icosahedron", "teapot"};
  // Figures 5.1 and 5.2 get a quadric-g1 column beside the thesis' models (its tables keep
  // the thesis' four).
  std::vector<std::string> figureModels = models;
  figureModels.push_back("quadric-g1");
  FigureRun a{"a", shapes, figureModels, 0, 0, 3, {}}, b{"b", shapes, figureModels, 0, 0, 3, {}};
  FigureRun scaling{"scaling", {}, {"shading", "quadric-param", "quadric-implicit"}, 0, 0, 5, {}};
  for (int l = 0; l <= levels; ++l) scaling.shapes.push_back(fmt::format("icosphere-{}", l));
  FigureRun everyA{"a", {"teapot", "torus"}, modelNames(), 0, 0, 1, {}}, everyB = everyA;
  everyB.setup = "b";
  std::vector<std::string> tableShapes = {"triangle", "tetrahedron", "icosahedron"};
  if (!options.full) {
    a.res = 96, a.spp = 32;
    b.res = 88, b.defines["spp"] = "64";
    everyA.res = 160, everyA.spp = 32;
    everyB.res = 128, everyB.defines["spp"] = "64";
    scaling.res = 128, scaling.spp = 16;
  } else {
    tableShapes.push_back("data/teapot.obj");
  }

  // Figures 5.1 and 5.2 with the render times of tables 5.2 and 5.3; figure 5.5 extended.
  const auto cellsA = r.figure(a, r.image("fig5_1_diffuse.png"), r.result("times_a.csv"));
  const auto cellsB = r.figure(b, r.image("fig5_2_glass.png"), r.result("times_b.csv"));
  const auto cellsS =
      r.figure(scaling, options.work / "scaling_grid.png", r.result("times_scaling.csv"));
  r.savePng(renderTimeRatioPlot(cellsS, scaling.models, "scaling"), r.image("fig5_5_ratio.png"));

  // Figures 5.3 and 5.4: corners-only and 2500-point tessellations of the parametric models.
  for (const std::string s : {"tetrahedron", "icosahedron"}) {
    const fs::path views = options.work / ("views-" + s);
    const auto mesh = std::make_shared<const TriangleMesh>(loadMeshSpec(s).mesh);
    for (const std::string m : {"quadric-edges", "quadric-param"}) {
      writeTessellationViews(*makeModel(m, mesh), views);
      for (const std::string k : {"corners", "2500"})
        r.copy(views / fmt::format("{}-view-{}.png", m, k),
               r.image(fmt::format("fig5_3_4_{}-{}-{}.png", s, m, k)));
    }
  }

  // Table 5.1 (thesis tessellation) and the constraint metrics, with figures 5.6 and 6.2.
  AnalysisOptions thesis;
  thesis.tessellation = Tessellation::thesis();
  thesis.crack.lines = 200;
  std::vector<ModelMetrics> primitives;
  for (const std::string& s : tableShapes) {
    const NormalSource normals =
        s == "data/teapot.obj" ? NormalSource::Average : NormalSource::File;
    for (ModelMetrics& m : r.analyze(s, normals, modelNames(), thesis))
      primitives.push_back(std::move(m));
  }
  r.write(r.result("primitives.csv"), metricsCsv(primitives));
  auto heatmaps = [](const fs::path& dir, int width) {
    return [dir, width](const SurfaceModel& model, const std::string& label) {
      if (model.name() == "quadric-implicit") writeHeatmaps(model, dir, label, width);
    };
  };
  const fs::path heatIco = options.work / "heat-icosahedron",
                 heatTeapot = options.work / "heat-teapot";
  const auto icosahedron =
      r.analyze("icosahedron", NormalSource::File, modelNames(), {}, heatmaps(heatIco, 800));
  r.write(r.result("icosahedron_metrics.csv"), metricsCsv(icosahedron));
  const auto teapot = r.analyze("data/teapot.obj", NormalSource::Average, modelNames(), {},
                                heatmaps(heatTeapot, 640));
  r.write(r.result("teapot_metrics.csv"), metricsCsv(teapot));
  for (const std::string f : {"residual", "normal-misfit"}) {
    r.copy(heatIco / fmt::format("quadric-implicit-{}.png", f),
           r.image(fmt::format("fig5_6_icosahedron-{}.png", f)));
    r.copy(heatTeapot / fmt::format("quadric-implicit-{}.png", f),
           r.image(fmt::format("fig6_2_teapot-{}.png", f)));
  }

  const ReproduceResult measured = measureModels(options);
  r.written().insert(r.written().end(), measured.written.begin(), measured.written.end());
  // Every model on the teapot and the torus.
  r.figure(everyA, r.image("models_a.png"), r.result("models_times_a.csv"));
  r.figure(everyB, r.image("models_b.png"), r.result("models_times_b.csv"));

  ReproduceResult result;
  for (auto* part : {&cellsA, &cellsB}) {
    const auto checks = renderRatioTargets(*part, shapes, part == &cellsA ? "a" : "b");
    result.targets.insert(result.targets.end(), checks.begin(), checks.end());
  }
  for (const auto& checks : {scalingTargets(cellsS), memoryTargets(primitives)})
    result.targets.insert(result.targets.end(), checks.begin(), checks.end());

  auto seconds = [](const FigureCell& c) { return c.renderSeconds; };
  auto spp = [](const FigureCell& c) { return c.meanSamplesPerPixel; };
  std::string md = fmt::format(
      R"(# Reproducing the thesis' results

Generated by `{} --{}` on {} at commit
`{}`, on {} cores of a
{} (a machine shared with other jobs: single renders scatter by tens of percent, so every
ratio below is the median of side-by-side ratios over several rounds, with their range).
The CSVs behind every table are in [results/](results/). The thesis' numbers come from its
chapter 5 (Mitsuba 0.5 on an i5 4690k, 64 spp and 500 spp at its own, unstated resolution);
only ratios between models can be compared, not absolute times.

## Figure 5.1: diffuse objects, point light (setup a)

![figure 5.1](images/fig5_1_diffuse.png)

## Figure 5.2: glass objects, area light, adaptive sampling (setup b)

![figure 5.2](images/fig5_2_glass.png)

## Table 5.1: primitives per model (thesis tessellation, 4802 triangles per patch)

quadtri (`quadtri analyze SHAPE --tessellation thesis --csv`; in brackets the geometry memory):

{}
Thesis:

{}
## Table 5.2: render time, setup (a)

quadtri, seconds (`quadtri figure --setup a {}`; render only, the
acceleration structure's build is in build_s of the CSV):

{}
Ratio to `shading`, quadtri: the median over the rounds of the ratio of renders done side by
side, and its range over the rounds:

{}
Thesis, seconds, and ratio to shading:

{}
## Table 5.3: render time, setup (b)

quadtri, seconds (`quadtri figure --setup b {}`):

{}
Mean samples per pixel the adaptive integrator took:

{}
Ratio to `shading`, quadtri (median over rounds, and range):

{}
Thesis, hours, and ratio to shading:

{}
)",
      options.command, options.full ? "full" : "quick", today(), options.commit, cores(), cpuName(),
      toMarkdown(primitivesTable(primitives, models)), kThesisTable51, a.flags(),
      toMarkdown(figurePivot(cellsA, models, shapes, seconds, "{:.2f}")),
      toMarkdown(ratioTable(cellsA, models, shapes)), kThesisTable52, b.flags(),
      toMarkdown(figurePivot(cellsB, models, shapes, seconds, "{:.2f}")),
      toMarkdown(figurePivot(cellsB, models, shapes, spp, "{:.1f}")),
      toMarkdown(ratioTable(cellsB, models, shapes)), kThesisTable53);
  md += fmt::format(
      R"(## Figure 5.5 extended: render-time ratio as the patches grow

![figure 5.5](images/fig5_5_ratio.png)

`quadtri figure --setup scaling --shapes icosphere-0..{} --models shading,quadric-param,quadric-implicit {} --ratio-plot ...`
(quadric-param tessellated at the scene default, lattice level 8 = 64 triangles per patch;
times are medians of the rounds, ratios the median of per-round ratios, range in brackets):

{}
The thesis' figure 5.5 has two points per setup: quadric-param (4802 triangles per patch) /
quadric-implicit fell from 1.444 with one patch to 0.678 with 20 patches.

## Speed and memory targets

Render-time ratios are side by side (same round), medians over the rounds; memory from table 5.1.

{}
)",
      levels, scaling.flags(), toMarkdown(scalingTable(cellsS)),
      toMarkdown(targetsTable(result.targets)));
  md +=
      R"(## Figures 5.3 and 5.4: the parametric models at corners-only and 2500-point tessellations

`quadtri analyze SHAPE --heatmaps DIR` (`MODEL-view-corners.png`, `MODEL-view-2500.png`):
normal as colour (each component mapped from its range over the model, thesis §5.2), patch
boundaries and silhouette in black. With the 3 corner points per patch (figure 5.3) the
tessellation is the input mesh (constraints 1 and 2); with the thesis' 50x50 = 2500 points
(figure 5.4) the patches bulge and meet without gaps (constraint 3), the normal is continuous at
the vertices but kinks across the edges (constraint 4 holds at the vertices only).

| | tetrahedron, quadric-edges | tetrahedron, quadric-param | icosahedron, quadric-edges | icosahedron, quadric-param |
|---|---|---|---|---|
| corners only (5.3) | ![](images/fig5_3_4_tetrahedron-quadric-edges-corners.png) | ![](images/fig5_3_4_tetrahedron-quadric-param-corners.png) | ![](images/fig5_3_4_icosahedron-quadric-edges-corners.png) | ![](images/fig5_3_4_icosahedron-quadric-param-corners.png) |
| 2500 points (5.4) | ![](images/fig5_3_4_tetrahedron-quadric-edges-2500.png) | ![](images/fig5_3_4_tetrahedron-quadric-param-2500.png) | ![](images/fig5_3_4_icosahedron-quadric-edges-2500.png) | ![](images/fig5_3_4_icosahedron-quadric-param-2500.png) |

## Figures 5.6 and 6.2: the implicit model against its parametric patch

Per patch (patches laid out in cells, corner 0 bottom left), (f_i o f_p)(u, v) / |grad f_i|
divided by the mean edge length, and |n_p x n_i|, for `quadric-implicit`
(`quadtri analyze icosahedron --heatmaps DIR`, `quadtri analyze data/teapot.obj --normals average --model quadric-implicit --heatmaps DIR`).

Figure 5.6, icosahedron:

![figure 5.6a](images/fig5_6_icosahedron-residual.png)
![figure 5.6b](images/fig5_6_icosahedron-normal-misfit.png)

Figure 6.2, teapot:

![figure 6.2a](images/fig6_2_teapot-residual.png)
![figure 6.2b](images/fig6_2_teapot-normal-misfit.png)

)";
  md += fmt::format(
      R"(## Constraint metrics (icosahedron, `quadtri analyze icosahedron --csv`)

{}
## Teapot (`quadtri analyze data/teapot.obj --normals average --csv`)

{}
## Every model on the teapot and the torus

Setups (a) and (b) as above (`quadtri figure --shapes teapot,torus --models all eleven`),
the torus a coarse 24×12 one (576 triangles) so that facets, terminators and cracks show.

![every model, setup (a)](images/models_a.png)
![every model, setup (b)](images/models_b.png)

)",
      toMarkdown(metricsMarkdown(icosahedron)), toMarkdown(metricsMarkdown(teapot)));
  md += readFileOr(options.out / "results" / "models.md", "") + "\n";
  md += readFileOr(root / "docs" / "results-discussion.md", "");
  r.write(options.out / "RESULTS.md", md);
  result.written = r.written();
  return result;
}

}  // namespace quadtri
