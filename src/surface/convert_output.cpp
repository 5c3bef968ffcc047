#include "quadtri/surface/convert_output.h"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "quadtri/io/atomic_file.h"
#include "quadtri/io/atomic_stream.h"
#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/patch_record.h"
#include "quadtri/surface/patch_table.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

std::string tessellationName(const Tessellation& tessellation) {
  switch (tessellation.kind) {
    case Tessellation::Kind::ThesisGrid:
      return "thesis";
    case Tessellation::Kind::Adaptive:
      return tessellation.tolerance == Tessellation::kDefaultTolerance
                 ? "auto"
                 : fmt::format("auto:{}", tessellation.tolerance);
    case Tessellation::Kind::Lattice:
      break;
  }
  return std::to_string(tessellation.level);
}

namespace {

void bridgeRecordOf(const QuadricPatch& b, PatchRecord& out) {
  const PatchRecord::Ref root = PatchRecord::kRoot;
  const PatchRecord::Ref joins = out.setArray(root, "joins");
  out.pushInt(joins, b.joins[0]);
  out.pushInt(joins, b.joins[1]);
  out.set(root, "plane", b.q.data() + 6, 4);
  const PatchRecord::Ref joinPlanes = out.setArray(root, "join_planes");
  out.pushInt(joinPlanes, b.joinPlanes[0]);
  out.pushInt(joinPlanes, b.joinPlanes[1]);
  const PatchRecord::Ref planes = out.setArray(root, "planes");
  for (int k = 0; k < b.planeCount; ++k) out.push(planes, b.planes[k].data(), 4);
  const PatchRecord::Ref bounds = out.setObject(root, "bounds");
  out.set(bounds, "min", b.bounds.lo);
  out.set(bounds, "max", b.bounds.hi);
}

bool writesBridges(const SurfaceModel& model) {
  return model.name() == std::string_view("quadric-implicit-robust");
}

// Writes "[item(0),item(1),...]": the records item(i, record) dumped in parallel, kChunk at a
// time, and written in order, so that at most one chunk of text is held.
template <typename Item>
void writeArray(std::ostream& out, size_t count, const Item& item) {
  constexpr size_t kChunk = 4096;
  std::vector<std::string> text;
  out << '[';
  for (size_t first = 0; first < count; first += kChunk) {
    const size_t n = std::min(kChunk, count - first);
    text.assign(n, std::string());
    parallelForRange(tbb::blocked_range<size_t>(0, n, 64),
                     [&](const tbb::blocked_range<size_t>& r) {
                       PatchRecord record;
                       for (size_t i = r.begin(); i != r.end(); ++i) {
                         record.clear();
                         item(first + i, record);
                         record.dump(text[i]);
                       }
                     });
    for (size_t i = 0; i < n; ++i) {
      if (first + i > 0) out << ',';
      out << text[i];
    }
  }
  out << ']';
}

// The layout of `count` records item(i, record), or of `empty` when there are none: each part of
// kPart records makes its own layout in parallel, one record at a time in one reused record
// (never all held), and the parts' layouts are merged in order. Where a part saw a null (whose
// layout depends on the order the records come in) or refused a record, the records are added
// one by one instead: the layout, or the error, is then the one-by-one result.
template <typename Item>
RecordLayout layoutOf(size_t count, const Item& item, const nlohmann::json& empty) {
  constexpr size_t kPart = 256;
  const auto oneByOne = [&] {
    RecordLayout layout;
    if (count == 0) layout.add(empty);
    PatchRecord record;
    for (size_t i = 0; i < count; ++i) {
      record.clear();
      item(i, record);
      layout.add(record);
    }
    layout.finish();
    return layout;
  };
  std::vector<RecordLayout> parts((count + kPart - 1) / kPart);
  std::vector<char> refused(parts.size(), 0);
  parallelFor(size_t(0), parts.size(), [&](size_t p) {
    try {
      PatchRecord record;
      for (size_t i = p * kPart; i < std::min(count, (p + 1) * kPart); ++i) {
        record.clear();
        item(i, record);
        parts[p].add(record);
      }
    } catch (const Error&) {
      refused[p] = 1;
    }
  });
  if (std::find(refused.begin(), refused.end(), 1) != refused.end()) return oneByOne();
  RecordLayout layout;
  if (count == 0) layout.add(empty);
  try {
    for (const RecordLayout& part : parts) layout.merge(part);
  } catch (const Error&) {
    return oneByOne();
  }
  if (layout.sawNull()) return oneByOne();
  layout.finish();
  return layout;
}

// Packs the n records item(first + i) in `layout` into `bytes` (n × itemSize), in parallel.
template <typename Item>
void packRecords(size_t first, size_t n, const Item& item, const RecordLayout& layout,
                 char* bytes) {
  const size_t size = layout.itemSize();
  parallelForRange(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& r) {
    PatchRecord record;
    for (size_t i = r.begin(); i != r.end(); ++i) {
      record.clear();
      item(first + i, record);
      layout.fill(record, bytes + i * size);
    }
  });
}

// Writes the `count` records item(i) in `layout`, kChunk at a time.
template <typename Item>
void writeRecords(std::ostream& out, size_t count, const Item& item, const RecordLayout& layout) {
  constexpr size_t kChunk = 4096;
  std::vector<char> bytes;
  for (size_t first = 0; first < count; first += kChunk) {
    const size_t n = std::min(kChunk, count - first);
    bytes.resize(n * layout.itemSize());
    packRecords(first, n, item, layout, bytes.data());
    out.write(bytes.data(), std::streamsize(bytes.size()));
  }
}

template <typename Item>
PackedRecords packAll(size_t count, const Item& item, const nlohmann::json& empty) {
  PackedRecords packed{layoutOf(count, item, empty), {}, count};
  packed.bytes.resize(count * packed.layout.itemSize());
  packRecords(0, count, item, packed.layout, packed.bytes.data());
  return packed;
}

}  // namespace

size_t bridgeCount(const SurfaceModel& model) {
  if (model.representation() != Representation::Implicit) return 0;
  return model.renderPatches().size() - model.patchCount();
}

void bridgeRecord(const SurfaceModel& model, size_t i, PatchRecord& out) {
  bridgeRecordOf(model.renderPatches().at(model.patchCount() + i), out);
}

nlohmann::json bridgeJson(const SurfaceModel& model, size_t i) {
  PatchRecord record;
  bridgeRecord(model, i, record);
  return record.toJson();
}

nlohmann::json conversionJson(const SurfaceModel& model, const Tessellation& tessellation) {
  nlohmann::json j;
  j["model"] = std::string(model.name());
  j["triangles"] = model.mesh().triangleCount();
  j["tessellation"] = tessellationName(tessellation);
  j["patches"] = nlohmann::json::array();
  for (size_t t = 0; t < model.patchCount(); ++t) j["patches"].push_back(model.patchJson(t));
  // Edge bridges (quadric-implicit-robust): the primitives after the patches. The robust model
  // always writes the array, empty when it has no bridges.
  if (writesBridges(model)) j["bridges"] = nlohmann::json::array();
  const size_t bridges = bridgeCount(model);
  for (size_t i = 0; i < bridges; ++i) j["bridges"].push_back(bridgeJson(model, i));
  return j;
}

void writeConversionJson(const SurfaceModel& model, const Tessellation& tessellation,
                         std::ostream& out) {
  // The keys in nlohmann::json's order (sorted), so the text is conversionJson(...).dump().
  out << '{';
  const size_t bridges = bridgeCount(model);
  if (writesBridges(model) || bridges > 0) {
    out << "\"bridges\":";
    writeArray(out, bridges, [&](size_t i, PatchRecord& r) { bridgeRecord(model, i, r); });
    out << ',';
  }
  out << "\"model\":" << nlohmann::json(std::string(model.name())).dump() << ",\"patches\":";
  writeArray(out, model.patchCount(), [&](size_t t, PatchRecord& r) { model.patchRecord(t, r); });
  out << ",\"tessellation\":" << nlohmann::json(tessellationName(tessellation)).dump()
      << ",\"triangles\":" << nlohmann::json(model.mesh().triangleCount()).dump() << "}\n";
}

PackedRecords packedPatches(const SurfaceModel& model) {
  return packAll(
      model.patchCount(), [&](size_t t, PatchRecord& r) { model.patchRecord(t, r); },
      nlohmann::json::object());
}

PackedRecords packedBridges(const SurfaceModel& model) {
  return packAll(
      bridgeCount(model), [&](size_t i, PatchRecord& r) { bridgeRecord(model, i, r); },
      emptyBridgeRecord());
}

void writePatchTable(const SurfaceModel& model, const Tessellation& tessellation,
                     std::ostream& out) {
  const auto patch = [&](size_t t, PatchRecord& r) { model.patchRecord(t, r); };
  const auto bridge = [&](size_t i, PatchRecord& r) { bridgeRecord(model, i, r); };
  PatchTableInfo info;
  info.model = std::string(model.name());
  info.tessellation = tessellationName(tessellation);
  info.triangles = model.mesh().triangleCount();
  info.patchCount = model.patchCount();
  info.bridgeCount = bridgeCount(model);
  const RecordLayout patches = layoutOf(info.patchCount, patch, nlohmann::json::object());
  const RecordLayout bridges = layoutOf(info.bridgeCount, bridge, emptyBridgeRecord());
  out << patchTableHeader(info, patches, bridges);
  writeRecords(out, info.patchCount, patch, patches);
  writeRecords(out, info.bridgeCount, bridge, bridges);
}

std::string conversionExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

size_t writeConversion(const SurfaceModel& model, const Tessellation& tessellation,
                       const std::filesystem::path& path) {
  const std::string ext = conversionExtension(path);
  if (ext == ".json") {
    writeStreamAtomically(
        path, [&](std::ostream& out) { writeConversionJson(model, tessellation, out); });
    return 0;
  }
  if (ext == ".qtp") {
    writeStreamAtomically(path,
                          [&](std::ostream& out) { writePatchTable(model, tessellation, out); });
    return 0;
  }
  if (ext != ".obj" && ext != ".ply")
    fail("{}: unknown output extension '{}': expected .obj, .ply, .json or .qtp", path.string(),
         ext);
  return saveTessellation(model, tessellation, path);
}

}  // namespace quadtri
