// What a poor fit says it could not reproduce (src/analysis/fit_goodness.cpp, internal fit_parts.hpp): the
// output the answer's run misses most, and either the fixed key to check or, when the runs near the answer
// scatter there by as much as the miss, that the model's shape moves with the free keys more finely than
// the fit resolves.
#include <doctest/doctest.h>

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fit_parts.hpp"
#include "tolerance_support.hpp"

using namespace rootsim;
using namespace rootsim::app;

namespace {

// a skewing trace without waves, straight as the runs are, so that the sentence names the output missed
// most; its tip 12.1 mm downhill, traced to 0.023 mm
struct PoorFit {
  TraceTarget target;
  std::vector<FitEvaluation> runs;
  FitEvaluation answer;
  FitComponents trace;
  std::vector<FixedKey> fixed{{"plane.alpha_deg", "30.0", "scene"}, {"growth.rate_per_h", "0.2", "default"}};

  explicit PoorFit(double answerTip) {
    target.traits.shape.pattern = "skewing";
    target.traits.chordMm = 18.0;
    target.rootLengthMm = 20.0;
    trace.names = {"lateral_at_100_pct", "downhill_at_100_pct"};
    trace.trace = Eigen::Vector2d(14.0, 12.1);
    trace.sigma = Eigen::Vector2d(0.023, 0.023);
    trace.cov = trace.sigma.array().square().matrix().asDiagonal();
    for (double st : {0.85, 0.9, 0.95}) {
      FitEvaluation e;
      e.pattern = "skewing";
      e.straightness = st;
      e.sim = Eigen::Vector2d(14.0, 12.1);
      runs.push_back(e);
    }
    answer = runs[1];
    answer.sim(1) = answerTip;
  }
};

}  // namespace

TEST_CASE("a poor fit's sentence: a miss the runs' own scatter explains names no fixed key, any other miss does") {
  const std::string lead = "the model with these free keys and this scene does not reproduce the trace: the answer's run misses "
                           "downhill_at_100_pct by ";
  SUBCASE("the runs near the answer scatter by 0.43 mm, 19 times the trace's uncertainty; the miss is 0.73 mm") {
    const PoorFit f(12.83);
    const std::string s = misfitSentence(f.target, f.runs, f.answer, f.trace, Eigen::Vector2d(0.01, 0.43), f.fixed);
    INFO(s);
    CHECK(s.rfind(lead, 0) == 0);
    CHECK(s.find("(trace 12.1, run 12.83; the runs near the answer scatter by 0.43 there)") != std::string::npos);
    CHECK(s.find("a miss within 3 times that scatter, which is 18.7 times the trace's uncertainty") != std::string::npos);
    CHECK(s.find("more finely than the fit resolves") != std::string::npos);
    CHECK(s.find("check ") == std::string::npos);
  }
  SUBCASE("the same scatter, a miss beyond three times it: the tilt is the key to check") {
    const PoorFit f(12.1 + 3.5 * 0.43);
    const std::string s = misfitSentence(f.target, f.runs, f.answer, f.trace, Eigen::Vector2d(0.01, 0.43), f.fixed);
    INFO(s);
    CHECK(s.rfind(lead, 0) == 0);
    CHECK(s.find("more finely") == std::string::npos);
    CHECK(s.find("; check plane.alpha_deg (30.0, from the scene) against the plate's tilt, or free it") != std::string::npos);
  }
  SUBCASE("runs that scatter by no more than three times the trace's uncertainty: a miss is the model's, not its scatter") {
    const PoorFit f(12.15);
    const std::string s = misfitSentence(f.target, f.runs, f.answer, f.trace, Eigen::Vector2d(0.01, 0.06), f.fixed);
    INFO(s);
    CHECK(s.find("more finely") == std::string::npos);
    CHECK(s.find("; check plane.alpha_deg") != std::string::npos);
  }
  SUBCASE("no scatter known for the output: the fixed key is named") {
    const PoorFit f(12.83);
    const std::string s = misfitSentence(f.target, f.runs, f.answer, f.trace, Eigen::VectorXd(), f.fixed);
    INFO(s);
    CHECK(s.find("more finely") == std::string::npos);
    CHECK(s.find("; check plane.alpha_deg") != std::string::npos);
  }
}

TEST_CASE("the covariance a fit reports has the reported sigmas on its diagonal and the surface's correlation") {
  // a surface covariance in the scaled box: variances 4e-4 and 1e-4, correlation 0.6
  Eigen::Matrix2d surface;
  surface << 4e-4, 0.6 * 2e-2 * 1e-2, 0.6 * 2e-2 * 1e-2, 1e-4;
  // the reported sigmas (the surface's widened by the minima's spread, the bootstrap and the answer's scale,
  // in the keys' units)
  const std::vector<double> sigma{0.09, 0.05};
  const Eigen::MatrixXd c = reportedCovariance(surface, sigma);
  REQUIRE(c.rows() == 2);
  REQUIRE(c.cols() == 2);
  ROOTSIM_CHECK_CLOSE(c(0, 0), 0.09 * 0.09, test::kRoundoff);
  ROOTSIM_CHECK_CLOSE(c(1, 1), 0.05 * 0.05, test::kRoundoff);
  ROOTSIM_CHECK_CLOSE(c(0, 1), 0.6 * 0.09 * 0.05, test::kRoundoff);
  CHECK(c(1, 0) == c(0, 1));
  // nothing to report: no surface covariance, one of another size, a sigma that is not finite
  CHECK(reportedCovariance(Eigen::MatrixXd(), sigma).size() == 0);
  CHECK(reportedCovariance(Eigen::MatrixXd::Identity(3, 3), sigma).size() == 0);
  CHECK(reportedCovariance(surface, {0.09, std::numeric_limits<double>::quiet_NaN()}).size() == 0);
  Eigen::Matrix2d singular = surface;
  singular(1, 1) = 0;
  CHECK(reportedCovariance(singular, sigma).size() == 0);
}
