// quadtri's parallel loops: TBB's parallel_for, parallel_reduce and parallel_sort, and under
// ThreadSanitizer a scheduler that it can see.
//
// Debian's TBB is not built with -fsanitize=thread. The synchronisation inside it (a body
// starts after its call began; the call returns after every body ended) is invisible to
// ThreadSanitizer, while TBB's inlined task and partitioner code is instrumented in our files:
// a run reports every write before a loop and read in its bodies, and the reuse of a stack slot
// that TBB's completion counter held, as races. Annotating the bodies' boundaries is not enough
// (TBB still touches its counter after the last body's release). So under ThreadSanitizer these
// calls run their bodies on std::threads instead: as many as the TBB arena's concurrency and
// the global_control limit allow, each taking the next chunk of the range from a relaxed
// counter. Two chunks are never ordered, so a race between two bodies of one loop is still
// reported, which is what a ThreadSanitizer run is for; the calls' own edges (the caller before
// every body, every body before the return) are thread creation and join, which it sees.
// A body's exception is rethrown by the call, as TBB does. parallelSort runs std::sort there.
// Without ThreadSanitizer every call is TBB's, unchanged.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <utility>

#if defined(__SANITIZE_THREAD__)
#define QUADTRI_TSAN_ANNOTATE 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define QUADTRI_TSAN_ANNOTATE 1
#endif
#endif

#ifdef QUADTRI_TSAN_ANNOTATE
#include <sanitizer/tsan_interface.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>
#endif

namespace quadtri {

/// A happens-before edge for ThreadSanitizer through `token` (only its address is used): what
/// a thread did before releaseEdge(token) is ordered before what another thread does after
/// acquireEdge(token). For work another library runs on its own threads, whose synchronisation
/// ThreadSanitizer cannot see (Embree's calls to a user geometry's bounds function inside
/// rtcCommitScene). No-ops without ThreadSanitizer.
#ifdef QUADTRI_TSAN_ANNOTATE
inline void releaseEdge(const void* token) {
  __tsan_release(const_cast<void*>(token));
}
inline void acquireEdge(const void* token) {
  __tsan_acquire(const_cast<void*>(token));
}
#else
inline void releaseEdge(const void*) {}
inline void acquireEdge(const void*) {}
#endif

#ifdef QUADTRI_TSAN_ANNOTATE
namespace parallel_detail {

/// Threads a loop may use: the current arena's concurrency within the global_control limit.
inline size_t threads() {
  const size_t arena = size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  const size_t limit =
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return std::max<size_t>(1, std::min(arena, limit));
}

/// Runs chunk(c) for every c in [0, chunks) on up to threads() threads (the caller one of
/// them); rethrows the first exception once every thread has stopped.
template <typename Chunk>
void runChunks(size_t chunks, const Chunk& chunk) {
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  const auto work = [&] {
    for (size_t c; (c = next.fetch_add(1, std::memory_order_relaxed)) < chunks;) {
      try {
        chunk(c);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(errorMutex);
        if (!error) error = std::current_exception();
        next.store(chunks, std::memory_order_relaxed);
      }
    }
  };
  std::vector<std::thread> pool;
  const size_t n = std::min(threads(), chunks);
  for (size_t i = 1; i < n; ++i) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

/// [first, last) in chunks of at least `grain`, about eight per thread.
inline size_t chunkSize(size_t count, size_t grain) {
  return std::max({grain, size_t(1), count / (8 * threads())});
}

}  // namespace parallel_detail
#endif

/// f(i) for every i in [first, last), in parallel (tbb::parallel_for's index form).
template <typename Index, typename F>
void parallelFor(Index first, Index last, const F& f) {
#ifdef QUADTRI_TSAN_ANNOTATE
  if (!(first < last)) return;
  const size_t count = size_t(last - first), size = parallel_detail::chunkSize(count, 1);
  parallel_detail::runChunks((count + size - 1) / size, [&](size_t c) {
    const size_t end = std::min(count, (c + 1) * size);
    for (size_t i = c * size; i < end; ++i) f(Index(first + Index(i)));
  });
#else
  tbb::parallel_for(first, last, f);
#endif
}

/// f(range) over sub-ranges of a tbb::blocked_range (tbb::parallel_for's range form), with an
/// optional partitioner (e.g. tbb::simple_partitioner() for one grain per task).
template <typename Value, typename F, typename... Partitioner>
void parallelForRange(const tbb::blocked_range<Value>& range, const F& f,
                      Partitioner&&... partitioner) {
#ifdef QUADTRI_TSAN_ANNOTATE
  const size_t count = range.size(), size = parallel_detail::chunkSize(count, range.grainsize());
  parallel_detail::runChunks((count + size - 1) / size, [&](size_t c) {
    const Value begin = range.begin() + Value(c * size);
    f(tbb::blocked_range<Value>(begin, range.begin() + Value(std::min(count, (c + 1) * size)),
                                range.grainsize()));
  });
  ((void)partitioner, ...);
#else
  tbb::parallel_for(range, f, std::forward<Partitioner>(partitioner)...);
#endif
}

/// tbb::parallel_reduce's functional form: body(range, partial) returns the partial result
/// with the range added, join(a, b) combines two (in range order).
template <typename Value, typename T, typename Body, typename Join>
T parallelReduce(const tbb::blocked_range<Value>& range, const T& identity, const Body& body,
                 const Join& join) {
#ifdef QUADTRI_TSAN_ANNOTATE
  const size_t count = range.size(), size = parallel_detail::chunkSize(count, range.grainsize());
  const size_t chunks = (count + size - 1) / size;
  std::vector<T> partial(chunks, identity);
  parallel_detail::runChunks(chunks, [&](size_t c) {
    const Value begin = range.begin() + Value(c * size);
    partial[c] =
        body(tbb::blocked_range<Value>(
                 begin, range.begin() + Value(std::min(count, (c + 1) * size)), range.grainsize()),
             identity);
  });
  T result = identity;
  for (const T& p : partial) result = join(result, p);
  return result;
#else
  return tbb::parallel_reduce(range, identity, body, join);
#endif
}

/// Sorts [first, last) with `less` (tbb::parallel_sort; std::sort under ThreadSanitizer).
template <typename It, typename Less>
void parallelSort(It first, It last, const Less& less) {
#ifdef QUADTRI_TSAN_ANNOTATE
  std::sort(first, last, less);
#else
  tbb::parallel_sort(first, last, less);
#endif
}

template <typename It>
void parallelSort(It first, It last) {
  parallelSort(first, last, std::less<>());
}

}  // namespace quadtri
