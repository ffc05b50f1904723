// numbers as text (include/rootsim/number_text.hpp): the shortest form that reads back exactly, as scene values,
// sweep run names and table.csv's grid columns show them; and the numbers of messages and labels
#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include "rootsim/number_text.hpp"
#include "rootsim/sweep.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("number_text", name); }
}  // namespace

TEST_CASE("numbers are written in the shortest form that reads back exactly") {
  CHECK(shortestNumber(0.3) == "0.3");
  CHECK(shortestNumber(35.7) == "35.7");
  CHECK(shortestNumber(0.1 + 0.2) == "0.30000000000000004");  // not 0.3: another double
  CHECK(shortestNumber(2) == "2.0");
  CHECK(shortestNumber(-0.0) == "-0.0");
  CHECK(shortestNumber(1e-7) == "1e-07");
  CHECK(shortestNumber(1e300) == "1e+300");
  const fs::path d = scratch("numbers");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/cantilever_tip_load.toml\"\n"
                                << "[grid]\n\"plane.alpha_deg\" = [35.7, 40.0]\n\"tropism.twist_r_tau\" = [0.3]\n"
                                << "\"load.tip_force_n\" = [[0, 0.1, -2.5e-5]]\n";
  }
  // (grid keys in the order toml++ gives them: sorted)
  const SweepPlan p = loadSweep((d / "s.toml").string());
  REQUIRE(p.points.size() == 2);
  CHECK(p.points[0].dirName == "run_0000_tip_force_n=_0_0.1_-2.5e-05__alpha_deg=35.7_twist_r_tau=0.3");
  CHECK(p.points[1].dirName == "run_0001_tip_force_n=_0_0.1_-2.5e-05__alpha_deg=40.0_twist_r_tau=0.3");
  REQUIRE(p.points[0].grid.size() == 3);
  CHECK(p.points[0].grid[1].second == "35.7");  // table.csv's grid column
  CHECK(p.points[0].grid[0].second == "[0,0.1,-2.5e-05]");
  CHECK(p.points[0].overrides[2] == "tropism.twist_r_tau=0.3");
  // the resolved scene writes the value as given
  CHECK(p.points[0].resolvedToml.find("\nalpha_deg = 35.7 ") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("decimal numbers: the shortest text without an exponent that reads back exactly (RSML's xs:decimal)") {
  CHECK(decimalNumber(1e-7) == "0.0000001");
  CHECK(decimalNumber(0.3) == "0.3");
  CHECK(decimalNumber(2.0) == "2");
  CHECK(decimalNumber(-123456.75) == "-123456.75");
  CHECK(decimalNumber(1e21) == "1000000000000000000000");
  CHECK(decimalNumber(-0.0) == "-0");
  // random doubles over many magnitudes: never an exponent, the same bits back
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> ex(-30, 30);
  for (int i = 0; i < 20000; ++i) {
    const double x = std::ldexp(mant(rng), ex(rng) * 3);
    const std::string t = decimalNumber(x);
    CHECK(t.find_first_of("eE") == std::string::npos);
    double back = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), back);
    REQUIRE(r.ec == std::errc());
    CHECK(std::memcmp(&back, &x, sizeof x) == 0);
  }
}

TEST_CASE("numbers for people: significant digits as %g writes them, fixed decimals, ticks") {
  CHECK(significantText(0.15) == "0.15");
  CHECK(significantText(1000.0) == "1000");
  CHECK(significantText(1e6) == "1e+06");
  CHECK(significantText(1.0 / 3.0) == "0.333333");
  CHECK(significantText(1.0 / 3.0, 3) == "0.333");
  CHECK(significantText(123456.0, 4) == "1.235e+05");
  CHECK(significantText(2.0 / 3.0, 10) == "0.6666666667");
  CHECK(significantText(-0.0) == "-0");
  CHECK(significantText(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(fixedText(12.25, 1) == "12.2");  // 12.25 is exact: round half to even
  CHECK(fixedText(2.5, 0) == "2");
  CHECK(fixedText(0.049, 2) == "0.05");
  CHECK(fixedText(-1.0, 1) == "-1.0");
  CHECK(tickText(0.0) == "0");
  CHECK(tickText(1e-301) == "0");
  CHECK(tickText(-1e-301) == "0");
  CHECK(tickText(1e-299) == "1e-299");
  CHECK(tickText(0.12345) == "0.123");
  CHECK(tickText(-2500.0) == "-2.5e+03");
}

TEST_CASE("niceLength: the largest 1, 2 or 5 times a power of ten not above the limit") {
  CHECK(niceLength(1.0) == 1.0);
  CHECK(niceLength(1.99) == 1.0);
  CHECK(niceLength(2.0) == 2.0);
  CHECK(niceLength(4.99) == 2.0);
  CHECK(niceLength(5.0) == 5.0);
  CHECK(niceLength(9.99) == 5.0);
  CHECK(niceLength(10.0) == 10.0);
  CHECK(niceLength(730.0) == 500.0);
  CHECK(niceLength(0.37) == doctest::Approx(0.2).epsilon(1e-15));
  CHECK(niceLength(0.05) == doctest::Approx(0.05).epsilon(1e-15));
  for (double x : {0.0123, 0.7, 3.3, 42.0, 999.0, 1e5 + 1}) {
    const double n = niceLength(x);
    CAPTURE(x);
    CHECK(n <= x);
    CHECK(n > x / 2.5);  // the next round length up (2x or 2.5x) is above x
  }
}
