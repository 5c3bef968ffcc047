// The one exception type quadtri throws for bad input; its message names the file, line or
// element and what was expected.
#pragma once

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace quadtri {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace quadtri
