#include "quadtri/io/memory_limit.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>

#include "quadtri/math/error.h"

namespace quadtri {
namespace {

// The first line of a cgroup limit file as bytes; 0 when absent, unreadable or "max".
uint64_t readCgroupLimit(const char* path) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word)) return 0;
  uint64_t value = 0;
  const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  return ec == std::errc() && ptr == word.data() + word.size() ? value : 0;
}

}  // namespace

uint64_t physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
  uint64_t bytes = pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
  for (const char* path :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    const uint64_t limit = readCgroupLimit(path);
    if (limit > 0 && (bytes == 0 || limit < bytes)) bytes = limit;
  }
  return bytes;
}

uint64_t defaultMemoryLimit() {
  return uint64_t(double(physicalMemoryBytes()) * kDefaultMemoryShare);
}

uint64_t parseByteSize(std::string_view text, std::string_view option) {
  const auto bad = [&] {
    fail(
        "{} {}: expected a size in bytes, or a number with K, M, G or T (binary units), e.g. "
        "8G or 512M",
        option, text);
  };
  std::string_view number = text;
  while (!number.empty() && std::isspace(static_cast<unsigned char>(number.back())))
    number.remove_suffix(1);
  const auto dropSuffix = [&](std::string_view suffix) {
    if (number.size() < suffix.size()) return false;
    for (size_t i = 0; i < suffix.size(); ++i)
      if (std::toupper(static_cast<unsigned char>(number[number.size() - suffix.size() + i])) !=
          std::toupper(static_cast<unsigned char>(suffix[i])))
        return false;
    number.remove_suffix(suffix.size());
    return true;
  };
  if (!dropSuffix("iB")) dropSuffix("B");
  double scale = 1.0;
  if (!number.empty()) {
    static constexpr std::pair<char, double> units[] = {
        {'K', 0x1p10}, {'M', 0x1p20}, {'G', 0x1p30}, {'T', 0x1p40}};
    for (const auto& [letter, factor] : units)
      if (std::toupper(static_cast<unsigned char>(number.back())) == letter) {
        scale = factor;
        number.remove_suffix(1);
        break;
      }
  }
  if (number.empty() || !std::isdigit(static_cast<unsigned char>(number.front()))) bad();
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), value,
                                         std::chars_format::fixed);
  if (ec != std::errc() || ptr != number.data() + number.size()) bad();
  const double bytes = std::floor(value * scale);
  if (!(bytes >= 1.0)) fail("{} {}: expected a positive size (at least 1 byte)", option, text);
  if (!(bytes <= 0x1p63)) fail("{} {}: expected a size under 2^63 bytes", option, text);
  return uint64_t(bytes);
}

uint64_t peakResidentBytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return uint64_t(usage.ru_maxrss) * 1024;  // Linux reports kibibytes
}

std::string formatBytes(uint64_t bytes) {
  if (bytes < 1024) return fmt::format("{} B", bytes);
  static constexpr const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = double(bytes) / 1024.0;
  size_t unit = 0;
  while (value >= 1024.0 && unit + 1 < std::size(units)) {
    value /= 1024.0;
    ++unit;
  }
  const int decimals = value < 10.0 ? 2 : value < 100.0 ? 1 : 0;
  return fmt::format("{:.{}f} {}", value, decimals, units[unit]);
}

}  // namespace quadtri
