// Mitsuba's `path` integrator (and `direct`, which is a path of at most one bounce).
#pragma once

#include "quadtri/render/integrator/integrator.h"

namespace quadtri {

/// Unidirectional path tracing. At each non-delta vertex one light is chosen by power and
/// sampled (next-event estimation), and the BSDF is sampled to continue; an area or
/// environment light reached either way is weighted by the power heuristic between the two
/// strategies, point lights only by next-event estimation. Depth counts path vertices as in
/// Mitsuba: max_depth 1 shows only directly visible emitters, 2 direct lighting, −1 no limit.
/// From rr_depth bounces on, Russian roulette continues with probability
/// min(max(throughput)·η², 0.95).
class PathIntegrator final : public Integrator {
 public:
  struct Params {
    int maxDepth = -1;
    int rrDepth = 5;
    bool hideEmitters = false;
  };
  explicit PathIntegrator(const Params& params);
  Color radianceFrom(const RenderScene& scene, const Ray& ray,
                     const std::optional<SurfaceInteraction>& first, Pcg32& rng,
                     uint64_t& rays) const override;
  std::string toString() const override;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace quadtri
