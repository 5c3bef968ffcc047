#include "quadtri/surface/convert_output.h"

#include <nlohmann/json.hpp>

#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/quadric_patch.h"

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
  // Edge bridges (quadric-implicit-robust): the primitives after the patches. The robust model
  // always writes the array, empty when it has no bridges.
  if (model.name() == std::string_view("quadric-implicit-robust"))
    j["bridges"] = nlohmann::json::array();
  if (model.representation() == Representation::Implicit) {
    const std::vector<QuadricPatch>& all = model.renderPatches();
    for (size_t i = model.patchCount(); i < all.size(); ++i) {
      const QuadricPatch& b = all[i];
      nlohmann::json bridge;
      bridge["joins"] = {b.joins[0], b.joins[1]};
      bridge["plane"] = {b.q[6], b.q[7], b.q[8], b.q[9]};
      bridge["join_planes"] = {b.joinPlanes[0], b.joinPlanes[1]};
      bridge["planes"] = nlohmann::json::array();
      for (int k = 0; k < b.planeCount; ++k)
        bridge["planes"].push_back(
            {b.planes[k][0], b.planes[k][1], b.planes[k][2], b.planes[k][3]});
      bridge["bounds"] = {{"min", {b.bounds.lo.x(), b.bounds.lo.y(), b.bounds.lo.z()}},
                          {"max", {b.bounds.hi.x(), b.bounds.hi.y(), b.bounds.hi.z()}}};
      j["bridges"].push_back(bridge);
    }
  }
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
