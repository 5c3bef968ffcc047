// Mitsuba's `direct` integrator: emission seen directly plus light reflected once.
#pragma once

#include "quadtri/render/integrator/integrator.h"

namespace quadtri {

/// Direct illumination at the first hit from `emitterSamples` light samples and `bsdfSamples`
/// BSDF samples, combined by the power heuristic with the sample counts (Veach's multi-sample
/// MIS): a light sample weighs (nₑpₑ)² / ((nₑpₑ)² + (n_b p_b)²) and is divided by nₑ; point
/// lights by light sampling only. Delta BSDFs take only BSDF samples.
class DirectIntegrator final : public Integrator {
 public:
  struct Params {
    int emitterSamples = 1;
    int bsdfSamples = 1;
    bool hideEmitters = false;
  };
  explicit DirectIntegrator(const Params& params);
  Color radianceFrom(const RenderScene& scene, const Ray& ray,
                     const std::optional<SurfaceInteraction>& first, Pcg32& rng,
                     uint64_t& rays) const override;
  std::string toString() const override;

 private:
  Params params_;
};

}  // namespace quadtri
