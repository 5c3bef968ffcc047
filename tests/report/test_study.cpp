// `quadtri study` over a folder of small meshes: its rows, its CSV, its summary and its shards.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "quadtri/io/csv.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/report/study.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

// A temporary folder with two built-in meshes written as OBJ and one corrupt OBJ (a face that
// uses vertex 9 of 3), removed at the end.
struct StudyFolder {
  fs::path dir;
  StudyFolder() {
    dir = fs::temp_directory_path() /
          fmt::format("quadtri_study_{}",
                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    saveMesh(makeBuiltin("icosahedron").mesh, dir / "ico.obj");
    saveMesh(parseBuiltinSpec("torus:1,0.35,12,6")->mesh, dir / "torus.obj");
    std::ofstream(dir / "broken.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
    std::ofstream(dir / "notes.txt") << "not a mesh\n";
  }
  ~StudyFolder() { fs::remove_all(dir); }
};

StudyOptions quickOptions() {
  StudyOptions options;
  options.analysis.crack.lines = 3000;
  options.analysis.crack.seed = 5;
  options.threads = 2;
  return options;
}

// A row without its conversion time (the one figure that differs between runs).
std::string rowKey(const StudyRow& row) {
  nlohmann::ordered_json j = row.metrics ? toJson(*row.metrics) : nlohmann::ordered_json();
  if (row.metrics) j.erase("convert_seconds");
  return fmt::format("{}|{}|{}|{}|{}|{}", row.mesh, row.model, row.triangles.value_or(0),
                     row.closed.value_or(false), j.dump(), row.error);
}

TEST(Study, FolderRowsCsvAndSummaryAgreeWithAnalyze) {
  const StudyFolder folder;
  const std::vector<StudyMesh> meshes = meshesInFolder(folder.dir);
  ASSERT_EQ(meshes.size(), 3u);
  EXPECT_EQ(meshes[0].name, "broken.obj");
  EXPECT_EQ(meshes[1].name, "ico.obj");
  EXPECT_EQ(meshes[2].name, "torus.obj");

  StudyOptions options = quickOptions();
  size_t started = 0, finished = 0, lastDone = 0;
  options.onProgress = [&](const StudyProgress& p) {
    EXPECT_EQ(p.total, 3u);
    (p.finished ? finished : started) += 1;
    lastDone = std::max(lastDone, p.done);
    if (p.finished) {
      EXPECT_EQ(p.failedModels, p.mesh == "broken.obj" ? modelNames().size() : 0u) << p.mesh;
    }
  };
  const std::vector<StudyRow> rows = runStudy(meshes, options);
  EXPECT_EQ(started, 3u);
  EXPECT_EQ(finished, 3u);
  EXPECT_EQ(lastDone, 3u);
  const size_t M = modelNames().size();
  ASSERT_EQ(rows.size(), 3 * M);
  for (size_t i = 0; i < rows.size(); ++i) {
    const StudyRow& row = rows[i];
    EXPECT_EQ(row.mesh, meshes[i / M].name);
    EXPECT_EQ(row.model, modelNames()[i % M]);
    if (i < M) {
      // The corrupt file's rows carry the loader's error, which names the file and line.
      EXPECT_FALSE(row.metrics);
      EXPECT_FALSE(row.triangles);
      EXPECT_NE(row.error.find("broken.obj"), std::string::npos) << row.error;
      EXPECT_NE(row.error.find(":4"), std::string::npos) << row.error;
      EXPECT_EQ(row.error, rows[0].error);
    } else {
      EXPECT_EQ(row.error, "") << row.mesh << " " << row.model;
      ASSERT_TRUE(row.metrics);
      EXPECT_EQ(*row.closed, true);
      EXPECT_EQ(*row.triangles, i < 2 * M ? 20u : 144u);
    }
  }

  // Each measured row is what analyze measures for that mesh and model.
  std::map<std::pair<std::string, std::string>, ModelMetrics> analyzed;
  for (const char* file : {"ico.obj", "torus.obj"}) {
    const auto mesh = std::make_shared<const TriangleMesh>(loadMesh(folder.dir / file));
    for (const std::string& model : modelNames()) {
      analyzed[{file, model}] =
          analyzeNamedModel(model, mesh, file, std::nullopt, options.analysis);
      nlohmann::ordered_json expected = toJson(analyzed[{file, model}]);
      const StudyRow& row = rows[(std::string(file) == "ico.obj" ? 1 : 2) * M +
                                 size_t(std::find(modelNames().begin(), modelNames().end(), model) -
                                        modelNames().begin())];
      nlohmann::ordered_json got = toJson(*row.metrics);
      expected.erase("convert_seconds");
      got.erase("convert_seconds");
      EXPECT_EQ(got, expected) << file << " " << model;
    }
  }

  // The summary's figures are those values.
  const std::vector<ModelSummary> summaries = summarizeStudy(rows);
  ASSERT_EQ(summaries.size(), M);
  for (const ModelSummary& s : summaries) {
    const ModelMetrics& a = analyzed[{"ico.obj", s.model}];
    const ModelMetrics& b = analyzed[{"torus.obj", s.model}];
    EXPECT_EQ(s.rows, 3u);
    EXPECT_EQ(s.measured, 2u);
    EXPECT_EQ(s.closed, 2u);
    EXPECT_EQ(s.cracking, size_t(*a.crackRate > 0) + size_t(*b.crackRate > 0)) << s.model;
    ASSERT_TRUE(s.worstCrackRate && s.worstFoldRate && s.worstFallbackRate &&
                s.worstNormalErrorConsistentDeg && s.meanFallbackRate && s.medianConvertSeconds);
    EXPECT_EQ(s.worstCrackRate->value, std::max(*a.crackRate, *b.crackRate)) << s.model;
    EXPECT_EQ(s.worstCrackRate->mesh, *b.crackRate > *a.crackRate ? "torus.obj" : "ico.obj");
    EXPECT_EQ(s.withConsistentCorners, 2u);
    EXPECT_EQ(s.folding, size_t(*a.vertexNormalFlipRateConsistent > 0) +
                             size_t(*b.vertexNormalFlipRateConsistent > 0));
    EXPECT_EQ(s.worstFoldRate->value,
              std::max(*a.vertexNormalFlipRateConsistent, *b.vertexNormalFlipRateConsistent));
    EXPECT_EQ(s.worstFallbackRate->value, std::max(a.fallbackRate, b.fallbackRate));
    EXPECT_EQ(*s.meanFallbackRate, (a.fallbackRate + b.fallbackRate) / 2.0);
    EXPECT_EQ(s.worstNormalErrorConsistentDeg->value,
              std::max(*a.vertexNormalErrorConsistentDeg, *b.vertexNormalErrorConsistentDeg));
    // Two measured meshes: the median is the mean of their two conversion times.
    const StudyRow* r[2] = {nullptr, nullptr};
    for (const StudyRow& row : rows)
      if (row.model == s.model && row.metrics) (r[0] ? r[1] : r[0]) = &row;
    EXPECT_EQ(*s.medianConvertSeconds,
              0.5 * (std::min(r[0]->metrics->convertSeconds, r[1]->metrics->convertSeconds) +
                     std::max(r[0]->metrics->convertSeconds, r[1]->metrics->convertSeconds)));
  }
  // The thesis' implicit model cracks the icosahedron (README: crack_rate 0.14).
  const auto implicit = std::find_if(summaries.begin(), summaries.end(), [](const ModelSummary& s) {
    return s.model == "quadric-implicit";
  });
  EXPECT_GE(implicit->cracking, 1u);
  EXPECT_GT(implicit->worstCrackRate->value, 0.05);

  // study.csv and summary.md, written atomically into a new folder.
  const fs::path out = folder.dir / "out" / "nested";
  const std::vector<fs::path> written = writeStudy(out, rows, "Test run.");
  ASSERT_EQ(written.size(), 2u);
  const CsvTable csv = readCsvFile(out / "study.csv");
  ASSERT_EQ(csv.rows.size(), 1 + rows.size());
  EXPECT_EQ(csv.rows[0], studyColumns());
  const std::vector<std::string>& columns = studyColumns();
  auto column = [&](const std::string& name) {
    return size_t(std::find(columns.begin(), columns.end(), name) - columns.begin());
  };
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::vector<std::string>& line = csv.rows[i + 1];
    ASSERT_EQ(line.size(), columns.size());
    EXPECT_EQ(line[column("mesh")], rows[i].mesh);
    EXPECT_EQ(line[column("model")], rows[i].model);
    EXPECT_EQ(line[column("error")], rows[i].error);
    EXPECT_EQ(line[column("closed")], rows[i].closed ? "yes" : "");
    if (rows[i].metrics) {
      EXPECT_EQ(std::stod(line[column("crack_rate")]), *rows[i].metrics->crackRate);
      EXPECT_EQ(std::stod(line[column("fallback_rate")]), rows[i].metrics->fallbackRate);
      EXPECT_EQ(line[column("truth_distance")], "");  // files have no true surface
    } else {
      EXPECT_EQ(line[column("crack_rate")], "");
      EXPECT_EQ(line[column("triangles")], "");
    }
  }
  std::ifstream summaryFile(out / "summary.md");
  const std::string summary((std::istreambuf_iterator<char>(summaryFile)),
                            std::istreambuf_iterator<char>());
  EXPECT_NE(summary.find("3 meshes, 12 models. Test run."), std::string::npos);
  const std::string implicitLine =
      fmt::format("| quadric-implicit | 2 of 3 | {} of 2 | {:.4g} ({}) |", implicit->cracking,
                  implicit->worstCrackRate->value, implicit->worstCrackRate->mesh);
  EXPECT_NE(summary.find(implicitLine), std::string::npos) << summary;
  EXPECT_NE(summary.find("- `broken.obj` (flat, shading,"), std::string::npos) << summary;
  for (const fs::directory_entry& e : fs::directory_iterator(out))
    EXPECT_TRUE(e.path().filename() == "study.csv" || e.path().filename() == "summary.md")
        << e.path();
}

TEST(Study, ShardsPartitionTheRows) {
  const StudyFolder folder;
  const std::vector<StudyMesh> meshes = meshesInFolder(folder.dir);
  StudyOptions options = quickOptions();
  options.models = {"quadric-implicit", "flat", "nagata"};
  const std::vector<StudyRow> all = runStudy(meshes, options);
  ASSERT_EQ(all.size(), 9u);
  EXPECT_EQ(all[0].model, "quadric-implicit");
  EXPECT_EQ(all[1].model, "flat");
  std::multiset<std::string> expected, got;
  for (const StudyRow& row : all) expected.insert(rowKey(row));
  std::vector<std::set<std::string>> shardMeshes(2);
  for (size_t shard = 1; shard <= 2; ++shard) {
    options.shard = StudyShard::parse(fmt::format("{}/2", shard));
    options.threads = int(shard);  // the thread count changes nothing either
    for (const StudyRow& row : runStudy(meshes, options)) {
      got.insert(rowKey(row));
      shardMeshes[shard - 1].insert(row.mesh);
    }
  }
  EXPECT_EQ(got, expected);
  // Mesh indices 0 and 2 in shard 1/2, index 1 in shard 2/2.
  EXPECT_EQ(shardMeshes[0], (std::set<std::string>{"broken.obj", "torus.obj"}));
  EXPECT_EQ(shardMeshes[1], (std::set<std::string>{"ico.obj"}));
}

// `quadtri merge s1/study.csv s2/study.csv -o study.csv`: the shards' rows in one file, each
// mesh once; shards that overlap or are of another table are refused, writing nothing.
TEST(Study, ShardCsvsMergeIntoTheWholeStudysRows) {
  const StudyFolder folder;
  const std::vector<StudyMesh> meshes = meshesInFolder(folder.dir);
  StudyOptions options = quickOptions();
  options.models = {"flat", "nagata"};
  std::multiset<std::pair<std::string, std::string>> expected, got;
  for (const StudyRow& row : runStudy(meshes, options)) expected.insert({row.mesh, row.model});
  std::vector<fs::path> shards;
  for (size_t shard = 1; shard <= 2; ++shard) {
    options.shard = StudyShard::parse(fmt::format("{}/2", shard));
    const fs::path dir = folder.dir / fmt::format("out{}", shard);
    writeStudy(dir, runStudy(meshes, options), "shard");
    shards.push_back(dir / "study.csv");
  }
  const fs::path merged = folder.dir / "merged.csv";
  EXPECT_EQ(mergeStudyShards(shards, merged), expected.size());
  const CsvTable table = readCsvFile(merged);
  ASSERT_EQ(table.rows.size(), expected.size() + 1);
  EXPECT_EQ(table.rows[0], readCsvFile(shards[0]).rows[0]);
  for (size_t r = 1; r < table.rows.size(); ++r) got.insert({table.rows[r][0], table.rows[r][1]});
  EXPECT_EQ(got, expected);

  const fs::path refused = folder.dir / "refused.csv";
  try {
    mergeStudyShards({shards[0], shards[1], shards[0]}, refused);
    ADD_FAILURE() << "a shard given twice merged";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find(shards[0].string() + ": given twice (study shards 1 and 3)"),
        std::string::npos)
        << e.what();
  }
  // A copy of a shard under another name holds the same meshes' rows.
  const fs::path copy = folder.dir / "copy.csv";
  fs::copy_file(shards[0], copy);
  try {
    mergeStudyShards({shards[0], shards[1], copy}, refused);
    ADD_FAILURE() << "overlapping shards merged";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find("has rows in " + shards[0].string() + " and " + copy.string()),
        std::string::npos)
        << e.what();
  }
  // The output may not be one of the shards: it would be replaced while read.
  const auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string before = bytes(shards[1]);
  try {
    mergeStudyShards({shards[0], shards[1]}, shards[1]);
    ADD_FAILURE() << "merged onto a shard";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the output is also an input (study shard 2)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(bytes(shards[1]), before);
  std::ofstream(folder.dir / "other.csv") << "mesh,something\nico.obj,1\n";
  EXPECT_THROW(mergeStudyShards({shards[0], folder.dir / "other.csv"}, refused), Error);
  EXPECT_FALSE(fs::exists(refused));
}

TEST(Study, ShardAndModelErrors) {
  EXPECT_EQ(StudyShard::parse("3/4").index, 3u);
  for (const char* bad : {"0/2", "3/2", "1", "a/b", "1/0", "/2", "1/"}) {
    try {
      StudyShard::parse(bad);
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()),
                fmt::format("--shard {}: expected I/N with 1 <= I <= N, e.g. 2/4", bad));
    }
  }
  StudyOptions options;
  options.models = {"flat", "bogus"};
  EXPECT_THROW(runStudy({}, options), Error);
}

TEST(Study, ManifestNamesItsMeshesAndItsErrors) {
  const StudyFolder folder;
  const fs::path manifest = folder.dir / "manifest.csv";
  std::ofstream(manifest)
      << "name,path,source,licence,triangles,vertices,closed,manifold,file_normals,kind\n"
         "icosahedron,ico.obj,built-in,CC0,20,12,yes,yes,yes,organic\n"
         "missing,sub/none.off,nowhere,CC0,1,3,no,yes,no,mechanical\n";
  const std::vector<StudyMesh> meshes = readCorpusManifest(manifest, folder.dir);
  ASSERT_EQ(meshes.size(), 2u);
  EXPECT_EQ(meshes[0].name, "icosahedron");
  EXPECT_EQ(meshes[0].path, folder.dir / "ico.obj");
  StudyOptions options = quickOptions();
  options.models = {"shading"};
  const std::vector<StudyRow> rows = runStudy(meshes, options);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_TRUE(rows[0].metrics);
  EXPECT_EQ(rows[1].error, (folder.dir / "sub/none.off").string() + ": no such file");

  auto manifestError = [&](const std::string& text) {
    std::ofstream(manifest) << text;
    try {
      readCorpusManifest(manifest, folder.dir);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string m = manifest.string();
  EXPECT_EQ(manifestError("name,file\na,b\n"),
            m + ":1: the header has no column 'path' (it has name, file)");
  EXPECT_EQ(manifestError("name,path\na,b\nc\n"), m + ":3: 1 fields, but the header has 2 columns");
  EXPECT_EQ(manifestError("name,path\na,b\n\na,c\n"),
            m + ":4: mesh 'a' is listed twice (first on line 2)");
  EXPECT_EQ(manifestError("name,path\n,b\n"), m + ":2: the name is empty");
  EXPECT_EQ(manifestError("name,path\n"), m + ": the manifest lists no mesh");
  EXPECT_THROW(meshesInFolder(folder.dir / "nowhere"), Error);
}

}  // namespace
}  // namespace quadtri
