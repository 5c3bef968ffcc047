// A render in progress, saved so that it can be resumed: which pixels are finished, with how
// many samples, and their values.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "quadtri/math/color.h"

namespace quadtri {

/// Pixels are independent (each has its own random stream seeded from the seed and its index),
/// so a finished pixel's value is final: resuming renders only the others and gives the image
/// an uninterrupted render with the same scene, options and seed gives, bit for bit.
struct RenderState {
  /// What the image depends on (renderKey, scene layer): a state is only resumed by a render
  /// with the same key.
  uint64_t key = 0;
  int width = 0, height = 0;
  std::vector<uint32_t> samples;  ///< per pixel, row-major; 0: not rendered yet
  std::vector<Color> pixels;      ///< the values of the pixels with samples > 0 (others 0)

  size_t finishedPixels() const;
};

/// Writes the state atomically: "QTRSTATE", format version, width, height, key, then per pixel
/// its sample count (uint32) and its value (3 doubles), little-endian.
void saveRenderState(const RenderState& state, const std::filesystem::path& path);

/// Reads a state written by saveRenderState; throws Error naming the file when it is not one
/// (magic, version, or a size that does not match its width and height).
RenderState loadRenderState(const std::filesystem::path& path);

}  // namespace quadtri
