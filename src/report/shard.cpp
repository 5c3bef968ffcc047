#include "quadtri/report/shard.h"

#include <algorithm>
#include <cctype>

#include "quadtri/math/error.h"

namespace quadtri {

Shard Shard::parse(const std::string& text) {
  const size_t slash = text.find('/');
  Shard shard;
  auto parsePart = [&](const std::string& part, size_t& out) {
    if (part.empty() || part.size() > 9 ||
        !std::all_of(part.begin(), part.end(), [](unsigned char c) { return std::isdigit(c); }))
      return false;
    out = std::stoul(part);
    return true;
  };
  if (slash == std::string::npos || !parsePart(text.substr(0, slash), shard.index) ||
      !parsePart(text.substr(slash + 1), shard.count) || shard.count == 0 || shard.index == 0 ||
      shard.index > shard.count)
    fail("--shard {}: expected I/N with 1 <= I <= N, e.g. 2/4", text);
  return shard;
}

}  // namespace quadtri
