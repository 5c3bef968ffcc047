// Two calls at the same time, over TBB (math/parallel.h holds the loops; ThreadSanitizer sees
// a std::thread here, as it does there).
#pragma once

#include <tbb/parallel_invoke.h>

#include <exception>

#include "quadtri/math/parallel.h"

#ifdef QUADTRI_TSAN_ANNOTATE
#include <thread>
#endif

namespace quadtri {

/// Runs f() and g() at the same time and returns when both have ended (tbb::parallel_invoke;
/// under ThreadSanitizer g runs on a std::thread). An exception of f is rethrown, else one of g.
template <typename F, typename G>
void parallelInvoke(const F& f, const G& g) {
  std::exception_ptr fError, gError;
  const auto runF = [&] {
    try {
      f();
    } catch (...) {
      fError = std::current_exception();
    }
  };
  const auto runG = [&] {
    try {
      g();
    } catch (...) {
      gError = std::current_exception();
    }
  };
#ifdef QUADTRI_TSAN_ANNOTATE
  std::thread other(runG);
  runF();
  other.join();
#else
  tbb::parallel_invoke(runF, runG);
#endif
  if (fError) std::rethrow_exception(fError);
  if (gError) std::rethrow_exception(gError);
}

}  // namespace quadtri
