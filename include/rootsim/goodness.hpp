#pragma once
// What a fit may claim (docs/experiments.md, "Goodness of fit"): the chance of a chi-square at least as
// large when the model is right (the chi-square distribution's upper tail), the verdict it gives, and the
// rule that picks a fit's answer among its candidates. Plain arithmetic: no file formats here.
#include <string>
#include <vector>

namespace rootsim {

// the regularised upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a) for a > 0, x >= 0: its
// series below x = a + 1, its continued fraction (modified Lentz) above (Numerical Recipes, 3rd ed.,
// section 6.2). Throws std::invalid_argument for a <= 0, x < 0 or a non-finite argument.
double regularizedGammaQ(double a, double x);

// P(X >= chi2) for X chi-square distributed with dof degrees of freedom: Q(dof / 2, chi2 / 2)
double chiSquarePValue(double chi2, int dof);

// below this p-value a fit is "poor": the model does not reproduce the trace within its uncertainty
inline constexpr double kPoorFitPValue = 1e-3;

// the goodness of fit of one run against a trace, with the trace's uncertainty alone (a response surface's
// scatter belongs in the parameters' uncertainty, not here)
struct Goodness {
  double chi2 = 0;
  int outputs = 0;       // the compared values
  int dof = 0;           // outputs - free keys
  int pDof = 0;          // the degrees of freedom p is taken at: dof, or outputs when dof < 1 (a fit with
                         // no more outputs than keys: its p is an upper bound, the keys' tuning left out)
  double pValue = 1;
  std::string verdict;   // "consistent" (p >= kPoorFitPValue) or "poor"
  std::string against = "the trace's uncertainty alone";  // the covariance chi2 was computed against
};
Goodness goodnessOf(double chi2, int outputs, int freeKeys);
// "chi2 817 for 14 dof against the trace's uncertainty alone, p < 1e-16: poor" (g.against after
// "against"; chi2Name: how to write chi-square, "chi2" on a terminal, "χ²" in a picture)
std::string goodnessText(const Goodness& g, const std::string& chi2Name = "chi2");

// a fit's answer: the index of the smallest objective among its evaluated runs (non-finite ones are
// failed runs), preferring the response surface's minimum's run (surfaceIndex, -1 when it has none) on a
// tie: the answer is never worse, by the objective, than a run the fit made. -1 when every run failed.
int answerIndex(const std::vector<double>& objectives, int surfaceIndex);

}  // namespace rootsim
