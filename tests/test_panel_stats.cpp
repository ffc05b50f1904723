// The statistics of the figure panels' claims (src/figure/panel_stats.cpp): the referee's window, the
// median of the finite values, the count within a window, zero crossings interpolated linearly and the
// mean spacing of successive values, against values worked out by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "panel_stats.hpp"

using namespace rootsim::fig;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST_CASE("panel stats: within is finite and in the closed window, the referee's windows are 0.75 to 1.25 and 0.75 to 1.33") {
  CHECK(within(0.75, kScaleLo, kScaleHi));
  CHECK(within(1.25, kScaleLo, kScaleHi));
  CHECK_FALSE(within(1.2500001, kScaleLo, kScaleHi));
  CHECK_FALSE(within(0.7499999, kScaleLo, kScaleHi));
  CHECK(within(1.33, kRatioLo, kRatioHi));
  CHECK_FALSE(within(kNaN, -kInf, kInf));
  CHECK_FALSE(within(kInf, 0.0, kInf));
}

TEST_CASE("panel stats: the median of the finite values, the mean of the middle two for an even count, NaN for none") {
  CHECK(median({3.0, 1.0, 2.0}) == 2.0);
  CHECK(median({4.0, 1.0, 3.0, 2.0}) == 2.5);
  CHECK(median({5.0, kNaN, 1.0, kInf, 3.0}) == 3.0);
  CHECK(std::isnan(median({})));
  CHECK(std::isnan(median({kNaN, -kInf})));
}

TEST_CASE("panel stats: k of n runs within counts the finite values only") {
  CHECK(countWithin({0.8, 1.0, 1.3, kNaN, 0.5}, 0.75, 1.25) == "2 of 4 runs within");
  CHECK(countWithin({}, 0.0, 1.0) == "0 of 0 runs within");
}

TEST_CASE("panel stats: zero crossings interpolated linearly after t0, and their mean spacing") {
  // a piecewise-linear series through worked points: crossings at 0.25, 2.25 and 4.5
  const std::vector<double> tt{0.0, 1.0, 2.0, 3.0, 4.0, 5.0};
  const std::vector<double> yy{-1.0, 3.0, 1.0, -3.0, -1.0, 1.0};
  const std::vector<double> z = zeroCrossings(tt, yy, 0.0);
  REQUIRE(z.size() == 3);
  CHECK(z[0] == doctest::Approx(0.25).epsilon(1e-15));
  CHECK(z[1] == doctest::Approx(2.25).epsilon(1e-15));
  CHECK(z[2] == doctest::Approx(4.5).epsilon(1e-15));
  CHECK(meanSpacing(z) == doctest::Approx((4.5 - 0.25) / 2.0).epsilon(1e-15));
  // only intervals starting at or after t0
  const std::vector<double> late = zeroCrossings(tt, yy, 1.0);
  REQUIRE(late.size() == 2);
  CHECK(late[0] == doctest::Approx(2.25).epsilon(1e-15));
  // a sample exactly at zero is not a sign change on either side
  CHECK(zeroCrossings({0.0, 1.0, 2.0}, {-1.0, 0.0, 1.0}, 0.0).empty());
  CHECK(std::isnan(meanSpacing({1.0})));
}
