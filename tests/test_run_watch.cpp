// What a run watches across its growth steps (src/sim/run_watch.cpp): the first sideways snap, the
// turning time interpolated linearly in the tip angle, and the extremes of the steps.
#include <doctest/doctest.h>

#include <cmath>

#include "physics_support.hpp"
#include "rootsim/run_watch.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;

namespace {
StepRecord record(int step, double timeH, double thetaDeg, long substeps = 0, int selfContacts = 0,
                  double minSelf = std::numeric_limits<double>::quiet_NaN()) {
  StepRecord r;
  r.step = step;
  r.timeH = timeH;
  r.thetaTip = thetaDeg * units::deg;
  r.substeps = substeps;
  r.selfContacts = selfContacts;
  r.minSelfDistance = minSelf;
  return r;
}
}  // namespace

TEST_CASE("run watch: the turning time is where theta crosses 0, linear between the two steps around it") {
  RunWatch w;
  w.start(record(0, 0.0, -40.0));
  CHECK(std::isnan(w.snapVertical));
  w.see(record(1, 0.05, -20.0));
  CHECK(std::isnan(w.snapVertical));
  w.see(record(2, 0.10, 10.0));
  // theta from -20 to +10 deg over 0.05 h: zero at 2/3 of the step
  ROOTSIM_CHECK_REL("turning time", w.snapVertical, 0.05 + 0.05 * 20.0 / 30.0, 1e-14);
  w.see(record(3, 0.15, -5.0));
  w.see(record(4, 0.20, 5.0));
  ROOTSIM_CHECK_REL("the first crossing stays", w.snapVertical, 0.05 + 0.05 * 20.0 / 30.0, 1e-14);
}

TEST_CASE("run watch: a tip vertical at its first step is seen at that step, the initial state never counts") {
  RunWatch w;
  w.start(record(0, 0.0, 5.0));
  CHECK(std::isnan(w.snapVertical));  // step 0 is the initial state
  w.see(record(1, 0.05, 6.0));
  CHECK(w.snapVertical == 0.05);  // no negative angle before it to interpolate from
}

TEST_CASE("run watch: the first sideways snap is the first step beyond 30 degrees either way") {
  RunWatch w;
  w.start(record(0, 0.0, 45.0));
  CHECK(std::isnan(w.snapFirst));
  w.see(record(1, 0.05, 29.9));
  w.see(record(2, 0.10, -30.1));
  CHECK(w.snapFirst == 0.10);
  w.see(record(3, 0.15, 80.0));
  CHECK(w.snapFirst == 0.10);
}

TEST_CASE("run watch: the most sub-steps and self-contacts of a step and the closest self-approach, NaN until one is seen") {
  RunWatch w;
  w.start(record(0, 0.0, 0.0, 7, 1));
  CHECK(w.maxSubsteps == 7);
  CHECK(w.maxSelfContacts == 1);
  CHECK(std::isnan(w.minSelfDistance));
  w.see(record(1, 0.05, 0.0, 3, 0, 2.5));
  CHECK(w.minSelfDistance == 2.5);
  w.see(record(2, 0.10, 0.0, 12, 4, 2.1));
  w.see(record(3, 0.15, 0.0, 5, 2, 2.8));
  CHECK(w.maxSubsteps == 12);
  CHECK(w.maxSelfContacts == 4);
  CHECK(w.minSelfDistance == 2.1);
  w.see(record(4, 0.20, 0.0, 5, 2));  // a step with no pair within 3R keeps the closest seen
  CHECK(w.minSelfDistance == 2.1);
}
