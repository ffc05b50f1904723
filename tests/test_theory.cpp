// the theory of docs/model.md, Theory (src/sim/theory.cpp): the pattern thresholds and the time scale T0
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "rootsim/model.hpp"
#include "rootsim/theory.hpp"

using namespace rootsim;

TEST_CASE("theory: worked values of docs/model.md, Theory") {
  auto at = [](double gain) {
    Model m;
    m.tropism.beta = gain * m.rod.radius / m.growth.zoneLength;
    return theoryFor(m);
  };
  const double deg = 180 / std::numbers::pi;
  const Theory a = at(0.5), b = at(1.0);
  CHECK(a.alphaStraightToWave * deg == doctest::Approx(15.6).epsilon(0.005));
  CHECK(a.alphaWaveToCoil * deg == doctest::Approx(45.0).epsilon(0.005));
  CHECK(a.T0 / 3600 == doctest::Approx(11.9).epsilon(0.005));
  CHECK(b.alphaStraightToWave * deg == doctest::Approx(11.8).epsilon(0.005));
  CHECK(b.alphaWaveToCoil * deg == doctest::Approx(47.6).epsilon(0.005));
  CHECK(b.T0 / 3600 == doctest::Approx(7.85).epsilon(0.005));
}
