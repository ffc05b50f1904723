// the bounds on input (src/io/limits.cpp, docs/outputs.md, Caps): a number flag is finite and in its range,
// a count the input decides is checked against its cap, memory running out is named with where, a near
// miss gets its closest name, a number from outside a scene is checked as the scene key
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>

#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"

using namespace rootsim;

namespace {
std::string refusal(const std::string& flag, double v, const NumberRange& r) {
  try {
    checkedNumber(flag, v, r);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(accepted)";
}
}  // namespace

TEST_CASE("limits: a number flag is finite and in its range or refused naming the flag and the value and the range") {
  const NumberRange mm{0, 10, true, false, "mm"};
  CHECK(refusal("--sigma-mm", 10, mm) == "(accepted)");
  CHECK(refusal("--sigma-mm", 1e-300, mm) == "(accepted)");
  CHECK(refusal("--sigma-mm", 0, mm) == "--sigma-mm 0: expected a finite number in (0, 10] mm");
  CHECK(refusal("--sigma-mm", std::nextafter(10.0, 11.0), mm).find("expected a finite number in (0, 10] mm") != std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  CHECK(refusal("--at-h", nan, kGrowthHours) == "--at-h nan: expected a finite number in [0, 1e+06] h");
  CHECK(refusal("--at-h", inf, kGrowthHours) == "--at-h inf: expected a finite number in [0, 1e+06] h");
  CHECK(refusal("--at-h", -inf, kGrowthHours) == "--at-h -inf: expected a finite number in [0, 1e+06] h");
  CHECK(refusal("--at-h", 0, kGrowthHours) == "(accepted)");
  CHECK(refusal("--dpi", 5, {10, 2400, false, false, "dpi"}) == "--dpi 5: expected a finite number in [10, 2400] dpi");
  CHECK(rangeText({0, 1, false, true, ""}) == "in [0, 1)");
}

TEST_CASE("limits: a count is checked against its cap before the work naming what and the count and the cap") {
  CHECK_NOTHROW(checkCount("x", 100, 100, "points", "why"));
  try {
    checkCount("--ds-mm 1e-12: root r", 1e15, caps::kTracePoints, "points", "caps::kTracePoints");
    FAIL("accepted");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()) ==
          "--ds-mm 1e-12: root r: would make 1000000000000000 points, more than the cap of 1000000 (caps::kTracePoints)");
  }
  // a count no long holds, and one that is not a number, are refused as well
  CHECK_THROWS_AS(checkCount("x", 1e300, 10, "frames", "why"), SceneError);
  CHECK_THROWS_AS(checkCount("x", std::numeric_limits<double>::quiet_NaN(), 10, "frames", "why"), SceneError);
  CHECK_THROWS_AS(checkCount("x", std::numeric_limits<double>::infinity(), 10, "frames", "why"), SceneError);
}

TEST_CASE("limits: memory running out is named with where it ran out and never only as std::bad_alloc") {
  const std::string t = failureText(std::bad_alloc(), "the run of fig2b_waving");
  CHECK(t.find("out of memory during the run of fig2b_waving") == 0);
  CHECK(t != "std::bad_alloc");
  CHECK(failureText(std::runtime_error("disk full"), "anything") == "disk full");
}

TEST_CASE("limits: the closest name for a near miss and none for a far one") {
  CHECK(closestName("fly", {"run", "fit", "figure"}) == "fit");
  CHECK(closestName("rnu", {"run", "fit", "figure"}) == "run");
  CHECK(closestName("--atH", {"--at-h", "--frame"}) == "--at-h");
  CHECK(closestName("completely-different", {"run", "fit"}).empty());
}

TEST_CASE("limits: a number from outside a scene is checked as the scene key it names") {
  CHECK(sceneNumberProblem("root.radius_mm", 0.1).empty());
  CHECK(sceneNumberProblem("root.radius_mm", -1) == "must be in (0, 100] (got -1)");
  CHECK(sceneNumberProblem("growth.growth_zone_mm", 1e300).find("must be in (0, 1000]") == 0);
  CHECK(sceneNumberProblem("root.radius_mm", std::numeric_limits<double>::quiet_NaN()).find("must be finite") == 0);
  CHECK(sceneNumberProblem("growth.steps", 2.5) == "must be an integer");
  CHECK(sceneNumberProblem("root.no_such_key", 1) == "is not a number key of a scene");
  CHECK(sceneNumberProblem("nodot", 1) == "is not a number key of a scene");
}
