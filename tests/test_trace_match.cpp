// A traced root against a simulated one (src/analysis/trace_match.cpp) and the fit's response surface
// (src/analysis/response_surface.cpp), against closed forms: distances between straight and bent lines, the
// uncertainties of the observables, the seed's common error, a quadratic recovered exactly, the scatter
// of known noise, the covariance of a linear model, and a direction the outputs do not see.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "rootsim/response_surface.hpp"
#include "rootsim/traits.hpp"
#include "rootsim/trace_match.hpp"
#include "rootsim/units.hpp"
#include "tracer_model.hpp"
#include "tolerance_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;

namespace {

// a straight root from (x0, 0) downhill over L [mm], n points
Eigen::Matrix3Xd straight(double x0, double L, int n) {
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i) p.col(i) = Eigen::Vector3d(x0, L * i / (n - 1), 0);
  return p;
}

}  // namespace

TEST_CASE("trace match: distances between two roots in closed form") {
  // parallel lines a distance d apart: both distances are d
  const double d = 0.3;
  CHECK(arcLengthDistanceMm(straight(0, 10, 11), straight(d, 10, 201), 0.05) == doctest::Approx(d).epsilon(1e-12));
  CHECK(frechetDistanceMm(straight(0, 10, 11), straight(d, 10, 201), 0.05) == doctest::Approx(d).epsilon(1e-12));
  // the same root sampled differently: 0 (up to rounding)
  CHECK(arcLengthDistanceMm(straight(0, 10, 3), straight(0, 10, 1001), 0.05) < 1e-12);
  // lines from one seed, one turned by phi: points at equal fractions s of both lengths are 2 s sin(phi/2)
  // apart; the RMS over s = k/n, k = 0..n is L 2 sin(phi/2) sqrt(sum k^2 / n^2 / (n + 1))
  const double phi = 10.0 * units::deg, L = 10;
  Eigen::Matrix3Xd turned(3, 2);
  turned.col(0) = Eigen::Vector3d::Zero();
  turned.col(1) = Eigen::Vector3d(L * std::sin(phi), L * std::cos(phi), 0);
  const int n = 200;  // L / 0.05
  double sum = 0;
  for (int k = 0; k <= n; ++k) sum += double(k) * k / (double(n) * n);
  const double rms = L * 2 * std::sin(phi / 2) * std::sqrt(sum / (n + 1));
  CHECK(arcLengthDistanceMm(straight(0, L, 2), turned, 0.05) == doctest::Approx(rms).epsilon(1e-9));
  // the Frechet distance of the two: their tips, 2 L sin(phi/2) apart
  CHECK(frechetDistanceMm(straight(0, L, 2), turned, 0.05) == doctest::Approx(2 * L * std::sin(phi / 2)).epsilon(1e-9));
  // a noisy trace is longer than its root; fractions of each length keep its points level: a zigzag of
  // amplitude e about the line is 0.5 e^2 / h^2 longer per unit, yet its distance is the zigzag's RMS
  Eigen::Matrix3Xd zig(3, 201);
  const double e = 0.01;
  for (int i = 0; i <= 200; ++i) zig.col(i) = Eigen::Vector3d(i % 2 ? e : -e, 10.0 * i / 200, 0);
  CHECK(arcLengthDistanceMm(straight(0, 10, 2), zig, 0.05) < 1.5 * e);
  CHECK_THROWS(arcLengthDistanceMm(straight(0, 0, 2), zig, 0.05));
}

TEST_CASE("trace match: the observables' uncertainties and chi-square") {
  RootTraits t, s;
  t.lengthMm = s.lengthMm = 20;
  t.chordMm = s.chordMm = 18;
  t.skewDeg = 3;
  s.skewDeg = 4;
  t.shape.peaks = 9;  // 4 whole waves
  t.shape.waves = 4;
  t.shape.wavelength = 2.5 * units::mm;
  t.shape.amplitude = 0.5 * units::mm;
  t.shape.maxKappa = 1.5 / units::mm;
  t.shape.skew = 2 * units::deg;
  s.shape = t.shape;
  s.shape.skew = 2.5 * units::deg;
  s.shape.wavelength = 2.6 * units::mm;
  const double sp = 0.05;
  const std::vector<Observation> obs = observeBoth(t, s, sp);
  REQUIRE(usedCount(obs) == 3);
  // the skew over 4 waves of 2.5 mm: sqrt(2) sp / 10 mm
  CHECK(obs[0].name == "skew_deg");
  ROOTSIM_CHECK_CLOSE(obs[0].sigma, std::sqrt(2.0) * sp / 10.0 * 180 / std::numbers::pi, kRoundoff);
  ROOTSIM_CHECK_CLOSE(obs[0].residual(), 0.5 / obs[0].sigma, kRoundoff);
  // lambda: 2 sqrt(2 sp / kappa) / (peaks - 2)
  ROOTSIM_CHECK_CLOSE(obs[1].sigma, 2 * std::sqrt(2 * sp / 1.5) / 7, kRoundoff);
  // A: sqrt(2) sp / sqrt(peaks - 1)
  ROOTSIM_CHECK_CLOSE(obs[2].sigma, std::sqrt(2.0) * sp / std::sqrt(8.0), kRoundoff);
  const double chi2 = std::pow(obs[0].residual(), 2) + std::pow(obs[1].residual(), 2);
  ROOTSIM_CHECK_CLOSE(chiSquare(obs), chi2, kRoundoff);
  // without whole waves in the trace: the base-to-tip skew, over the chord; lambda and A not used
  t.shape.peaks = 1;
  const std::vector<Observation> few = observeBoth(t, s, sp);
  CHECK(usedCount(few) == 1);
  CHECK(few[0].trace == 3);
  ROOTSIM_CHECK_CLOSE(few[0].sigma, std::sqrt(2.0) * sp / 18.0 * 180 / std::numbers::pi, kRoundoff);
  const FitComponents c = observableComponents(few);
  REQUIRE(c.trace.size() == 1);
  ROOTSIM_CHECK_CLOSE(c.cov(0, 0), few[0].sigma * few[0].sigma, kRoundoff);
}

TEST_CASE("trace match: the shape's points carry their own error and the seed's") {
  const double sigma = 0.05;
  const Eigen::Matrix3Xd a = straight(0, 8, 81);
  const Eigen::MatrixXd cov = shapeTraceCovariance(a, sigma, 8);
  const FitComponents c = shapeComponents(a, a, cov, 8);
  REQUIRE(c.trace.size() == 16);
  CHECK((c.trace - c.sim).norm() < 1e-12);
  ROOTSIM_CHECK_CLOSE(c.trace(0), 0.0, kRoundoff);        // lateral at 1/8
  ROOTSIM_CHECK_CLOSE(c.trace(1), 1.0, kRoundoff);        // downhill at 1/8 of 8 mm
  ROOTSIM_CHECK_CLOSE(c.trace(15), 8.0, kRoundoff);
  CHECK(c.names[2] == "lateral_at_25_pct");
  CHECK_THROWS(shapeComponents(a, a, Eigen::MatrixXd::Identity(4, 4), 8));
  CHECK_THROWS(shapeTraceCovariance(a, 0.0, 8));
  // a straight trace, its points' noise propagated (2000 draws: a covariance's estimate is good to about
  // 0.05 sigma^2 here). Across the root: a sample's own error (sigma^2 on a point, less between two) and
  // the seed's (sigma^2), so between two samples the seed's alone, sigma^2
  const double s2 = sigma * sigma;
  CHECK(c.cov(0, 0) > 1.4 * s2);
  CHECK(c.cov(0, 0) < 2.2 * s2);
  CHECK(c.cov(0, 2) == doctest::Approx(s2).epsilon(0.2));
  CHECK(std::abs(c.cov(0, 1)) < 0.2 * s2);
  // along the root, at the tip: a sample slides with the length's error, and at the tip that is the tip's
  // error less the seed's along it, 2 sigma^2
  CHECK(c.cov(15, 15) == doctest::Approx(2 * s2).epsilon(0.15));
  CHECK((c.cov - c.cov.transpose()).norm() < 1e-15);
  // a seed offset by delta moves every point alike: its chi-square is below (delta / sigma)^2 = 1, not
  // 8 (delta / sigma)^2 as if the points' errors were independent
  Eigen::Matrix3Xd b = a;
  b.row(0).array() += sigma;
  const FitComponents sh = shapeComponents(a, b, cov, 8);
  const Eigen::VectorXd d = sh.sim - sh.trace;
  const double chi2 = d.dot(sh.cov.ldlt().solve(d));
  CHECK(chi2 < 1.0);
  CHECK(chi2 > 0.7);
}

TEST_CASE("trace match: a traced straight root's placement drift gives compare and fit no waves to match") {
  // a straight root traced with the centreline drifting within the root's width (tests/tracer_model.hpp):
  // the trace's traits (traceTraits, what compare and fit measure a trace with) have no peaks, so lambda
  // and A are not observables and the skew is the base-to-tip one; a simulated wave is not pulled to it
  Eigen::Matrix3Xd truth(3, 2001);
  for (int i = 0; i <= 2000; ++i) truth.col(i) = Eigen::Vector3d(0, 0.01 * i, 0);
  for (unsigned long long seed = 1; seed <= 5; ++seed) {
    test::TracerModel tr;
    tr.seed = seed;
    const RootTraits t = traceTraits(test::traceLikeTracer(truth, tr), 0.05, 1.0, 0.1, AnalysisParams{});
    CAPTURE(seed);
    CHECK(t.shape.peaks < 2);
    const RootTraits sim = rootTraits(truth, 0.05, 1.0, 0.1, AnalysisParams{});
    for (const Observation& o : observeBoth(t, sim, 0.05))
      if (o.name == "wavelength_mm" || o.name == "amplitude_mm") CHECK_FALSE(o.used);
  }
}

TEST_CASE("response surface: a quadratic is recovered, known noise is measured, a linear model's covariance is exact") {
  // two outputs, an exact quadratic and a linear one, in two variables
  auto f = [](const Eigen::VectorXd& u) {
    Eigen::VectorXd y(2);
    y(0) = 1 + 2 * u(0) - 3 * u(1) + 0.5 * u(0) * u(0) + 0.25 * u(0) * u(1) - 1.5 * u(1) * u(1);
    y(1) = 4 * u(0) + u(1);
    return y;
  };
  std::vector<Eigen::VectorXd> us, ys;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      Eigen::VectorXd u(2);
      u << 0.3 + 0.01 * i, 0.6 + 0.01 * j;
      us.push_back(u);
      ys.push_back(f(u));
    }
  Eigen::VectorXd c(2);
  c << 0.32, 0.62;
  const ResponseSurface s = fitResponseSurface(us, ys, c, 0.02);
  Eigen::VectorXd at(2);
  at << 0.305, 0.637;
  CHECK((s.value(at) - f(at)).norm() < 1e-10);
  Eigen::MatrixXd J(2, 2);
  J << 2 + at(0) + 0.25 * at(1), -3 + 0.25 * at(0) - 3 * at(1), 4, 1;
  CHECK((s.jacobian(at) - J).norm() < 1e-8);
  CHECK(s.noiseCov.norm() < 1e-18);
  CHECK_THROWS(fitResponseSurface(std::vector<Eigen::VectorXd>(us.begin(), us.begin() + 6),
                                  std::vector<Eigen::VectorXd>(ys.begin(), ys.begin() + 6), c, 0.02));

  // a linear output with Gaussian noise of 0.1: the scatter measured within 15 % over 400 points, the
  // same noise added to both outputs is seen as correlated
  std::mt19937 gen(7);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<Eigen::VectorXd> un, yn;
  for (int k = 0; k < 400; ++k) {
    Eigen::VectorXd u(2);
    u << (k % 20) / 19.0, (k / 20) / 19.0;
    const double e = noise(gen);
    Eigen::VectorXd y(2);
    y << 3 * u(0) + e, -2 * u(1) + e;
    un.push_back(u);
    yn.push_back(y);
  }
  const ResponseSurface sn = fitResponseSurface(un, yn, Eigen::VectorXd::Constant(2, 0.5), 0.5);
  CHECK(std::sqrt(sn.noiseCov(0, 0)) == doctest::Approx(0.1).epsilon(0.15));
  CHECK(sn.noiseCov(0, 1) / sn.noiseCov(0, 0) == doctest::Approx(1.0).epsilon(1e-9));

  // uncertainty of a linear model y = A u without scatter: the covariance is (A' C^-1 A)^-1 exactly
  std::vector<Eigen::VectorXd> ul, yl;
  Eigen::MatrixXd A(3, 2);
  A << 2, 0.5, -1, 3, 0.25, 1;
  for (int k = 0; k < 12; ++k) {
    Eigen::VectorXd u(2);
    u << 0.4 + 0.02 * (k % 4), 0.5 + 0.03 * (k / 4);
    ul.push_back(u);
    yl.push_back(A * u);
  }
  const ResponseSurface sl = fitResponseSurface(ul, yl, Eigen::VectorXd::Constant(2, 0.45), 0.05);
  Eigen::VectorXd truth(2);
  truth << 0.43, 0.55;
  const Eigen::MatrixXd C = Eigen::Vector3d(0.01, 0.04, 0.09).asDiagonal();
  const FitUncertainty fu = uncertaintyAt(sl, truth, A * truth, C);
  const Eigen::MatrixXd expected = (A.transpose() * C.inverse() * A).inverse();
  CHECK((fu.covariance - expected).norm() < 1e-9 * expected.norm());
  CHECK(fu.chi2 < 1e-20);
  CHECK(fu.flat.empty());
  ROOTSIM_CHECK_CLOSE(fu.sigma[0], std::sqrt(expected(0, 0)), kRoundoff);
}

TEST_CASE("response surface: a direction the outputs do not see is flat, and has no uncertainty") {
  // outputs depend on u0 + u1 only: the direction (1, -1) is flat
  std::vector<Eigen::VectorXd> us, ys;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      Eigen::VectorXd u(2), y(2);
      u << 0.2 * i, 0.2 * j;
      y << 5 * (u(0) + u(1)), -3 * (u(0) + u(1));
      us.push_back(u);
      ys.push_back(y);
    }
  const ResponseSurface s = fitResponseSurface(us, ys, Eigen::VectorXd::Constant(2, 0.3), 0.3);
  Eigen::VectorXd u(2);
  u << 0.3, 0.3;
  const FitUncertainty fu = uncertaintyAt(s, u, s.value(u), Eigen::Matrix2d::Identity() * 0.01);
  REQUIRE(fu.flat.size() == 1);
  CHECK(std::abs(fu.flat[0](0) + fu.flat[0](1)) < 1e-6);
  CHECK(std::isnan(fu.sigma[0]));
  CHECK(std::isnan(fu.sigma[1]));
}

TEST_CASE("noiseDraws: each draw aligned at its own seed / a point's variance 2 sigma^2, two points' covariance sigma^2 (the seed's)") {
  const double sigma = 0.05;
  const int draws = 20000;
  const Eigen::MatrixXd y = noiseDraws(straight(0, 10, 11), sigma, draws, [](const Eigen::Matrix3Xd& p) {
    Eigen::VectorXd v(3);
    v << p(0, 5), p(0, 10), p(1, 10);
    return v;
  });
  REQUIRE(y.rows() == draws);
  const Eigen::MatrixXd c = y.rowwise() - y.colwise().mean();
  const Eigen::MatrixXd cov = c.transpose() * c / (draws - 1.0);
  // sampling error of a variance: sqrt(2 / draws) relative, about 1 %; 4 of those
  const double tol = 4 * std::sqrt(2.0 / draws);
  CHECK(cov(0, 0) == doctest::Approx(2 * sigma * sigma).epsilon(tol));
  CHECK(cov(1, 1) == doctest::Approx(2 * sigma * sigma).epsilon(tol));
  CHECK(cov(2, 2) == doctest::Approx(2 * sigma * sigma).epsilon(tol));
  CHECK(cov(0, 1) == doctest::Approx(sigma * sigma).epsilon(2 * tol));
  CHECK(std::abs(cov(0, 2)) < 4 * sigma * sigma / std::sqrt(draws) * std::sqrt(2.0));  // lateral and downhill: independent
  CHECK(y.col(1).mean() == doctest::Approx(0).scale(1).epsilon(4 * sigma * std::sqrt(2.0 / draws)));
  CHECK_THROWS_AS(noiseDraws(straight(0, 10, 11), 0.0, 10, [](const Eigen::Matrix3Xd& p) { return Eigen::VectorXd(p.row(0).transpose()); }),
                  std::invalid_argument);
}

TEST_CASE("strongestWave: a wave below the peak count's noise threshold is found from the root's whole length") {
  // 30 mm downhill with a sinusoid of lambda 3 mm and half amplitude 0.08 mm across, a point every 0.24 mm
  // (a 76 um pixel's tracer every 3 px), the last 1 mm (a growth zone) left out of the fit
  const double lambda = 3.0, amp = 0.08, L = 30.0;
  const int n = 126;
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i) {
    const double y = L * i / (n - 1);
    p.col(i) = Eigen::Vector3d(amp * std::sin(2 * std::numbers::pi * y / lambda), y, 0);
  }
  const auto [lo, hi] = waveRange(p, 1.0);
  CHECK(lo == doctest::Approx(4 * 0.24).epsilon(0.02));
  CHECK(hi == doctest::Approx(29.0).epsilon(0.01));
  const WaveFit clean = strongestWave(p, 1.0, lo, hi);
  CHECK(clean.wavelengthMm == doctest::Approx(lambda).epsilon(0.005));
  CHECK(clean.amplitudeMm == doctest::Approx(amp).epsilon(0.02));
  // with 0.046 mm of noise on each coordinate (0.6 px): 3 sigma is 0.14 mm, more than the half amplitude,
  // so no peak counts; the fit over 120 points still finds the wave
  std::mt19937 gen(5);
  std::normal_distribution<double> noise(0.0, 0.046);
  Eigen::Matrix3Xd q = p;
  for (int i = 0; i < n; ++i) {
    q(0, i) += noise(gen);
    q(1, i) += noise(gen);
  }
  const WaveFit noisy = strongestWave(q, 1.0, lo, hi);
  CHECK(noisy.wavelengthMm == doctest::Approx(lambda).epsilon(0.03));
  CHECK(noisy.amplitudeMm == doctest::Approx(amp).epsilon(0.2));
  // a straight root with the same noise: the strongest "wave" is the noise's, far below 0.08 mm
  Eigen::Matrix3Xd s = straight(0.0, L, n);
  for (int i = 0; i < n; ++i) {
    s(0, i) += noise(gen);
    s(1, i) += noise(gen);
  }
  CHECK(strongestWave(s, 1.0, lo, hi).amplitudeMm < 0.03);
  // too few points, or an empty range: no wave
  CHECK(std::isnan(strongestWave(straight(0.0, 1.0, 5), 0.0, 0.1, 1.0).wavelengthMm));
  CHECK(std::isnan(strongestWave(p, 1.0, 2.0, 1.0).wavelengthMm));
}
