#include "quadtri/render/integrator/adaptive_integrator.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"

namespace quadtri {

AdaptiveIntegrator::AdaptiveIntegrator(std::shared_ptr<const Integrator> inner,
                                       const AdaptiveSampling& sampling)
    : inner_(std::move(inner)), sampling_(sampling) {
  if (!inner_) fail("adaptive integrator: expected a nested integrator");
  if (inner_->adaptive()) fail("adaptive integrator: the nested integrator is adaptive too");
  if (sampling.minSamples < 2 || sampling.maxSamples < sampling.minSamples || sampling.batch < 1)
    fail(
        "adaptive integrator: expected 2 <= min samples ({}) <= max samples ({}) and batch >= 1 "
        "({})",
        sampling.minSamples, sampling.maxSamples, sampling.batch);
  if (!(sampling.threshold > 0.0) || !std::isfinite(sampling.threshold))
    fail("adaptive integrator: threshold {}: expected a positive relative error",
         sampling.threshold);
}

std::string AdaptiveIntegrator::toString() const {
  return fmt::format("adaptive(min={}, max={}, batch={}, threshold={}, {})", sampling_.minSamples,
                     sampling_.maxSamples, sampling_.batch, sampling_.threshold,
                     inner_->toString());
}

}  // namespace quadtri
