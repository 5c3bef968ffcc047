#include "quadtri/render/integrator/normals_integrator.h"

#include "quadtri/render/render_scene.h"

namespace quadtri {

Color NormalsIntegrator::radianceFrom(const RenderScene&, const Ray&,
                                      const std::optional<SurfaceInteraction>& si, Pcg32&,
                                      uint64_t& rays) const {
  ++rays;
  if (!si) return Color::Zero();
  return 0.5 * (si->shadingNormal.array() + 1.0);
}

}  // namespace quadtri
