#include "quadtri/render/integrator/integrator.h"

#include "quadtri/render/render_scene.h"

namespace quadtri {

Color Integrator::radiance(const RenderScene& scene, const Ray& ray, Pcg32& rng,
                           uint64_t& rays) const {
  return radianceFrom(scene, ray, scene.intersect(ray), rng, rays);
}

}  // namespace quadtri
