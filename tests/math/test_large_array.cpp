#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "quadtri/math/large_array.h"

namespace quadtri {
namespace {

TEST(LargeArray, HoldsWhatTheStandardCallsHold) {
  // Below and above the size that asks for huge pages.
  for (const size_t n : {size_t(10), kLargeArrayBytes / sizeof(double) + 3}) {
    const std::vector<double> zeros = largeVector<double>(n);
    EXPECT_EQ(zeros, std::vector<double>(n));
    const std::vector<std::array<float, 3>> copies = largeVector(n, std::array<float, 3>{1, 2, 3});
    const std::vector<std::array<float, 3>> expected(n, {1, 2, 3});
    EXPECT_EQ(copies, expected);

    std::vector<uint32_t> grown = {7, 8, 9};
    resizeLarge(grown, n);
    ASSERT_EQ(grown.size(), n);
    EXPECT_EQ(grown[0], 7u);
    EXPECT_EQ(grown[2], 9u);
    EXPECT_EQ(grown[n - 1], 0u);

    std::vector<int> assigned = {1, 2};
    assignLarge(assigned, n, -4);
    EXPECT_EQ(assigned, std::vector<int>(n, -4));

    std::string text = "ab";
    reserveLarge(text, n);
    EXPECT_GE(text.capacity(), n);
    EXPECT_EQ(text, "ab");
  }
}

// The kernel's transparent huge page mode: "always", "madvise" or "never" (the bracketed one),
// or "" where the kernel has none.
std::string transparentHugePageMode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(in, line)) return "";
  const size_t open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos
             ? ""
             : line.substr(open + 1, close - open - 1);
}

// AnonHugePages (bytes) summed over the mappings that overlap [data, data + bytes), from
// /proc/self/smaps (madvise splits a mapping at the advised range); -1 if it has no such field.
int64_t anonHugePageBytes(const void* data, size_t bytes) {
  std::ifstream in("/proc/self/smaps");
  const auto first = reinterpret_cast<uintptr_t>(data), last = first + bytes;
  std::string line;
  bool overlaps = false, reported = false;
  int64_t total = 0;
  while (std::getline(in, line)) {
    uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream header(line);
    if (header >> std::hex >> begin >> dash >> end && dash == '-') {
      overlaps = begin < last && first < end;
      continue;
    }
    if (line.rfind("AnonHugePages:", 0) == 0) {
      reported = true;
      int64_t kiB = 0;
      std::istringstream(line.substr(14)) >> kiB;
      if (overlaps) total += kiB * 1024;
    }
  }
  return reported ? total : -1;
}

TEST(LargeArray, IsBackedByHugePagesWhereTheKernelOffersThemOnRequest) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator, not glibc's, places large blocks here";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
  GTEST_SKIP() << "a sanitizer's allocator, not glibc's, places large blocks here";
#endif
#endif
  const std::string mode = transparentHugePageMode();
  if (mode != "madvise" && mode != "always")
    GTEST_SKIP() << "transparent huge pages are '" << mode << "' here";
  constexpr size_t kBytes = size_t(64) << 20;
  std::vector<char> large = largeVector<char>(kBytes, 1);
  const int64_t huge = anonHugePageBytes(large.data(), large.size());
  if (huge < 0) GTEST_SKIP() << "/proc/self/smaps does not report AnonHugePages";
  // Without the advice a `madvise` kernel backs none of it with huge pages (0 bytes); with it,
  // nearly all. At least one huge page allows for a kernel that could not find the others.
  EXPECT_GE(huge, int64_t(kHugePageBytes)) << "mode " << mode;
}

}  // namespace
}  // namespace quadtri
