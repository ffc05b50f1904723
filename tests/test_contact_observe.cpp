// What is observed of a state's contacts (src/sim/contact_observe.cpp): the self-contact pairs and the
// closest self-approach of a hairpin against brute force, obstacle contacts counted per element, and the
// force per node of a snapshot.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "physics_support.hpp"
#include "rootsim/contact.hpp"
#include "rootsim/contact_observe.hpp"

using namespace rootsim;
using namespace rootsim::test;

TEST_CASE("contact counts: pairs closer than 2R are in contact, the closest approach is the smallest pair distance / R within 3R, as brute force finds them") {
  RodParams p;
  Environment env;
  env.plane.enabled = false;
  for (const double gap : {1.8, 2.5}) {
    INFO("legs " << gap << " R apart");
    const RodState s = hairpin(p, gap * p.radius);
    ContactWorkspace cw;
    const ContactCounts c = countContacts(p, env, s, cw);
    int touching = 0;
    double closest = std::numeric_limits<double>::quiet_NaN();
    for (const auto& [i, j] : closePairs(p, s, 3.0 * p.radius)) {
      const double d = pairDistance(s, i, j);
      touching += d < 2.0 * p.radius;
      if (std::isnan(closest) || d / p.radius < closest) closest = d / p.radius;
    }
    CHECK(c.selfContacts == touching);
    ROOTSIM_CHECK_REL("closest approach / R", c.minSelfDistance, closest, 1e-12);
    CHECK(closest <= gap + 1e-12);  // the legs, or closer across a corner of the hairpin
    if (gap < 2.0) CHECK(touching >= 24);  // every element of a leg touches the other leg
    else CHECK(touching == 0);
    CHECK(c.obstacleContacts == 0);
  }
  // a straight rod: nothing within 3R, no closest approach
  const Cantilever straight(40);
  ContactWorkspace cw;
  CHECK(std::isnan(countContacts(p, env, straight.s, cw).minSelfDistance));
  // self-contact off: nothing counted
  env.selfContact.enabled = false;
  const RodState s = hairpin(p, 1.8 * p.radius);
  CHECK(countContacts(p, env, s, cw).selfContacts == 0);
}

TEST_CASE("contact observables: the force per node is zero without contact and nonzero exactly on the nodes of touching pairs") {
  RodParams p;
  Environment env;
  env.plane.enabled = false;
  const RodState s = hairpin(p, 1.8 * p.radius);
  const ContactObservables o = observeContacts(p, env, s);
  REQUIRE(o.perNode.cols() == s.nodes());
  std::vector<int> touched(static_cast<size_t>(s.nodes()), 0);
  for (const auto& [i, j] : closePairs(p, s, 2.0 * p.radius))
    for (int a : {i, i + 1, j, j + 1}) touched[static_cast<size_t>(a)] = 1;
  for (int k = 0; k < s.nodes(); ++k) {
    INFO("node " << k);
    // perNode rows: plate, self-contact, obstacles
    CHECK(o.perNode(0, k) == 0.0);
    CHECK(o.perNode(2, k) == 0.0);
    if (!touched[static_cast<size_t>(k)]) CHECK(o.perNode(1, k) == 0.0);
  }
  CHECK(o.perNode.row(1).maxCoeff() > 0.0);
  CHECK(o.selfContacts > 0);
  const ContactObservables apart = observeContacts(p, env, hairpin(p, 2.5 * p.radius));
  CHECK(apart.perNode.cwiseAbs().maxCoeff() == 0.0);
}
