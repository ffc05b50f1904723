// The text of the figure report (src/figure/panel_text.cpp): numbers to three significant digits, yes and
// a bold no, and a panel's markdown section.
#include <doctest/doctest.h>

#include <limits>

#include "panel_text.hpp"

using namespace rootsim::fig;

TEST_CASE("panel text: three significant digits, n/a for what is not finite") {
  CHECK(fmt3(3.14159) == "3.14");
  CHECK(fmt3(2.0) == "2");
  CHECK(fmt3(1234.5) == "1.23e+03");
  CHECK(fmt3(0.000123456) == "0.000123");
  CHECK(fmt3(-0.5) == "-0.5");
  CHECK(fmt3(std::numeric_limits<double>::quiet_NaN()) == "n/a");
  CHECK(fmt3(-std::numeric_limits<double>::infinity()) == "n/a");
}

TEST_CASE("panel text: yes, or a bold no") {
  CHECK(yesNo(true) == "yes");
  CHECK(yesNo(false) == "**no**");
}

TEST_CASE("panel text: a panel's section is its heading, its picture NAME.png, the caption and the body") {
  CHECK(md("fig2b", "Waving.", "| a | b |") == "## fig2b\n\n![fig2b](fig2b.png)\n\nWaving.\n\n| a | b |\n");
  CHECK(md("x", "c") == "## x\n\n![x](x.png)\n\nc\n\n\n");
}
