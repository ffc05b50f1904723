// The model's completion (src/sim/model.cpp): the solver's length scale follows the growth zone.
#include <doctest/doctest.h>

#include "rootsim/model.hpp"

using namespace rootsim;

TEST_CASE("completeModel: the solver's length scale is the growth zone's length, 0 without growth") {
  Model m;
  m.growth.enabled = true;
  m.growth.zoneLength = 1.7e-3;
  m.solver.lengthScale = -1.0;
  completeModel(m);
  CHECK(m.solver.lengthScale == 1.7e-3);
  m.growth.enabled = false;
  completeModel(m);
  CHECK(m.solver.lengthScale == 0.0);
  const Model d = defaultModel();
  CHECK(d.solver.lengthScale == (d.growth.enabled ? d.growth.zoneLength : 0.0));
  CHECK(d.solver.lengthScale > 0.0);
}
