// Choosing which light next-event estimation samples.
#pragma once

#include <unordered_map>
#include <vector>

#include "quadtri/render/emitter/emitter.h"

namespace quadtri {

/// Picks one light per next-event estimate with probability proportional to its power
/// (Emitter::power), so a dim fill light does not get as many shadow rays as the key light;
/// when every light has zero power the choice is uniform. A light of zero power is never
/// picked, which is unbiased because it contributes nothing.
class LightSampler {
 public:
  LightSampler() = default;
  LightSampler(std::vector<const Emitter*> lights, const Bounds3& sceneBounds);

  struct Choice {
    const Emitter* light = nullptr;
    double probability = 0.0;
  };
  /// Chooses a light with one uniform number in [0, 1).
  Choice choose(double u) const;
  /// Probability that choose() returns `light`.
  double probability(const Emitter* light) const;
  bool empty() const { return lights_.empty(); }

 private:
  std::vector<const Emitter*> lights_;
  std::vector<double> cdf_;
  std::unordered_map<const Emitter*, double> probability_;
};

}  // namespace quadtri
