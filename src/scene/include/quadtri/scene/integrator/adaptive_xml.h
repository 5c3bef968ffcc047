// <integrator type="adaptive">  <!-- quadtri's version of the thesis' adaptive integration -->
//   <float name="threshold" value="0.05"/>  <!-- relative standard error that stops a pixel -->
//   <integer name="min_samples" value="16"/> <integer name="max_samples" value="256"/>
//   <integrator type="path"> ... </integrator>
// </integrator>
#pragma once

#include "quadtri/scene/integrator/path_xml.h"

namespace quadtri {

/// Path tracing until each pixel's relative standard error is below `threshold`
/// (render/integrator/adaptive_integrator.h).
struct AdaptiveIntegratorParams final : IntegratorParams {
  double threshold = 0.05;  ///< relative standard error that stops a pixel
  int minSamples = 16;      ///< samples taken before the first test
  int maxSamples = 0;       ///< cap per pixel; 0 until the parse gives it the sample_count
  PathSettings path;

  std::string toString() const override;
  std::shared_ptr<const Integrator> build(int samplesPerPixel) const override;
  /// max_samples defaults to the sampler's sample_count, which must reach min_samples.
  std::shared_ptr<const IntegratorParams> withSamplerCount(int sampleCount,
                                                           const std::string& location,
                                                           const std::string& file) const override;
  /// --spp N caps each pixel at N samples (min_samples lowered to N where needed); N >= 2.
  std::shared_ptr<const IntegratorParams> withSamplesPerPixel(
      int samplesPerPixel, const std::string& file) const override;
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
};

std::shared_ptr<const IntegratorParams> parseAdaptiveIntegrator(ObjectProperties& props);

}  // namespace quadtri
