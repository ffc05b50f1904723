// phenotyping traits of a centreline (src/sim/traits.cpp): resampling, length, tortuosity, the skew angle's
// sign against the runs' theta, the insertion angle, and the run observables of a trace equal to those
// analyseShape measures on the same shape
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "rootsim/analysis.hpp"
#include "rootsim/rod.hpp"
#include "rootsim/traits.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;

namespace {
constexpr double pi = std::numbers::pi;

// a planar curve in plate coordinates [mm]: (lateral u(p), downhill w(p), 0), p in [0, 1], n + 1 points
template <class F>
Eigen::Matrix3Xd plateCurve(int n, F f) {
  Eigen::Matrix3Xd c(3, n + 1);
  for (int i = 0; i <= n; ++i) {
    double u = 0, w = 0;
    f(static_cast<double>(i) / n, u, w);
    c.col(i) = Eigen::Vector3d(u, w, 0.0);
  }
  return c;
}
}  // namespace

TEST_CASE("resampling keeps the ends, spaces the points equally and drops repeated points") {
  Eigen::Matrix3Xd p(3, 4);
  p << 0, 0, 3, 3,   //
      0, 0, 4, 4,    //
      0, 0, 0, 0;    // a 5 mm segment with its two ends doubled
  const Eigen::Matrix3Xd r = resampleByArcLength(p, 0.5);
  REQUIRE(r.cols() == 11);
  for (int i = 1; i < r.cols(); ++i) CHECK((r.col(i) - r.col(i - 1)).norm() == doctest::Approx(0.5).epsilon(1e-12));
  CHECK(r.col(10).isApprox(Eigen::Vector3d(3, 4, 0)));
  CHECK(polylineLength(r) == doctest::Approx(5.0).epsilon(1e-14));
  CHECK_THROWS(resampleByArcLength(p, 0.0));
  CHECK_THROWS(resampleByArcLength(Eigen::Matrix3Xd::Zero(3, 3), 0.1));
}

TEST_CASE("length and chord and tortuosity of a half circle - a straight root has tortuosity 1") {
  const double R = 2.0;  // [mm]
  const Eigen::Matrix3Xd half = plateCurve(2000, [&](double p, double& u, double& w) {
    u = R - R * std::cos(pi * p);
    w = R * std::sin(pi * p);
  });
  const RootTraits t = rootTraits(half, 0.05, 0.0, 0.1, AnalysisParams{});
  CHECK(t.lengthMm == doctest::Approx(pi * R).epsilon(1e-6));
  CHECK(t.chordMm == doctest::Approx(2 * R).epsilon(1e-12));
  CHECK(t.tortuosity == doctest::Approx(pi / 2).epsilon(1e-6));
  const Eigen::Matrix3Xd line = plateCurve(7, [](double p, double& u, double& w) { u = 0; w = 10 * p; });
  const RootTraits s = rootTraits(line, 0.05, 0.0, 0.1, AnalysisParams{});
  CHECK(s.tortuosity == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(s.skewDeg == doctest::Approx(0.0));
  CHECK(s.shape.pattern == "straight");
  CHECK_THROWS(rootTraits(Eigen::Matrix3Xd::Zero(3, 2), 0.05, 0.0, 0.1, AnalysisParams{}));
}

TEST_CASE("the skew angle has the sign of the runs' theta on a tilted plate") {
  // a rod on the 40 degree plate heading downhill and 10 degrees towards +lateral: its planar angle by the
  // runs' code, and the trace of the same points in plate coordinates
  Plane pl;
  pl.alpha = 40 * units::deg;
  const PlateFrame f = pl.frame();
  const double a = 10 * units::deg;
  const Vec3 dir = std::cos(a) * f.downhill + std::sin(a) * f.lateral;
  const double theta = planarAngle(pl, dir);
  Eigen::Matrix3Xd trace(3, 2);
  trace.col(0) = f.coords(Vec3::Zero()) / units::mm;
  trace.col(1) = f.coords(5 * units::mm * dir) / units::mm;
  const RootTraits t = rootTraits(trace, 0.0, 0.0, 0.1, AnalysisParams{});
  CHECK(std::abs(theta) == doctest::Approx(a));
  CHECK(t.skewDeg == doctest::Approx(theta / units::deg).epsilon(1e-12));
}

TEST_CASE("a traced sine gives the lambda, A and pattern analyseShape gives the same shape as a run") {
  // 6 waves of wavelength 2.5 mm and half excursion 0.3 mm, 80 points a wave, on a 40 degree plate
  const double lam = 2.5, amp = 0.3;
  const int n = 480;
  const Eigen::Matrix3Xd trace = plateCurve(n, [&](double p, double& u, double& w) {
    w = 6 * lam * p;
    u = amp * std::sin(2 * pi * w / lam);
  });
  Model m;
  m.growth.enabled = false;
  m.env.plane.alpha = 40 * units::deg;
  RodState s;
  s.resize(n);
  s.x = plateMmToLab(trace, m.env.plane.frame());
  const ShapeAnalysis run = analyseShape(m, s);
  const RootTraits t = rootTraits(trace, 0.0, 0.0, m.rod.radius / units::mm, m.analysis);
  CHECK(run.pattern == "waving");
  CHECK(t.shape.pattern == run.pattern);
  CHECK(t.shape.peaks == run.peaks);
  CHECK(t.shape.wavelength == doctest::Approx(run.wavelength).epsilon(1e-12));
  CHECK(t.shape.amplitude == doctest::Approx(run.amplitude).epsilon(1e-12));
  CHECK(t.shape.skew == doctest::Approx(run.skew).scale(1.0).epsilon(1e-12));
  CHECK(t.shape.maxKappa == doctest::Approx(run.maxKappa).epsilon(1e-9));
  CHECK(t.shape.wavelength == doctest::Approx(lam * units::mm).epsilon(0.01));
  CHECK(t.shape.amplitude == doctest::Approx(2 * amp * units::mm).epsilon(0.01));
  // the growth zone left out: the mature part ends at the last point at least 2.5 mm of arc length
  // before the tip, and the peaks of that stretch are not counted
  const RootTraits z = rootTraits(trace, 0.0, lam, m.rod.radius / units::mm, m.analysis);
  const int last = z.matureLast;
  CHECK(polylineLength(trace.rightCols(n + 1 - last)) >= lam);
  CHECK(polylineLength(trace.rightCols(n - last)) < lam);
  CHECK(z.shape.peaks < run.peaks);
  CHECK(z.shape.peaks >= run.peaks - 2);
}

TEST_CASE("the insertion angle of a lateral on its parent") {
  const Eigen::Matrix3Xd parent = plateCurve(100, [](double p, double& u, double& w) { u = 0; w = 20 * p; });
  for (double ang : {30.0, 60.0, 90.0, 120.0}) {
    const double a = ang * units::deg;
    // a lateral from the parent's point at 8 mm, heading 'ang' from the parent's direction (downhill)
    const Eigen::Matrix3Xd lat = plateCurve(50, [&](double p, double& u, double& w) {
      u = 5 * p * std::sin(a);
      w = 8 + 5 * p * std::cos(a);
    });
    CHECK(insertionAngleDeg(parent, lat, 1.0) == doctest::Approx(ang).epsilon(1e-9));
  }
}
