// How much memory a command may use: the machine's memory, the default share of it, and the
// `--max-memory` option's byte sizes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace quadtri {

/// Physical memory from sysconf(_SC_PHYS_PAGES × _SC_PAGE_SIZE), lowered to the cgroup's
/// memory.max (cgroup v2) or memory.limit_in_bytes (v1) when this process runs under a smaller
/// limit (a container or a batch scheduler's job).
uint64_t physicalMemoryBytes();

/// The peak resident set of this process so far (getrusage's ru_maxrss), in bytes.
uint64_t peakResidentBytes();

/// The share of physicalMemoryBytes() a command may use unless told otherwise.
constexpr double kDefaultMemoryShare = 0.5;

/// kDefaultMemoryShare of physicalMemoryBytes().
uint64_t defaultMemoryLimit();

/// Parses BYTES (digits), or a number with the binary suffix K, M, G or T (2^10, 2^20, 2^30,
/// 2^40 bytes; "1.5G" is allowed, case does not matter, a trailing "B" or "iB" is ignored).
/// Throws Error naming `option` and what was expected; 0 or a size over 2^63 is refused.
uint64_t parseByteSize(std::string_view text, std::string_view option = "--max-memory");

/// "512 B", "12.3 KiB", "4.00 GiB": three significant digits, binary units.
std::string formatBytes(uint64_t bytes);

}  // namespace quadtri
