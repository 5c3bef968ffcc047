// What `quadtri convert` writes: a model's tessellated surface or its patches as JSON.
#pragma once

#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "quadtri/surface/model.h"
#include "quadtri/surface/patch_table.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

/// "thesis" or the lattice level, as `--tessellation` takes it.
std::string tessellationName(const Tessellation& tessellation);

/// {"model": name, "triangles": input triangles, "tessellation": tessellationName,
///  "patches": [model.patchJson(t) for every triangle t]}.
nlohmann::json conversionJson(const SurfaceModel& model, const Tessellation& tessellation);

/// The edge bridges of quadric-implicit-robust (an implicit model's render patches after its
/// patches; 0 for other models), bridge i's record (into `out`, empty) and its JSON as
/// conversionJson lists it.
size_t bridgeCount(const SurfaceModel& model);
void bridgeRecord(const SurfaceModel& model, size_t i, PatchRecord& out);
nlohmann::json bridgeJson(const SurfaceModel& model, size_t i);

/// Every patch's (or edge bridge's) record packed as the binary patch table packs it: the layout,
/// then count × layout.itemSize() bytes (what Python's Model.patches() and bridges() return).
struct PackedRecords {
  RecordLayout layout;
  std::vector<char> bytes;
  size_t count = 0;
};
PackedRecords packedPatches(const SurfaceModel& model);
PackedRecords packedBridges(const SurfaceModel& model);

/// Writes conversionJson(model, tessellation).dump() and a newline to `out`, the same bytes, as
/// a stream: the patches are dumped in parallel a few thousand at a time and written in order,
/// so the whole document is never held in memory.
void writeConversionJson(const SurfaceModel& model, const Tessellation& tessellation,
                         std::ostream& out);

/// The extension of a conversion's output path, lower case (".PLY" writes a PLY file): what
/// writeConversion dispatches on.
std::string conversionExtension(const std::filesystem::path& path);

/// Writes the conversion by the file's extension: .obj or .ply get the tessellated surface
/// (the input triangles for InputTriangles models), .json gets conversionJson (written as a
/// stream, writeConversionJson), .qtp the binary patch table (writePatchTable, patch_table.h).
/// The file appears atomically; any other extension throws Error before anything is written.
/// Returns the number of triangles written (0 for JSON and .qtp).
size_t writeConversion(const SurfaceModel& model, const Tessellation& tessellation,
                       const std::filesystem::path& path);

}  // namespace quadtri
