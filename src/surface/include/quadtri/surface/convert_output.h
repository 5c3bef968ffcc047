// What `quadtri convert` writes: a model's tessellated surface or its patches as JSON.
#pragma once

#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

/// "thesis" or the lattice level, as `--tessellation` takes it.
std::string tessellationName(const Tessellation& tessellation);

/// {"model": name, "triangles": input triangles, "tessellation": tessellationName,
///  "patches": [model.patchJson(t) for every triangle t]}.
nlohmann::json conversionJson(const SurfaceModel& model, const Tessellation& tessellation);

/// Writes the conversion by the file's extension: .obj or .ply get the tessellated surface
/// (the input triangles for InputTriangles models), .json gets conversionJson. The file
/// appears atomically; any other extension throws Error before anything is written. Returns
/// the number of triangles written (0 for JSON).
size_t writeConversion(const SurfaceModel& model, const Tessellation& tessellation,
                       const std::filesystem::path& path);

}  // namespace quadtri
