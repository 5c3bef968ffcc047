// The streamed exports: `convert -o x.json` writes the bytes of the whole document's dump, and
// `convert -o x.qtp` the binary patch table, whose records are the patch JSON's values in the
// layout Python's m.patches() takes; a damaged table is refused naming the file and offset.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>

#include "quadtri/math/error.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/convert_output.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/patch_table.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

class PatchTableTest : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("quadtri-patch-table-" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeAll(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::shared_ptr<const TriangleMesh> torus() {
  // Bridges under quadric-implicit-robust, and more patches than one chunk of 4096.
  static const auto mesh =
      std::make_shared<const TriangleMesh>(parseBuiltinSpec("torus:1,0.35,96,24")->mesh);
  return mesh;
}

TEST_F(PatchTableTest, StreamedJsonIsTheDocumentsDump) {
  for (const std::string& name : modelNames()) {
    const auto model = makeModel(name, torus());
    const fs::path path = dir / "p.json";
    writeConversion(*model, Tessellation{}, path);
    EXPECT_EQ(readAll(path), conversionJson(*model, Tessellation{}).dump() + "\n") << name;
  }
}

TEST_F(PatchTableTest, RecordsHoldThePatchJsonInTheirLayout) {
  for (const std::string& name : modelNames()) {
    const auto model = makeModel(name, torus());
    const fs::path path = dir / "p.qtp";
    EXPECT_EQ(writeConversion(*model, Tessellation::thesis(), path), 0u);
    const PatchTable table = readPatchTable(path);
    EXPECT_EQ(table.model, name);
    EXPECT_EQ(table.tessellation, "thesis");
    EXPECT_EQ(table.triangles, torus()->triangleCount());
    // The records, made here from the whole JSON document, are the file's bytes.
    const nlohmann::json j = conversionJson(*model, Tessellation::thesis());
    const auto expect = [&](const nlohmann::json& list, const nlohmann::json& empty,
                            const RecordLayout& got, const std::vector<char>& bytes,
                            uint64_t count) {
      const std::vector<nlohmann::json> records(list.begin(), list.end());
      RecordLayout want;
      if (records.empty()) want.add(empty);
      for (const nlohmann::json& r : records) want.add(r);
      want.finish();
      ASSERT_EQ(count, records.size()) << name;
      ASSERT_EQ(got.itemSize(), want.itemSize()) << name;
      std::vector<char> record(want.itemSize());
      for (size_t i = 0; i < records.size(); ++i) {
        want.fill(records[i], record.data());
        ASSERT_EQ(std::memcmp(record.data(), bytes.data() + i * want.itemSize(), record.size()), 0)
            << name << " record " << i;
      }
    };
    expect(j["patches"], nlohmann::json::object(), table.patchLayout, table.patches,
           table.patchCount);
    expect(j.value("bridges", nlohmann::json::array()), emptyBridgeRecord(), table.bridgeLayout,
           table.bridges, table.bridgeCount);
    if (name == "quadric-implicit-robust") {
      EXPECT_GT(table.bridgeCount, 0u);
    }
    // Every field the layout names, with its shape: the fields of the JSON's first patch.
    for (const auto& item : j["patches"][0].items()) {
      if (item.value().is_string()) continue;
      const std::string key = item.key();
      EXPECT_TRUE(std::any_of(table.patchLayout.root().children.begin(),
                              table.patchLayout.root().children.end(),
                              [&](const RecordField& f) { return f.name == key; }))
          << name << " " << key;
    }
  }
}

TEST(RecordLayoutMerge, PartsMergedInOrderGiveTheLayoutOfTheRecordsAddedOneByOne) {
  // Records that exercise every rule: lists of varying and equal lengths, empty lists before
  // and after full ones, int and float in one key, keys that appear late, nested objects.
  std::mt19937 rng(7);
  const auto pick = [&](int n) { return int(rng() % unsigned(n)); };
  std::vector<nlohmann::json> records;
  for (int r = 0; r < 200; ++r) {
    nlohmann::json j;
    j["id"] = r;
    j["scale"] = pick(3) == 0 ? nlohmann::json(r) : nlohmann::json(0.5 * r);
    j["same"] = {1.0, 2.0, 3.0};
    nlohmann::json list = nlohmann::json::array();
    for (int i = 0, n = pick(5); i < n; ++i) list.push_back({1.0 * i, 2.0, 3.0});
    j["rows"] = list;
    if (r > 150 && pick(2) == 0) j["late"] = {{"a", r}, {"b", {1.0, 2.0}}};
    if (pick(4) == 0) j["flag"] = pick(2) == 0;
    j["name"] = "skipped";
    records.push_back(j);
  }
  RecordLayout oneByOne;
  for (const nlohmann::json& r : records) oneByOne.add(r);
  oneByOne.finish();
  for (const size_t partSize : {1, 7, 64, 199}) {
    RecordLayout merged;
    for (size_t first = 0; first < records.size(); first += partSize) {
      RecordLayout part;
      for (size_t i = first; i < std::min(records.size(), first + partSize); ++i)
        part.add(records[i]);
      merged.merge(part);
    }
    EXPECT_FALSE(merged.sawNull());
    merged.finish();
    EXPECT_EQ(merged.itemSize(), oneByOne.itemSize()) << partSize;
    // The header spells out every field's name, kind, variability and shape, in order.
    EXPECT_EQ(patchTableHeader({}, merged, merged), patchTableHeader({}, oneByOne, oneByOne))
        << partSize;
  }
  RecordLayout withNull;
  withNull.add({{"x", 1.0}});
  RecordLayout later;
  later.add({{"x", nullptr}});
  withNull.merge(later);
  EXPECT_TRUE(withNull.sawNull());
  // Shapes that disagree across parts are refused as across records.
  RecordLayout lists, number;
  lists.add({{"k", {1.0, 2.0}}});
  number.add({{"k", 3.0}});
  EXPECT_THROW(lists.merge(number), Error);
}

// Runs f, which must throw Error; returns the message.
std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

TEST_F(PatchTableTest, DamagedTablesAreRefusedNamingFileAndOffset) {
  const auto model =
      makeModel("quadric-implicit",
                std::make_shared<const TriangleMesh>(parseBuiltinSpec("icosahedron")->mesh));
  const fs::path good = dir / "good.qtp";
  writeConversion(*model, Tessellation{}, good);
  const std::string bytes = readAll(good);
  ASSERT_EQ(readPatchTable(good).patchCount, 20u);
  const fs::path bad = dir / "bad.qtp";
  const auto refused = [&](const std::string& content, const std::string& what) {
    writeAll(bad, content);
    const std::string message = refusal([&] { readPatchTable(bad); });
    EXPECT_EQ(message.rfind(bad.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << what << " in: " << message;
  };
  refused(bytes.substr(0, 20), "20 bytes, expected a quadtri patch table");
  refused("QTPATCX" + bytes.substr(7), "offset 0: not a quadtri patch table");
  std::string v2 = bytes;
  v2[8] = 2;
  refused(v2, "offset 8: version 2, this reader reads version 1");
  std::string big = bytes;
  const uint32_t huge = uint32_t(bytes.size()) + 8;
  std::memcpy(big.data() + 12, &huge, 4);
  refused(big, "offset 12: a header of");
  refused(bytes.substr(0, bytes.size() - 3),
          fmt::format("offset {}: the header declares 20 patches", bytes.size() - 3));
  refused(bytes + "xxxxxxxx", "the file has " + std::to_string(bytes.size() + 8));
  std::string size = bytes;
  size[40] = char(size[40] + 8);
  refused(size, "offset 40: patch records of");
  // The first patch field's kind (after the fixed part, the two texts and the field count).
  const size_t texts = 48 + 4 + std::strlen("quadric-implicit") + 4 + 1;
  const size_t firstField = texts + 4;
  uint32_t nameLength = 0;
  std::memcpy(&nameLength, bytes.data() + firstField, 4);
  std::string kind = bytes;
  kind[firstField + 4 + nameLength] = 9;
  refused(kind, fmt::format("offset {}: field '", firstField));
  // A header cut inside its field list.
  std::string cut = bytes.substr(0, texts + 2);
  cut.resize(48 + 8, '\0');
  const uint32_t cutHeader = 56;
  std::memcpy(cut.data() + 12, &cutHeader, 4);
  refused(cut, "the header ends in");
  EXPECT_TRUE(fs::exists(good));
}

}  // namespace
}  // namespace quadtri
