// The `adaptive` integrator: another integrator with the per-pixel stopping rule.
#pragma once

#include <memory>

#include "quadtri/render/integrator/integrator.h"

namespace quadtri {

/// Samples like `inner`, but the renderer takes samples in batches per pixel until the
/// AdaptiveSampling rule is met, so smooth regions stop early and noisy ones go on.
class AdaptiveIntegrator final : public Integrator {
 public:
  AdaptiveIntegrator(std::shared_ptr<const Integrator> inner, const AdaptiveSampling& sampling);
  Color radianceFrom(const RenderScene& scene, const Ray& ray,
                     const std::optional<SurfaceInteraction>& first, Pcg32& rng,
                     uint64_t& rays) const override {
    return inner_->radianceFrom(scene, ray, first, rng, rays);
  }
  const AdaptiveSampling* adaptive() const override { return &sampling_; }
  std::string toString() const override;

 private:
  std::shared_ptr<const Integrator> inner_;
  AdaptiveSampling sampling_;
};

}  // namespace quadtri
