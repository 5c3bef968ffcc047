// Mesh loading from bytes, one harness per format (QUADTRI_FUZZ_EXT: ".obj", ".ply", ".off" or
// ".stl"): the bytes become a file of that extension and go through loadMesh with a memory
// budget, as `quadtri convert --max-memory` loads them. A mesh that loads must be valid: finite
// positions and normals, indices in range.
#include <cmath>

#include "fuzz_common.h"
#include "quadtri/mesh/mesh_io.h"

#ifndef QUADTRI_FUZZ_EXT
#error "define QUADTRI_FUZZ_EXT (the mesh file's extension)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace quadtri;
  const auto path = fuzz::writeScratch(std::string("mesh") + QUADTRI_FUZZ_EXT, data, size);
  return fuzz::runClean([&] {
    MemoryBudget budget;
    budget.maxBytes = uint64_t(256) << 20;
    budget.bytesPerTriangle = 512;
    const TriangleMesh mesh = loadMesh(path, NormalOptions{}, &budget);
    for (const Vec3& p : mesh.positions)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
        fuzz::broken("loadMesh returned a non-finite position");
    for (const Vec3& n : mesh.normals)
      if (!std::isfinite(n.x()) || !std::isfinite(n.y()) || !std::isfinite(n.z()))
        fuzz::broken("loadMesh returned a non-finite normal");
    for (const Tri& t : mesh.triangles)
      for (uint32_t i : t)
        if (i >= mesh.positions.size()) fuzz::broken("loadMesh returned an index out of range");
  });
}
