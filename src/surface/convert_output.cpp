#include "surface/convert_output.h"

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "math/error.h"
#include "mesh/mesh_io.h"

namespace quadtri {

std::string tessellationName(const Tessellation& tessellation) {
  return tessellation.kind == Tessellation::Kind::ThesisGrid ? "thesis"
                                                             : std::to_string(tessellation.level);
}

nlohmann::json conversionJson(const SurfaceModel& model, const Tessellation& tessellation) {
  nlohmann::json j;
  j["model"] = std::string(model.name());
  j["triangles"] = model.mesh().triangleCount();
  j["tessellation"] = tessellationName(tessellation);
  j["patches"] = nlohmann::json::array();
  for (size_t t = 0; t < model.patchCount(); ++t) j["patches"].push_back(model.patchJson(t));
  return j;
}

size_t writeConversion(const SurfaceModel& model, const Tessellation& tessellation,
                       const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") {
    writeTextFile(path, conversionJson(model, tessellation).dump() + "\n");
    return 0;
  }
  if (ext != ".obj" && ext != ".ply")
    fail("{}: unknown output extension '{}': expected .obj, .ply or .json", path.string(), ext);
  const TriangleMesh surface = tessellate(model, tessellation);
  saveMesh(surface, path);
  return surface.triangleCount();
}

}  // namespace quadtri
