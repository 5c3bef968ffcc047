// `phong`: Phong tessellation (Boubekeur and Alexa, "Phong Tessellation", SIGGRAPH Asia 2008).
#pragma once

#include "quadtri/surface/model.h"

namespace quadtri {

/// Phong tessellation: p*(u,v) = (1−α) p(u,v) + α Σ_i λ_i π_i(p(u,v)), where p is the flat
/// triangle, λ = (1−u−v, u, v) and π_i(q) = q − ((q − p_i)·n_i) n_i projects onto corner i's
/// tangent plane; α is the paper's shape factor (3/4 recommended). The patch is quadratic.
///
/// Normal: the paper shades with the interpolated vertex normals; this model returns the
/// geometric normal (∂p*/∂u × ∂p*/∂v, analytic) instead, because quadtri's point is that the
/// geometric normal is the shading normal, and analysis must measure the geometry.
///
/// What holds (tested): corners are interpolated exactly; each boundary curve depends only on
/// its edge's two corners and normals, so neighbours share edges only where the mesh shares
/// normals (split normals at a crease open a crack: sharesEdges() is false on such a mesh);
/// the geometric normal at a corner is not the vertex normal in general (the other corners'
/// tangent planes pull the corner tangents out of it: 2.64° on an icosahedron with sphere
/// normals at α = 3/4); flat input gives the flat triangle.
class PhongModel final : public SurfaceModel {
 public:
  explicit PhongModel(std::shared_ptr<const TriangleMesh> mesh, double alpha = 0.75);
  std::string_view name() const override { return "phong"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  bool sharesEdges() const override { return sharesEdges_; }
  nlohmann::json patchJson(size_t t) const override;
  double alpha() const { return alpha_; }

 private:
  double alpha_;
  bool sharesEdges_;
};

}  // namespace quadtri
