// What a picture needs of one moment (src/sim/snapshot.cpp): a state's snapshot (directors, radius
// R / sqrt(e), |kappa0| per node), a plate's roots merged into one snapshot and taken apart again, and
// the snapshot nearest a time.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "physics_support.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;
using namespace rootsim::test;

namespace {
// a snapshot of n elements whose every field tells its root and index apart
Snapshot numbered(int n, double tag, bool contact) {
  Snapshot s;
  s.step = static_cast<int>(tag);
  s.timeH = tag;
  s.x.resize(3, n + 1);
  s.d1.resize(3, n);
  s.d3.resize(3, n);
  s.radius.resize(n);
  s.kappa0.resize(n + 1);
  s.plateForce.resize(n + 1);
  for (int i = 0; i <= n; ++i) {
    s.x.col(i) = Vec3(tag, i, 0);
    s.kappa0[i] = 100 * tag + i;
    s.plateForce[i] = -(100 * tag + i);
  }
  for (int i = 0; i < n; ++i) {
    s.d1.col(i) = Vec3(tag, i, 1);
    s.d3.col(i) = Vec3(tag, i, 3);
    s.radius[i] = 1000 * tag + i;
  }
  if (contact) s.contactForce = s.x * 2.0;
  return s;
}
}  // namespace

TEST_CASE("snapshot of a state: positions, d1 and d3 rows of Q, radius R / sqrt(e), |kappa0| at interior nodes and 0 at the ends") {
  Cantilever c(6);
  c.s.time = 2.5 * units::hour;
  for (int j = 0; j < c.s.kappa0.cols(); ++j) c.s.kappa0.col(j) = Vec3(30.0 * j, 40.0 * j, 7.0);
  c.ws.resize(c.s.elements());
  computeStrains(c.p, c.s, c.ws.strains);
  c.ws.strains.e.setLinSpaced(6, 1.0, 1.5);
  const Snapshot sn = makeSnapshot(c.p, c.s, c.ws.strains, 9);
  CHECK(sn.step == 9);
  ROOTSIM_CHECK_REL("time", sn.timeH, 2.5, 1e-15);
  CHECK((sn.x - c.s.x).norm() == 0.0);
  for (int i = 0; i < 6; ++i) {
    CHECK((sn.d1.col(i) - c.s.Q[static_cast<size_t>(i)].row(0).transpose()).norm() == 0.0);
    CHECK((sn.d3.col(i) - c.s.Q[static_cast<size_t>(i)].row(2).transpose()).norm() == 0.0);
    ROOTSIM_CHECK_REL("radius", sn.radius[i], c.p.radius / std::sqrt(1.0 + 0.1 * i), 1e-14);
  }
  REQUIRE(sn.kappa0.size() == 7);
  CHECK(sn.kappa0[0] == 0.0);
  CHECK(sn.kappa0[6] == 0.0);
  for (int j = 0; j < 5; ++j) ROOTSIM_CHECK_REL("|kappa0| in the plane of d1, d2", sn.kappa0[j + 1], 50.0 * j, 1e-15);
  // without strains the radius is the rest radius
  const Snapshot rest = makeSnapshot(c.p, c.s, RodStrains{}, 0);
  for (int i = 0; i < 6; ++i) CHECK(rest.radius[i] == c.p.radius);
}

TEST_CASE("merged roots: nodes in turn, one joining element per root after the first, and rootOf gives each root back exactly") {
  const std::vector<Snapshot> roots{numbered(4, 1, true), numbered(2, 2, true), numbered(5, 3, true)};
  const Snapshot m = mergeRoots(roots);
  CHECK(rootCount(m) == 3);
  CHECK(m.rootStarts == std::vector<int>{5, 8});
  CHECK(m.x.cols() == 5 + 3 + 6);
  CHECK(m.elements() == m.x.cols() - 1);
  CHECK(m.step == 1);
  // the joining element before root 2 carries root 2's first element's fields
  CHECK(m.radius[4] == 2000.0);
  CHECK(m.radius[7] == 3000.0);
  for (int k = 0; k < 3; ++k) {
    const Snapshot r = rootOf(m, k);
    const Snapshot& want = roots[static_cast<size_t>(k)];
    CHECK(r.x == want.x);
    CHECK(r.d1 == want.d1);
    CHECK(r.d3 == want.d3);
    CHECK(r.radius == want.radius);
    CHECK(r.kappa0 == want.kappa0);
    CHECK(r.plateForce == want.plateForce);
    CHECK(r.contactForce == want.contactForce);
  }
  // one root is its own merge; a root without contact forces leaves them out of the merge
  CHECK(rootOf(mergeRoots({roots[0]}), 0).x == roots[0].x);
  const Snapshot partial = mergeRoots({numbered(3, 1, true), numbered(3, 2, false)});
  CHECK(partial.contactForce.cols() == 0);
  CHECK(partial.kappa0.size() == 8);
  CHECK(mergeRoots({}).x.cols() == 0);
}

TEST_CASE("nearest snapshot: the nearest time, ties to the earlier one, the ends beyond the range, none refused") {
  const std::vector<double> t{0.0, 1.0, 2.0, 4.0};
  CHECK(nearestSnapshot(t, -3.0) == 0);
  CHECK(nearestSnapshot(t, 0.4) == 0);
  CHECK(nearestSnapshot(t, 0.5) == 0);
  CHECK(nearestSnapshot(t, 0.6) == 1);
  CHECK(nearestSnapshot(t, 2.0) == 2);
  CHECK(nearestSnapshot(t, 3.0) == 2);
  CHECK(nearestSnapshot(t, 3.1) == 3);
  CHECK(nearestSnapshot(t, 99.0) == 3);
  CHECK_THROWS_AS(nearestSnapshot({}, 1.0), std::invalid_argument);
}
