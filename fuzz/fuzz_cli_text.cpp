// The other texts the command line parses: --max-memory sizes (parseByteSize), normal sources
// (--normals), and CSV tables (study and corpus manifests, parseCsv). The first byte picks
// the parser; the rest is its text.
#include "fuzz_common.h"
#include "quadtri/io/csv.h"
#include "quadtri/io/memory_limit.h"
#include "quadtri/mesh/normals.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace quadtri;
  if (size == 0) return 0;
  const std::string_view text = fuzz::asText(data + 1, size - 1);
  return fuzz::runClean([&] {
    switch (data[0] % 3) {
      case 0: {
        const uint64_t bytes = parseByteSize(text);
        (void)formatBytes(bytes);
        break;
      }
      case 1:
        (void)parseNormalSource(text);
        break;
      default:
        (void)parseCsv(text, "fuzz.csv");
        break;
    }
  });
}
