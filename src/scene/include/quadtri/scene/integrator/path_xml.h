// <integrator type="path">
//   <integer name="max_depth" value="-1"/>  <!-- -1: unbounded -->
//   <integer name="rr_depth" value="5"/>  <boolean name="hide_emitters" value="false"/>
// </integrator>
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// The path tracer's settings, also those of the adaptive integrator's path tracer.
struct PathSettings {
  int maxDepth = -1;  ///< longest path in segments; -1 = unbounded
  int rrDepth = 5;    ///< depth at which Russian roulette starts
  bool hideEmitters = false;

  /// "max_depth=... rr_depth=... hide_emitters=..." (no leading space).
  std::string toString() const;
};

/// Reads max_depth, rr_depth and hide_emitters.
PathSettings parsePathSettings(ObjectProperties& props);

/// An integer property `name` (fallback when absent) that must lie in [lo, hi].
int boundedInteger(ObjectProperties& props, std::string_view name, long long fallback, long long lo,
                   long long hi);

/// Unidirectional path tracing with next-event estimation and MIS
/// (render/integrator/path_integrator.h).
struct PathIntegratorParams final : IntegratorParams {
  PathSettings path;

  std::string toString() const override;
  std::shared_ptr<const Integrator> build(int samplesPerPixel) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const IntegratorParams> parsePathIntegrator(ObjectProperties& props);

}  // namespace quadtri
