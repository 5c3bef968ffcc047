#include "quadtri/render/integrator/normals_integrator.h"

#include "quadtri/render/render_scene.h"

namespace quadtri {

Color NormalsIntegrator::radiance(const RenderScene& scene, const Ray& ray, Pcg32&,
                                  uint64_t& rays) const {
  ++rays;
  const std::optional<SurfaceInteraction> si = scene.intersect(ray);
  if (!si) return Color::Zero();
  return 0.5 * (si->shadingNormal.array() + 1.0);
}

}  // namespace quadtri
