#pragma once
// A transition between patterns in alpha: bracketed on a grid of runs, then bisected by running the
// midpoints of the brackets.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "figure_cases.hpp"

namespace rootsim::fig {

// a transition in alpha, located by bisection: above(pattern) holds on the high-alpha side
struct Transition {
  std::function<bool(const std::string&)> above;
  double lo = NAN, hi = NAN;  // bracket [deg]: the pattern at lo is below the transition, at hi above
  int runs = 0;               // bisection runs made
  std::string log;            // markdown rows "| alpha | pattern |" of the bisection runs
};

// brackets a transition from a grid of runs ordered by alpha: the first run above, and the run before it
void bracket(Transition& tr, const std::vector<double>& alphas, const std::vector<std::string>& patterns);

// halves every bracket until it is at most `width` [deg] wide, running base at the midpoints of all
// brackets together
void bisect(const Ctx& c, const Case& base, std::vector<Transition*> trs, double width);

}  // namespace rootsim::fig
