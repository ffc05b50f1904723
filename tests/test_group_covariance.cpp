// the covariance of a group's mean in a fit by group (src/analysis/fit_groups.cpp, internal fit_parts.hpp):
// each seedling's residual against a smooth surface of its own runs' outputs keeps the runs' jumps out of
// it, against closed forms of the scatter a mean of seedlings has
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "fit_parts.hpp"
#include "physics_support.hpp"
#include "tracer_model.hpp"

using namespace rootsim;
using namespace rootsim::app;

TEST_CASE("a group's residual covariance against its seedlings' own surfaces holds their tracing scatter, not the runs' jumps") {
  // six seedlings, one output, two keys; the runs on a 6 x 6 grid of a box. Seedling i's run at u reads
  // a_i + 2 u_1 - u_2 plus a jump of SD J that changes from run to run (a skew whose window of whole waves
  // gains or loses a peak); its trace is that smooth output at the truth u0 plus its tracing error of SD s
  constexpr int n = 6, side = 6;
  constexpr double J = 0.5, s = 0.1, lo = 0.4, hi = 0.6;
  GroupSide g;
  g.trace.names = {"skew_deg"};
  g.users = {std::vector<bool>(n, true)};
  g.floor = Eigen::VectorXd::Zero(1);
  std::vector<Eigen::VectorXd> us;
  for (int a = 0; a < side; ++a)
    for (int b = 0; b < side; ++b) us.push_back(Eigen::Vector2d(lo + (hi - lo) * a / (side - 1), lo + (hi - lo) * b / (side - 1)));
  const Eigen::Vector2d u0 = us[14];  // a run's point: the answer's run is one of the box's
  // the variance a quadratic surface's value at u0 has from the jumps: J^2 x0' (X'X)^-1 x0 (its leverage)
  Eigen::MatrixXd X(static_cast<int>(us.size()), quadraticTerms(2));
  for (std::size_t k = 0; k < us.size(); ++k) X.row(static_cast<int>(k)) = quadraticBasis(us[k]).transpose();
  const Eigen::VectorXd x0 = quadraticBasis(u0);
  const double leverage = x0.dot((X.transpose() * X).ldlt().solve(x0));
  test::TracerRng rng{20240611};
  constexpr int reps = 400;
  double surfaceMean = 0, runMean = 0;
  std::vector<double> surfaceDraws;
  for (int r = 0; r < reps; ++r) {
    Eigen::MatrixXd trace(n, 1);
    std::vector<Eigen::MatrixXd> sims(us.size(), Eigen::MatrixXd(n, 1));
    Eigen::MatrixXd atAnswer(n, 1);
    for (int i = 0; i < n; ++i) {
      const double a = 3.0 * rng.normal();  // the seedlings' own offsets: reproduced by their runs
      trace(i, 0) = a + 2.0 * u0(0) - u0(1) + s * rng.normal();
      for (std::size_t k = 0; k < us.size(); ++k) {
        sims[k](i, 0) = a + 2.0 * us[k](0) - us[k](1) + J * rng.normal();
        if (k == 14) atAnswer(i, 0) = sims[k](i, 0);
      }
    }
    const double surface = groupSurfaceCovariance(g, trace, us, sims, u0, 0.5 * (hi - lo))(0, 0);
    surfaceMean += surface / reps;
    surfaceDraws.push_back(surface);
    runMean += groupMeanCovariance(g, trace - atAnswer, nullptr)(0, 0) / reps;
  }
  // E[S / n] = (s^2 + leverage J^2) / n; an unbiased S's variance over draws 2 sigma^4 / (n - 1)
  const double want = (s * s + leverage * J * J) / n;
  const double se = want * std::sqrt(2.0 / (n - 1) / reps);
  test::report("the surface residuals' variance of the mean", surfaceMean, want, std::abs(surfaceMean - want) / want);
  CHECK(std::abs(surfaceMean - want) < 3.0 * se);
  // against the answer's own runs the jumps count in full: (s^2 + J^2) / n, several times the surface's
  const double runWant = (s * s + J * J) / n;
  CHECK(std::abs(runMean - runWant) < 3.0 * runWant * std::sqrt(2.0 / (n - 1) / reps));
  CHECK(runMean > 2.0 * surfaceMean);
}
