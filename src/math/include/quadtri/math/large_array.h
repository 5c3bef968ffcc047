// Large arrays that are written right after they are allocated (a model's patches, a mesh's
// edge adjacency, its loaded vertices): each asks the kernel for transparent huge pages before
// its first write.
//
// A fresh allocation is mapped page by page as it is first written. With 4 KiB pages that is
// a fault per page, and under virtualisation a fault costs several microseconds: on the
// 2-core test machine a 1,000,000-triangle conversion spent most of its time there
// (quadtri_bench Convert at 2 threads, `phong` 1.11 s before the advice, 0.21 s after).
// madvise(MADV_HUGEPAGE) on the array's 2 MiB-aligned interior makes that one fault per 2 MiB
// where the system's THP setting is `madvise` or `always`; where it is `never`, or on other
// systems, the call changes nothing. Small arrays are left alone, so a huge page never backs a
// few bytes.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <vector>

#include "quadtri/math/parallel.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace quadtri {

inline constexpr size_t kHugePageBytes = size_t(2) << 20;
/// Arrays of at least this many bytes ask for huge pages.
inline constexpr size_t kLargeArrayBytes = 2 * kHugePageBytes;

/// Advises huge pages for the whole 2 MiB pages inside [data, data + bytes), when bytes is at
/// least kLargeArrayBytes. Advice only: the memory is the caller's, its contents unchanged, and
/// a refusal (no THP in this kernel) is not an error.
inline void adviseHugePages(const void* data, size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (data == nullptr || bytes < kLargeArrayBytes) return;
  const uintptr_t first = reinterpret_cast<uintptr_t>(data);
  const uintptr_t begin = (first + kHugePageBytes - 1) & ~uintptr_t(kHugePageBytes - 1);
  const uintptr_t end = (first + bytes) & ~uintptr_t(kHugePageBytes - 1);
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

/// Maps the pages of [data, data + bytes) on every thread: the threads share the 2 MiB parts
/// and write a zero to the first byte of each 4 KiB page of theirs, so the kernel's faults and
/// page clearing run in parallel instead of inside the one thread that constructs the elements
/// next. For storage that holds no object yet (reserveLarge's fresh allocation).
inline void prefaultLarge(void* data, size_t bytes) {
  if (data == nullptr || bytes < kLargeArrayBytes) return;
  auto* base = static_cast<unsigned char*>(data);
  const size_t parts = (bytes + kHugePageBytes - 1) / kHugePageBytes;
  parallelFor(size_t(0), parts, [&](size_t i) {
    unsigned char* begin = base + i * kHugePageBytes;
    const size_t length = std::min(kHugePageBytes, bytes - i * kHugePageBytes);
    for (size_t at = 0; at < length; at += 4096) begin[at] = 0;
  });
}

/// v.reserve(n) for a vector-like container; a new allocation of a large array asks for huge
/// pages before anything is written to it (the elements v held are then moved there). The
/// pages of the first `mapped` elements (all n by default) are mapped on every thread
/// (prefaultLarge); the rest, room that may stay unused, only where it is written (its writer
/// may call prefaultLarge on the part it is about to fill).
template <class Vector>
void reserveLarge(Vector& v, size_t n, size_t mapped = SIZE_MAX) {
  if (n <= v.capacity()) return;
  if (v.empty()) {
    v.reserve(n);
    adviseHugePages(v.data(), n * sizeof(typename Vector::value_type));
    prefaultLarge(v.data(), std::min(n, mapped) * sizeof(typename Vector::value_type));
    return;
  }
  Vector fresh;
  fresh.reserve(n);
  adviseHugePages(fresh.data(), n * sizeof(typename Vector::value_type));
  fresh.insert(fresh.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
  v.swap(fresh);
}

/// v.resize(n), the new storage advised as reserveLarge does.
template <class Vector>
void resizeLarge(Vector& v, size_t n) {
  reserveLarge(v, n);
  v.resize(n);
}

/// v.assign(n, value), the new storage advised as reserveLarge does.
template <class Vector, class T>
void assignLarge(Vector& v, size_t n, const T& value) {
  if (n > v.capacity()) {
    v.clear();
    reserveLarge(v, n);
  }
  v.assign(n, value);
}

/// A vector of n value-initialised elements, or n copies of `value`, advised as reserveLarge
/// does.
template <class T>
std::vector<T> largeVector(size_t n) {
  std::vector<T> v;
  resizeLarge(v, n);
  return v;
}
template <class T>
std::vector<T> largeVector(size_t n, const T& value) {
  std::vector<T> v;
  assignLarge(v, n, value);
  return v;
}

}  // namespace quadtri
