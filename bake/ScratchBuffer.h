#pragma once
#include <algorithm>
#include <cstddef>
#include <memory>

namespace baker {

// An array that only grows and is never cleared: per-thread scratch space, such as the short
// wavefronts a bake traces by the million (where a std::vector's initialisation and per-element
// capacity checks cost as much as the work on the elements) and a brick's sample matrix (where
// memory mapped afresh for each brick costs a page clearing per 4 KiB).
template <typename T>
class ScratchBuffer {
 public:
  // Room for n elements. What the buffer held is lost when it has to grow.
  T* reserve(std::size_t n) {
    if (capacity_ < n) {
      capacity_ = std::max(n, 2 * capacity_);
      data_.reset(new T[capacity_]);
    }
    return data_.get();
  }

 private:
  std::unique_ptr<T[]> data_;
  std::size_t capacity_ = 0;
};

}  // namespace baker
