// The `normals` integrator of the thesis' constraint figures.
#pragma once

#include "quadtri/render/integrator/integrator.h"

namespace quadtri {

/// The shading normal at the first hit as a colour, 0.5·(n + 1) per axis; black on a miss.
class NormalsIntegrator final : public Integrator {
 public:
  Color radianceFrom(const RenderScene& scene, const Ray& ray,
                     const std::optional<SurfaceInteraction>& first, Pcg32& rng,
                     uint64_t& rays) const override;
  std::string toString() const override { return "normals"; }
};

}  // namespace quadtri
