#include "quadtri/render/emitter/light_sampler.h"

#include <algorithm>

namespace quadtri {

LightSampler::LightSampler(std::vector<const Emitter*> lights, const Bounds3& sceneBounds)
    : lights_(std::move(lights)) {
  if (lights_.empty()) return;
  std::vector<double> weights;
  double total = 0.0;
  for (const Emitter* light : lights_) {
    const double p = light->power(sceneBounds);
    weights.push_back(std::isfinite(p) && p > 0.0 ? p : 0.0);
    total += weights.back();
  }
  if (!(total > 0.0)) {
    std::fill(weights.begin(), weights.end(), 1.0);
    total = double(weights.size());
  }
  double running = 0.0;
  for (size_t i = 0; i < lights_.size(); ++i) {
    running += weights[i];
    cdf_.push_back(running / total);
    probability_[lights_[i]] = weights[i] / total;
  }
  // Rounding may leave the sum short of 1: end the CDF at the last light that can be picked.
  size_t last = lights_.size() - 1;
  while (last > 0 && weights[last] == 0.0) --last;
  for (size_t i = last; i < cdf_.size(); ++i) cdf_[i] = 1.0;
}

LightSampler::Choice LightSampler::choose(double u) const {
  if (lights_.empty()) return {};
  // The first entry above u: never a zero-width one, since u < 1 = the CDF's last pickable entry.
  const size_t i = size_t(std::upper_bound(cdf_.begin(), cdf_.end() - 1, u) - cdf_.begin());
  return {lights_[i], probability_.at(lights_[i])};
}

double LightSampler::probability(const Emitter* light) const {
  const auto it = probability_.find(light);
  return it == probability_.end() ? 0.0 : it->second;
}

}  // namespace quadtri
