// the hot loop's workspaces grow only past their high-water mark, geometrically (rootsim/high_water.hpp)
#include <doctest/doctest.h>

#include <vector>

#include "rootsim/high_water.hpp"
#include "physics_support.hpp"

using rootsim::test::gAllocs;

TEST_CASE("high water: a vector that has seen its largest size allocates nothing, and grows by doubling past it") {
  std::vector<int> v;
  rootsim::resizeHighWater(v, 100);
  CHECK(v.size() == 100);
  const size_t room = v.capacity();
  CHECK(room >= 100);
  // smaller and equal sizes, assignments included: no allocation
  const std::vector<int> src(60, 7);
  const long before = gAllocs.load();
  rootsim::resizeHighWater(v, 10);
  rootsim::resizeHighWater(v, 100);
  rootsim::assignHighWater(v, src.begin(), src.end());
  rootsim::reserveHighWater(v, room);
  CHECK(gAllocs.load() - before == 0);
  CHECK(v.size() == 60);
  CHECK(v[59] == 7);
  // one past the mark: at least twice the room, so n growths by one cost O(log n) allocations
  rootsim::resizeHighWater(v, room + 1);
  CHECK(v.capacity() >= 2 * room);
  long grown = 0;
  for (size_t n = v.size(); n < 64 * room; ++n) {
    const long b = gAllocs.load();
    rootsim::resizeHighWater(v, n + 1);
    grown += gAllocs.load() - b;
  }
  CHECK(grown <= 6);  // 2 room -> 64 room: five doublings
  CHECK(grown >= 5);
}
