// What every fuzz harness shares: the rule that an input gives either a result or a
// quadtri::Error (a clean error with a message), and a scratch folder for parsers that read
// files. Any other exception escapes LLVMFuzzerTestOneInput and aborts: libFuzzer and the
// replay driver (replay_main.cpp) both report it as a crash.
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "quadtri/math/error.h"

namespace quadtri::fuzz {

/// Runs `f`; a quadtri::Error is the expected way to refuse an input and is swallowed.
template <typename F>
int runClean(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    // QUADTRI_FUZZ_VERBOSE=1 prints each refusal (to see what an input is refused for).
    if (std::getenv("QUADTRI_FUZZ_VERBOSE")) std::fprintf(stderr, "refused: %s\n", e.what());
  }
  return 0;
}

/// A broken promise (a NaN in a result that was returned without an error): abort so that the
/// fuzzer keeps the input.
[[noreturn]] inline void broken(const char* what) {
  std::fprintf(stderr, "quadtri fuzz: %s\n", what);
  std::abort();
}

/// This process's scratch folder, created on first use.
inline const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    auto d =
        std::filesystem::temp_directory_path() / ("quadtri-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

/// Writes the input to `name` in the scratch folder and returns its path.
inline std::filesystem::path writeScratch(const std::string& name, const uint8_t* data,
                                          size_t size) {
  const std::filesystem::path path = scratchDir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

inline std::string_view asText(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace quadtri::fuzz
