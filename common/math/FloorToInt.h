// floor(x) as an integer, for table lookups and cell numbers: the conversion truncates towards
// zero and one comparison steps down below it. Without SSE4.1 (the default build) std::floor
// is a dozen instructions and a branch that then convert anyway; this is four. The same integer
// as static_cast<Int>(std::floor(x)) wherever that is defined (x finite and in Int's range).
#pragma once

namespace prism {

template <class Int>
inline Int floorToInt(float x) {
  const Int truncated = static_cast<Int>(x);
  return x < static_cast<float>(truncated) ? truncated - 1 : truncated;
}

}  // namespace prism
