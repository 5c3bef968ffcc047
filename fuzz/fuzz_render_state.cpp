// Render state files (render --resume STATE): any bytes must be read as a state that matches
// its width and height with finite pixels, or refused with an error naming the file.
#include "fuzz_common.h"
#include "quadtri/render/render_state.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace quadtri;
  const auto path = fuzz::writeScratch("state.qtrstate", data, size);
  return fuzz::runClean([&] {
    const RenderState s = loadRenderState(path);
    const size_t n = size_t(s.width) * size_t(s.height);
    if (s.width <= 0 || s.height <= 0 || s.samples.size() != n || s.pixels.size() != n)
      fuzz::broken("loadRenderState returned a state whose sizes do not match");
    for (const Color& c : s.pixels)
      if (!c.isFinite().all()) fuzz::broken("loadRenderState returned a non-finite pixel");
  });
}
