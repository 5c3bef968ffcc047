#include "quadtri/surface/param_model.h"

#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"

namespace quadtri {

ParamModel::ParamModel(std::shared_ptr<const TriangleMesh> mesh)
    : QuadraticPatchModel(std::move(mesh)) {
  std::vector<uint8_t> fallbacks;
  controlPoints_ = edgeControlPoints(this->mesh(), &fallbacks);
  setFallbacks(std::move(fallbacks));
}

void ParamModel::patchRecord(size_t t, PatchRecord& out) const {
  addQuadraticPatch(patch(t), out);
}

}  // namespace quadtri
