// What the Newton solver needs of self-contact (src/sim/contact_newton.cpp): the nodes a contact couples
// off the band and how far back the window reaches, against brute force on a hairpin. Each pair's
// stiffness is checked against central differences of the whole Jacobian in test_contact.cpp.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "physics_support.hpp"
#include "rootsim/contact.hpp"
#include "rootsim/contact_newton.hpp"

using namespace rootsim;
using namespace rootsim::test;

TEST_CASE("contact Newton: the nodes of every element pair closer than 2R are marked, no others") {
  RodParams p;
  Environment env;
  env.plane.enabled = false;
  for (const double gap : {1.8, 2.5}) {
    INFO("legs " << gap << " R apart");
    const RodState s = hairpin(p, gap * p.radius);
    ContactWorkspace cw;
    cw.resize(s.elements());
    markSelfContactNodes(p, env, s, cw);
    std::vector<std::uint8_t> want(static_cast<size_t>(s.nodes()), 0);
    for (const auto& [i, j] : closePairs(p, s, 2.0 * p.radius))
      for (int a : {i, i + 1, j, j + 1}) want[static_cast<size_t>(a)] = 1;
    CHECK(cw.contactNode == want);
    if (gap < 2.0) CHECK(std::count(want.begin(), want.end(), 1) >= 40);  // most of both legs
    else CHECK(std::count(want.begin(), want.end(), 1) == 0);
  }
}

TEST_CASE("contact Newton: the window reaches back to the lowest node of a watched pair whose younger element reaches its start") {
  RodParams p;
  Environment env;
  env.plane.enabled = false;
  const RodState s = hairpin(p, 2.5 * p.radius);
  ContactWorkspace cw;
  const auto pairs = closePairs(p, s, 3.0 * p.radius);
  REQUIRE(!pairs.empty());
  for (const int from : {0, 30, s.nodes() - 10, s.nodes() - 1, s.nodes() + 5}) {
    int want = s.nodes();
    for (const auto& [i, j] : pairs)
      if (j + 1 >= from) want = std::min(want, i);
    INFO("from node " << from);
    CHECK(firstNodeNearContact(p, env, s, cw, from) == want);
  }
  // the first leg's base is watched against the second leg's end: the window of the tip reaches it
  CHECK(firstNodeNearContact(p, env, s, cw, s.nodes() - 1) == 0);
  env.selfContact.enabled = false;
  CHECK(firstNodeNearContact(p, env, s, cw, 0) == s.nodes());
}
