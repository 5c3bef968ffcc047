// <integrator type="direct">  <!-- shading_samples sets both of the next two -->
//   <integer name="emitter_samples" value="1"/> <integer name="bsdf_samples" value="1"/>
// </integrator>
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// Direct illumination only (render/integrator/direct_integrator.h).
struct DirectIntegratorParams final : IntegratorParams {
  int emitterSamples = 1;  ///< light samples per shading point
  int bsdfSamples = 1;     ///< BSDF samples per shading point
  bool hideEmitters = false;

  std::string toString() const override;
  std::shared_ptr<const Integrator> build(int samplesPerPixel) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const IntegratorParams> parseDirectIntegrator(ObjectProperties& props);

}  // namespace quadtri
