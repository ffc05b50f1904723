// A transition between patterns in alpha: bracketed on a grid of runs, then bisected (each step runs the
// midpoints of all open brackets in one batch).
#include "transitions.hpp"

#include "figure_runs.hpp"

namespace rootsim::fig {

void bracket(Transition& tr, const std::vector<double>& alphas, const std::vector<std::string>& patterns) {
  for (size_t i = 1; i < alphas.size(); ++i)
    if (tr.above(patterns[i]) && !tr.above(patterns[i - 1])) {
      tr.lo = alphas[i - 1];
      tr.hi = alphas[i];
      return;
    }
}

void bisect(const Ctx& c, const Case& base, std::vector<Transition*> trs, double width) {
  for (;;) {
    std::vector<Case> cs;
    std::vector<Transition*> who;
    for (Transition* tr : trs)
      if (std::isfinite(tr->lo) && tr->hi - tr->lo > width + 1e-9) {
        Case k = base;
        k.alpha = 0.5 * (tr->lo + tr->hi);
        cs.push_back(k);
        who.push_back(tr);
      }
    if (cs.empty()) return;
    runCases(c, cs);
    for (size_t j = 0; j < cs.size(); ++j) {
      const std::string pat = result(c, cs[j]).pattern;
      (who[j]->above(pat) ? who[j]->hi : who[j]->lo) = cs[j].alpha;
      ++who[j]->runs;
      who[j]->log += "| " + significantText(cs[j].alpha) + " | " + pat + " |\n";
    }
  }
}

}  // namespace rootsim::fig
