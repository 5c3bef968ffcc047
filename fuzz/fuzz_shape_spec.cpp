// The built-in shape specs of the command line (icosphere:3, torus:1,0.35,48,24, ...), as
// loadMeshSpec reads them with a memory budget (as --max-memory does). A shape that builds must be
// valid and finite.
#include <cmath>

#include "fuzz_common.h"
#include "quadtri/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace quadtri;
  const std::string spec(fuzz::asText(data, size));
  // A spec that names an existing file is a mesh file: that is the mesh harnesses' job.
  std::error_code ec;
  if (spec.find('/') != std::string::npos || std::filesystem::exists(spec, ec)) return 0;
  return fuzz::runClean([&] {
    // As `quadtri convert --max-memory 256M` builds it: the budget refuses what is too large
    // before it is built.
    MemoryBudget budget;
    budget.maxBytes = uint64_t(256) << 20;
    budget.bytesPerTriangle = 512;
    const BuiltinMesh b = loadMeshSpec(spec, NormalOptions{}, &budget);
    b.mesh.validate(spec);
    for (const Vec3& p : b.mesh.positions)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
        fuzz::broken("parseBuiltinSpec built a non-finite position");
    for (const Vec3& n : b.mesh.normals)
      if (!std::isfinite(n.x()) || !std::isfinite(n.y()) || !std::isfinite(n.z()))
        fuzz::broken("parseBuiltinSpec built a non-finite normal");
  });
}
