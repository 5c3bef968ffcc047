// A vector of at most N elements stored inline: for small per-triangle structures (a convex
// cell's planes, vertices and faces) that are built once per triangle, on every thread, by the
// million. std::vector would allocate for each; this never does, and a pushed element past N is
// a logic error the caller rules out by construction (asserted in debug builds). Elements are
// meant to be small values (numbers, fixed-size Eigen vectors, other FixedVectors).
#pragma once

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <type_traits>

namespace quadtri {

template <class T, size_t N>
class FixedVector {
 public:
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  FixedVector() = default;
  // Copies only the elements in use: the rest of the storage is never read, nor initialised.
  FixedVector(const FixedVector& other) { assign(other.begin(), other.end()); }
  FixedVector& operator=(const FixedVector& other) {
    if (this != &other) assign(other.begin(), other.end());
    return *this;
  }
  FixedVector(std::initializer_list<T> values) { assign(values.begin(), values.end()); }
  template <class It>
  requires(!std::is_integral_v<It>) FixedVector(It first, It last) { assign(first, last); }

  template <class It>
  void assign(It first, It last) {
    size_ = 0;
    for (; first != last; ++first) push_back(*first);
  }

  static constexpr size_t capacity() { return N; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == N; }

  void clear() { size_ = 0; }
  void push_back(const T& value) {
    assert(size_ < N);
    items_[size_] = value;
    ++size_;
  }
  /// Grows or shrinks to n ≤ N elements; new elements are assigned T{} (zero for numbers and
  /// for FixedVectors, empty; Eigen's fixed-size vectors stay uninitialised by T{}).
  void resize(size_t n) {
    assert(n <= N);
    for (size_t i = size_; i < n; ++i) items_[i] = T{};
    size_ = decltype(size_)(n);
  }

  T& operator[](size_t i) {
    assert(i < size_);
    return items_[i];
  }
  const T& operator[](size_t i) const {
    assert(i < size_);
    return items_[i];
  }
  T& back() { return (*this)[size_ - 1]; }
  const T& back() const { return (*this)[size_ - 1]; }

  T* data() { return items_.data(); }
  const T* data() const { return items_.data(); }
  iterator begin() { return items_.data(); }
  iterator end() { return items_.data() + size_; }
  const_iterator begin() const { return items_.data(); }
  const_iterator end() const { return items_.data() + size_; }

 private:
  std::array<T, N> items_;  // default-initialised: only [0, size_) is ever read
  std::conditional_t<(N < 256), uint8_t, size_t> size_ = 0;
};

}  // namespace quadtri
