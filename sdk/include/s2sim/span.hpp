#pragma once
/// \file
/// `s2sim::Span<T>`: a view of `size()` contiguous values owned by someone else (the SDK is
/// C++17, which has no std::span). A component's state block comes as one
/// (`StepContext::state`).

#include <cassert>
#include <cstddef>

namespace s2sim {

template <class T>
class Span {
 public:
  constexpr Span() = default;
  constexpr Span(T* data, std::size_t size) : data_(data), size_(size) {}

  constexpr T* data() const { return data_; }
  constexpr std::size_t size() const { return size_; }
  constexpr bool empty() const { return size_ == 0; }
  /// The value at `i` < size(); checked by an assert in debug builds.
  constexpr T& operator[](std::size_t i) const {
    assert(i < size_ && "s2sim::Span index out of range");
    return data_[i];
  }
  /// The first value; the span must not be empty (an assert in debug builds).
  constexpr T& front() const { return (*this)[0]; }
  constexpr T* begin() const { return data_; }
  constexpr T* end() const { return data_ + size_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace s2sim
