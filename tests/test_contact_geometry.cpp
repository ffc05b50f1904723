// The geometry of the contact pieces (src/sim/contact_geometry.cpp): the closest points of two segments
// and the self-contact Verlet list, against brute force over every element pair.
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "contact_geometry.hpp"
#include "physics_support.hpp"
#include "rootsim/contact.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
using namespace rootsim::test;

TEST_CASE("segment closest points: crossing, parallel overlap and end cases") {
  double a = 0, b = 0;
  closestSegmentPoints(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -1, 1), Vec3(0.5, 1, 1), a, b);
  ROOTSIM_CHECK_CLOSE(a, 0.75, kRoundoff);
  ROOTSIM_CHECK_CLOSE(b, 0.5, kRoundoff);
  // parallel, overlapping over x in [0, 1]: the middle of the overlap
  closestSegmentPoints(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(-1, 0, 1), Vec3(1, 0, 1), a, b);
  ROOTSIM_CHECK_CLOSE(a, 0.25, kRoundoff);
  ROOTSIM_CHECK_CLOSE(b, 0.75, kRoundoff);
  // end to end
  closestSegmentPoints(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 2, 0), a, b);
  ROOTSIM_CHECK_CLOSE(a, 1.0, kRoundoff);
  ROOTSIM_CHECK_CLOSE(b, 0.0, kRoundoff);
}

TEST_CASE("self-contact list: the Verlet list holds the pairs within 2R + skin as brute force finds them, sorted, and serves until a node moves skin/2") {
  RodParams p;
  for (const double gap : {2.5, 3.5}) {
    INFO("legs " << gap << " R apart");
    RodState s = hairpin(p, gap * p.radius);
    ContactWorkspace cw;
    cw.resize(s.elements());
    contact_detail::updatePairs(p, s, cw);
    // pairs exactly at the reach may fall either side by round-off: elements 3R apart along one straight leg
    // are 3R apart in space
    const double reach = (2.0 + contact_detail::kSkinRadii) * p.radius;
    const auto inner = closePairs(p, s, reach * (1 - 1e-9)), want = closePairs(p, s, reach * (1 + 1e-9));
    CHECK(std::includes(cw.pairs.begin(), cw.pairs.end(), inner.begin(), inner.end()));
    CHECK(std::includes(want.begin(), want.end(), cw.pairs.begin(), cw.pairs.end()));
    CHECK(std::is_sorted(cw.pairs.begin(), cw.pairs.end()));
    CHECK(cw.builds == 1);
    // pairs of an element of the first leg (elements 0-23) and one of the second (the last 24)
    long across = 0;
    for (const auto& [i, j] : cw.pairs) across += i < 24 && j >= s.elements() - 24;
    if (gap == 2.5) CHECK(across >= 24);  // every element of one leg lies within 3R of the other leg
    else CHECK(across == 0);
    // a rigid shift by 0.4 skin keeps the list; 0.6 skin rebuilds it
    const double skin = contact_detail::kSkinRadii * p.radius;
    s.x.colwise() += Vec3(0, 0, 0.4 * skin);
    contact_detail::updatePairs(p, s, cw);
    CHECK(cw.builds == 1);
    s.x.colwise() += Vec3(0, 0, 0.2 * skin);
    contact_detail::updatePairs(p, s, cw);
    CHECK(cw.builds == 2);
    CHECK(std::includes(want.begin(), want.end(), cw.pairs.begin(), cw.pairs.end()));
    // a grown rod (a longer rest length) rebuilds whatever moved
    s.S[s.elements()] += 1e-9;
    contact_detail::updatePairs(p, s, cw);
    CHECK(cw.builds == 3);
  }
}
