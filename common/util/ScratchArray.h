// A fixed-size array whose elements start unwritten: scratch space for a hot loop's plain
// records (hits, shading points) that the loop writes before it reads. A plain array of them
// would run every element's default member initializers on each call; in the renderer's packet
// loop those zero-fills (`rep stos`) were nearly half of its own time.
#pragma once

#include <cstddef>
#include <type_traits>

namespace prism {

template <class T, size_t N>
class ScratchArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "only plain records may start unwritten");

 public:
  ScratchArray() {}  // leaves the elements unwritten (the union has no active member yet)

  T& operator[](size_t i) { return items_[i]; }
  const T& operator[](size_t i) const { return items_[i]; }
  T* data() { return items_; }

 private:
  union {
    T items_[N];
  };
};

}  // namespace prism
