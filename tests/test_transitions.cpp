// A transition between patterns in alpha (src/figure/transitions.cpp): bracketed on a grid of runs by
// the first run above it and the run before.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "transitions.hpp"

using namespace rootsim::fig;

TEST_CASE("transitions: the bracket is the first run above the transition and the run before it") {
  Transition tr;
  tr.above = [](const std::string& p) { return p == "coiling"; };
  bracket(tr, {0, 20, 40, 60, 80}, {"straight", "waving", "waving", "coiling", "coiling"});
  CHECK(tr.lo == 40.0);
  CHECK(tr.hi == 60.0);
  CHECK(tr.runs == 0);

  // a run above followed by one below (noise at the border) does not bracket; the first clean step does
  Transition wave;
  wave.above = [](const std::string& p) { return p != "straight"; };
  bracket(wave, {0, 10, 20, 30}, {"straight", "straight", "waving", "coiling"});
  CHECK(wave.lo == 10.0);
  CHECK(wave.hi == 20.0);
}

TEST_CASE("transitions: no transition on the grid leaves the bracket unknown") {
  Transition tr;
  tr.above = [](const std::string& p) { return p == "coiling"; };
  bracket(tr, {0, 20, 40}, {"straight", "waving", "waving"});
  CHECK(std::isnan(tr.lo));
  CHECK(std::isnan(tr.hi));
  Transition all;
  all.above = [](const std::string&) { return true; };
  bracket(all, {0, 20, 40}, {"a", "b", "c"});  // above from the first run: no run below to bracket with
  CHECK(std::isnan(all.lo));
  bracket(all, {}, {});
  CHECK(std::isnan(all.hi));
}
