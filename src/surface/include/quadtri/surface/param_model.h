// `quadric-param`: the thesis' parametric quadric triangle (§4.2).
#pragma once

#include <array>
#include <vector>

#include "quadtri/surface/quadratic_model.h"

namespace quadtri {

/// Each triangle becomes the quadratic Bézier triangle f(u,v) = u²c5 + v²c4 + uv c3 + u c2 +
/// v c1 + c0 whose edge control points are the closed-form solution of the thesis' 18×18
/// system (eq. 4.7-4.9, see edge_curves.h). Shared edges get the same control point, so the
/// patches meet without cracks (C0); the normal is (p_u × p_v)/|p_u × p_v|. fellBack(t): one
/// of the patch's edge control points gave up its tangent planes (clamped, or a damped solve off
/// them: edge_curves.h).
///
/// patchJson(t): {"vertices": [v0, v1, v2], "control_points": {"b01", "b12", "b20"},
/// "coefficients": {"c0", ..., "c5"}}, every point an [x, y, z] array.
class ParamModel final : public QuadraticPatchModel {
 public:
  explicit ParamModel(std::shared_ptr<const TriangleMesh> mesh);
  std::string_view name() const override { return "quadric-param"; }
  void patchRecord(size_t t, PatchRecord& out) const override;
};

}  // namespace quadtri
