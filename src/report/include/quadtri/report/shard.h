// "--shard I/N": one of N processes' share of a list (a corpus for `study`, a figure's rows for
// `figure`), item i going to shard i mod N + 1.
#pragma once

#include <cstddef>
#include <string>

namespace quadtri {

struct Shard {
  size_t index = 1, count = 1;
  /// Parses "I/N" with 1 ≤ I ≤ N; throws Error otherwise.
  static Shard parse(const std::string& text);
  bool holds(size_t item) const { return item % count == index - 1; }
  std::string toString() const { return std::to_string(index) + "/" + std::to_string(count); }
};

}  // namespace quadtri
