// The other texts the command line parses: --max-memory sizes (parseByteSize), normal sources
// (--normals), CSV tables (study and corpus manifests, parseCsv) and tessellations
// (--tessellation, Tessellation::parse, whose accepted text must name itself again the same
// way). The first byte picks the parser; the rest is its text.
#include "fuzz_common.h"
#include "quadtri/io/csv.h"
#include "quadtri/io/memory_limit.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/surface/convert_output.h"
#include "quadtri/surface/tessellate.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace quadtri;
  if (size == 0) return 0;
  const std::string_view text = fuzz::asText(data + 1, size - 1);
  return fuzz::runClean([&] {
    switch (data[0] % 4) {
      case 0: {
        const uint64_t bytes = parseByteSize(text);
        (void)formatBytes(bytes);
        break;
      }
      case 1:
        (void)parseNormalSource(text);
        break;
      case 2:
        (void)parseCsv(text, "fuzz.csv");
        break;
      default: {
        const Tessellation t = Tessellation::parse(std::string(text));
        const Tessellation again = Tessellation::parse(tessellationName(t));
        if (again.kind != t.kind || again.level != t.level || again.tolerance != t.tolerance ||
            t.trianglesPerPatch() == 0)
          fuzz::broken("a tessellation's name parses as another tessellation");
        break;
      }
    }
  });
}
