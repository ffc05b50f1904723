#pragma once
// The workspaces of the hot loop keep their storage from step to step: a vector's storage grows only past
// its high-water mark, and then geometrically (at least doubling), so a workspace that has seen its largest
// size allocates nothing and one that keeps growing allocates O(log size) times.
#include <algorithm>
#include <cstddef>

namespace rootsim {

// room for n elements in v (its size unchanged)
template <class V>
void reserveHighWater(V& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(std::max(n, 2 * v.capacity()));
}

// v resized to n, its storage grown as reserveHighWater
template <class V>
void resizeHighWater(V& v, std::size_t n) {
  reserveHighWater(v, n);
  v.resize(n);
}

// v = [first, last), its storage grown as reserveHighWater
template <class V, class It>
void assignHighWater(V& v, It first, It last) {
  resizeHighWater(v, static_cast<std::size_t>(last - first));
  std::copy(first, last, v.begin());
}

}  // namespace rootsim
