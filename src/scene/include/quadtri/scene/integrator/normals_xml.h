// <integrator type="normals"/>  <!-- quadtri-specific: no properties -->
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// Colours surfaces by their shading normal (render/integrator/normals_integrator.h).
struct NormalsIntegratorParams final : IntegratorParams {
  std::string toString() const override { return {}; }
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
  std::shared_ptr<const Integrator> build(int samplesPerPixel) const override;
};

std::shared_ptr<const IntegratorParams> parseNormalsIntegrator(ObjectProperties& props);

}  // namespace quadtri
