// The relaxation's scratch memory (src/sim/relax.cpp): RelaxWorkspace::resize sizes every field to the
// rod it is given, so that a solver handed a workspace of another rod (a split, a plate's next root)
// writes inside it, and a workspace sized once allocates nothing when forces are evaluated again.
#include <doctest/doctest.h>

#include "physics_support.hpp"
#include "rootsim/relax.hpp"

using namespace rootsim;
using namespace rootsim::test;

TEST_CASE("relax workspace: resize(n) gives n + 1 nodes and n elements to every field, growing and shrinking") {
  RelaxWorkspace ws;
  for (int n : {3, 17, 2}) {
    ws.resize(n);
    CHECK(ws.force.cols() == n + 1);
    CHECK(ws.torque.cols() == n);
    CHECK(ws.mass.size() == n + 1);
    CHECK(ws.invMass.size() == n + 1);
    CHECK(ws.inertia.cols() == n);
    CHECK(ws.invInertia.cols() == n);
    CHECK(ws.xStart.cols() == n + 1);
    CHECK(ws.strains.l.size() == n);
    CHECK(ws.strains.t.cols() == n);
    CHECK(ws.strains.kappa.cols() == n - 1);
    CHECK(ws.strains.m.cols() == n - 1);
    CHECK(ws.contact.obstacleNormal.cols() == n + 1);
  }
}

TEST_CASE("relax workspace: a workspace sized for the rod evaluates its forces without allocating, again and again") {
  Cantilever c(12);
  c.env.gravity = Vec3(0, 0, -9.81);
  c.ws.resize(c.s.elements());
  computeForces(c.p, c.env, c.s, false, c.ws);  // warm-up: the contact lists take their capacity
  const long before = gAllocs.load();
  for (int k = 0; k < 5; ++k) computeForces(c.p, c.env, c.s, false, c.ws);
  CHECK(gAllocs.load() - before == 0);
}
