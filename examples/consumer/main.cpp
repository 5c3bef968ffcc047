// Uses quadtri as a library: loads a mesh (or a built-in shape spec), converts it with a model,
// and traces one ray straight down (-z) through (centre.x + 0.1, centre.y + 0.05) onto the surface.
//
//   quadtri_consumer [MESH|SPEC] [MODEL]     (default: icosphere:1 quadric-implicit-robust)
//
// Prints the hit distance and the geometric normal; exits 1 if the ray misses.
#include <cstdio>
#include <memory>
#include <string>

#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/model_geometry.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

int main(int argc, char** argv) {
  const std::string spec = argc > 1 ? argv[1] : "icosphere:1";
  const std::string modelName = argc > 2 ? argv[2] : "quadric-implicit-robust";
  try {
    auto mesh = std::make_shared<const quadtri::TriangleMesh>(quadtri::loadMeshSpec(spec).mesh);
    const auto model = quadtri::makeModel(modelName, mesh);

    quadtri::Accel accel;
    quadtri::addModelGeometry(accel, *model, quadtri::Tessellation{});
    accel.commit();

    const quadtri::Bounds3 box = accel.bounds();
    const quadtri::Vec3 centre = box.center();
    quadtri::Ray ray;
    ray.origin = {centre.x() + 0.1, centre.y() + 0.05, box.hi.z() + 1.0};
    ray.direction = {0.0, 0.0, -1.0};
    const quadtri::RayHit hit = accel.intersect(ray);
    if (!hit.valid()) {
      std::printf("%s under %s: the ray misses\n", spec.c_str(), modelName.c_str());
      return 1;
    }
    const quadtri::Vec3 p = ray.origin + hit.t * ray.direction;
    std::printf("%s under %s: %zu triangles, hit z = %.9f, normal (%.6f, %.6f, %.6f)\n",
                spec.c_str(), modelName.c_str(), mesh->triangleCount(), p.z(),
                hit.geometricNormal.x(), hit.geometricNormal.y(), hit.geometricNormal.z());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "quadtri_consumer: %s\n", e.what());
    return 2;
  }
}
