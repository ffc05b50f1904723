// What a fit may claim (src/analysis/goodness.cpp): the chi-square distribution's upper tail against its closed
// forms and printed tables, the verdict, the rule that picks a fit's answer, and the goodness of a traced
// root's shape against the run it was traced from, calibrated over noise seeds.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "physics_support.hpp"
#include "rootsim/goodness.hpp"
#include "rootsim/response_surface.hpp"
#include "rootsim/trace_match.hpp"
#include "rootsim/traits.hpp"

using namespace rootsim;

namespace {

// P(chi2_k >= x) in closed form: for even k, e^-y sum_{j < k/2} y^j / j!; for odd k,
// erfc(sqrt y) + e^-y sum_{j = 1}^{(k-1)/2} y^(j - 1/2) / Gamma(j + 1/2), with y = x / 2
double closedFormP(double x, int k) {
  const double y = 0.5 * x;
  double sum = 0;
  if (k % 2 == 0) {
    double term = 1;
    for (int j = 0; j < k / 2; ++j) {
      if (j > 0) term *= y / j;
      sum += term;
    }
    return std::exp(-y) * sum;
  }
  for (int j = 1; j <= (k - 1) / 2; ++j) sum += std::exp((j - 0.5) * std::log(y) - std::lgamma(j + 0.5));
  return std::erfc(std::sqrt(y)) + std::exp(-y) * sum;
}

}  // namespace

TEST_CASE("goodness: the chi-square p-value against its closed forms and a printed table") {
  for (int k = 1; k <= 60; ++k)
    for (double x : {0.01, 0.3, 1.0, 2.5, 7.0, 15.0, 40.0, 90.0, 200.0}) {
      const double want = closedFormP(x, k);
      if (want < 1e-280) continue;
      const std::string what = "p(chi2 " + std::to_string(x) + ", " + std::to_string(k) + " dof)";
      ROOTSIM_CHECK_REL(what, chiSquarePValue(x, k), want, 1e-11);
    }
  // the 5 % and 0.1 % points of a printed table (Abramowitz & Stegun, Table 26.8)
  CHECK(chiSquarePValue(3.841, 1) == doctest::Approx(0.05).epsilon(1e-3));
  CHECK(chiSquarePValue(10.828, 1) == doctest::Approx(0.001).epsilon(1e-3));
  CHECK(chiSquarePValue(18.307, 10) == doctest::Approx(0.05).epsilon(1e-3));
  CHECK(chiSquarePValue(29.588, 10) == doctest::Approx(0.001).epsilon(1e-3));
  CHECK(chiSquarePValue(124.342, 100) == doctest::Approx(0.05).epsilon(1e-3));
  CHECK(chiSquarePValue(0.0, 3) == 1.0);
  CHECK_THROWS(chiSquarePValue(1.0, 0));
  CHECK_THROWS(regularizedGammaQ(0.0, 1.0));
  CHECK_THROWS(regularizedGammaQ(1.0, -1.0));
}

TEST_CASE("goodness: the verdict and its degrees of freedom") {
  const Goodness good = goodnessOf(14.0, 16, 2);
  CHECK(good.dof == 14);
  CHECK(good.pDof == 14);
  CHECK(good.verdict == "consistent");
  const Goodness poor = goodnessOf(817.0, 16, 2);
  CHECK(poor.verdict == "poor");
  CHECK(poor.pValue < 1e-100);
  CHECK(goodnessText(poor).find("chi2 817 for 14 dof against the trace's uncertainty alone, p < 1e-16: poor") == 0);
  // at the threshold: p = 0.001 exactly is consistent, just below it poor
  CHECK(goodnessOf(10.7, 2, 1).verdict == "consistent");
  CHECK(goodnessOf(11.0, 2, 1).verdict == "poor");
  // no more outputs than keys: p at the outputs' count, an upper bound, and said
  const Goodness few = goodnessOf(30.0, 1, 2);
  CHECK(few.dof == -1);
  CHECK(few.pDof == 1);
  CHECK(few.verdict == "poor");
  CHECK(goodnessText(few).find("for 1 outputs (no more than the free keys)") != std::string::npos);
  // the covariance it was computed against, as its maker names it, in both forms of the text
  Goodness group = goodnessOf(3.0, 3, 2);
  group.against = "the group mean's covariance";
  CHECK(goodnessText(group).find("chi2 3 for 1 dof against the group mean's covariance, p ") == 0);
  Goodness groupFew = few;
  groupFew.against = "the group mean's covariance";
  CHECK(goodnessText(groupFew).find("(no more than the free keys) against the group mean's covariance, p ") != std::string::npos);
  CHECK(goodnessText(groupFew).find("uncertainty alone") == std::string::npos);
  // a failed run: no p, not consistent
  CHECK(goodnessOf(std::nan(""), 3, 1).verdict == "poor");
}

TEST_CASE("goodness: the answer is never worse than a run the fit made") {
  const double nan = std::nan("");
  // the surface's minimum's run (index 3) is worse than a design run (index 1): the design run answers
  CHECK(answerIndex({5.0, 2.51, 4.0, 2.68}, 3) == 1);
  // the surface's minimum's run is the best: it answers; on a tie it is preferred
  CHECK(answerIndex({5.0, 2.51, 4.0, 1.0}, 3) == 3);
  CHECK(answerIndex({5.0, 2.0, 4.0, 2.0}, 3) == 3);
  CHECK(answerIndex({2.0, 2.0, 4.0}, 1) == 1);
  // failed runs (NaN) are no candidates; none left: -1
  CHECK(answerIndex({nan, 3.0, nan}, 0) == 1);
  CHECK(answerIndex({nan, nan}, -1) == -1);
  CHECK(answerIndex({}, -1) == -1);
}

TEST_CASE("goodness: a traced root against the run it was traced from, calibrated over noise seeds") {
  // a waving root (lateral 0.5 sin(2 pi y / 3) mm over 20 mm downhill, 2001 points) traced as a plate scan
  // is: a point every 0.2 mm (4 px at 20 px/mm) with Gaussian noise sigma on each coordinate, the trace
  // aligned at its own first point. Against the covariance a trace of the root would have (its noise
  // propagated through the sampling: shapeNoiseCovariance of the root traced like the trace), the shape
  // objective's chi-square of the true root is chi-square with 16 degrees of freedom (nothing fitted):
  // its mean is 16 and its p-values uniform.
  const double sigma = 0.025;
  const int samples = 8, outputs = 2 * samples, seeds = 400;
  Eigen::Matrix3Xd truth(3, 2001);
  for (int i = 0; i < truth.cols(); ++i) {
    const double y = 20.0 * i / (truth.cols() - 1);
    truth.col(i) = Eigen::Vector3d(0.5 * std::sin(2 * std::numbers::pi * y / 3.0), y, 0);
  }
  const double L = polylineLength(truth);
  const Eigen::Matrix3Xd traced = resampleByArcLength(truth, L / 100);  // a point every ~0.2 mm
  std::mt19937 gen(11);
  std::normal_distribution<double> noise(0.0, sigma);
  double sum = 0;
  int below05 = 0, below50 = 0;
  for (int s = 0; s < seeds; ++s) {
    Eigen::Matrix3Xd t = traced;
    for (int i = 0; i < t.cols(); ++i) {
      t(0, i) += noise(gen);
      t(1, i) += noise(gen);
    }
    const Eigen::Vector3d seed = t.col(0);
    for (int i = 0; i < t.cols(); ++i) t.col(i) -= seed;
    const FitComponents c = shapeComponents(t, truth, shapeNoiseCovariance(tracedLike(truth, t), sigma, samples), samples);
    const double chi2 = chiSquareOf(c.sim, c.trace, c.cov);
    sum += chi2;
    const double p = goodnessOf(chi2, outputs, 0).pValue;
    below05 += p < 0.05;
    below50 += p < 0.5;
  }
  const double mean = sum / seeds;
  // the mean of chi-square_16 over 400 seeds has the standard error sqrt(2 * 16 / 400) = 0.28; the
  // p-values' fractions below 0.05 and 0.5 within 3 binomial standard errors
  INFO("mean chi2 " << mean << " for " << outputs << " outputs; p < 0.05: " << below05 << ", p < 0.5: " << below50 << " of " << seeds);
  CHECK(std::abs(mean - outputs) < 3 * std::sqrt(2.0 * outputs / seeds));
  CHECK(std::abs(below05 - 0.05 * seeds) < 3 * std::sqrt(0.05 * 0.95 * seeds));
  CHECK(std::abs(below50 - 0.5 * seeds) < 3 * std::sqrt(0.25 * seeds));
}
