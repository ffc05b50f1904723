#include "rootsim/goodness.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace rootsim {

namespace {

// P(a, x) by its series: e^-x x^a / Gamma(a + 1) * sum_n x^n / ((a + 1) ... (a + n)), for x < a + 1
double gammaPSeries(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 100000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by its continued fraction (modified Lentz), for x >= a + 1
double gammaQFraction(double a, double x) {
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double regularizedGammaQ(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0) || !std::isfinite(a) || !std::isfinite(x))
    throw std::invalid_argument("regularizedGammaQ: needs a > 0 and x >= 0, both finite");
  if (x == 0.0) return 1.0;
  if (x < a + 1.0) return 1.0 - gammaPSeries(a, x);
  return gammaQFraction(a, x);
}

double chiSquarePValue(double chi2, int dof) {
  if (dof < 1) throw std::invalid_argument("chiSquarePValue: needs at least 1 degree of freedom");
  if (std::isnan(chi2)) return std::numeric_limits<double>::quiet_NaN();
  if (chi2 == std::numeric_limits<double>::infinity()) return 0.0;
  return regularizedGammaQ(0.5 * dof, std::max(0.0, 0.5 * chi2));
}

Goodness goodnessOf(double chi2, int outputs, int freeKeys) {
  Goodness g;
  g.chi2 = chi2;
  g.outputs = outputs;
  g.dof = outputs - freeKeys;
  g.pDof = g.dof >= 1 ? g.dof : outputs;
  g.pValue = g.pDof >= 1 ? chiSquarePValue(chi2, g.pDof) : std::numeric_limits<double>::quiet_NaN();
  // a NaN p (no output, or a failed run) is no evidence of a good fit
  g.verdict = g.pValue >= kPoorFitPValue ? "consistent" : "poor";
  return g;
}

std::string goodnessText(const Goodness& g, const std::string& chi2Name) {
  char p[64];
  if (std::isnan(g.pValue))
    std::snprintf(p, sizeof p, "no p-value");
  else if (g.pValue < 1e-16)
    std::snprintf(p, sizeof p, "p < 1e-16");
  else
    std::snprintf(p, sizeof p, "p %.2g", g.pValue);
  char b[256];
  if (g.dof >= 1)
    std::snprintf(b, sizeof b, " %.3g for %d dof against %s, %s: %s", g.chi2, g.dof, g.against.c_str(), p, g.verdict.c_str());
  else
    std::snprintf(b, sizeof b, " %.3g for %d outputs (no more than the free keys) against %s, %s at %d dof: %s", g.chi2, g.outputs,
                  g.against.c_str(), p, g.pDof, g.verdict.c_str());
  return chi2Name + b;
}

int answerIndex(const std::vector<double>& objectives, int surfaceIndex) {
  int best = -1;
  for (int i = 0; i < static_cast<int>(objectives.size()); ++i) {
    const double f = objectives[static_cast<std::size_t>(i)];
    if (!std::isfinite(f)) continue;
    if (best < 0 || f < objectives[static_cast<std::size_t>(best)] ||
        (f == objectives[static_cast<std::size_t>(best)] && i == surfaceIndex))
      best = i;
  }
  return best;
}

}  // namespace rootsim
