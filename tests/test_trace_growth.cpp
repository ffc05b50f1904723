// Traced roots over time (src/analysis/trace_growth.cpp), from its pieces: a 2D+t root at a fractional
// observation and a polyline at a time (interpolated linearly), its points' times from the observation
// times, the tip angle over its span, and the matching's position noise. `rootsim analyze` on whole files
// (dated files, RootSystemTracker plates, plants.csv, growth.csv) is in test_analyze_traces.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "physics_support.hpp"
#include "rootsim/analyze_traces.hpp"
#include "rootsim/trace_growth.hpp"

using namespace rootsim;
using namespace rootsim::app;

namespace {
// four points along downhill, 1 mm apart, reached at coord_t 0, 1, 2, 4
TracedRoot fourPoints() {
  TracedRoot r;
  r.plateMm.resize(3, 4);
  for (int i = 0; i < 4; ++i) r.plateMm.col(i) = Eigen::Vector3d(0.0, i, 0.0);
  r.timeIndex = {0.0, 1.0, 2.0, 4.0};
  return r;
}
}  // namespace

TEST_CASE("trace growth: a 2D+t root at observation k holds the points reached by k and the tip interpolated linearly in coord_t") {
  const TracedRoot r = fourPoints();
  CHECK(rootAtObservation(r, -0.5).cols() == 0);
  CHECK(rootAtObservation(r, 0.0).cols() == 1);
  const Eigen::Matrix3Xd half = rootAtObservation(r, 0.5);
  REQUIRE(half.cols() == 2);
  CHECK((half.col(1) - Eigen::Vector3d(0, 0.5, 0)).norm() < 1e-15);
  CHECK(rootAtObservation(r, 2.0).cols() == 3);  // exactly at a point: no extra point
  const Eigen::Matrix3Xd three = rootAtObservation(r, 3.0);
  REQUIRE(three.cols() == 4);
  CHECK((three.col(3) - Eigen::Vector3d(0, 2.5, 0)).norm() < 1e-15);  // halfway between coord_t 2 and 4
  CHECK(rootAtObservation(r, 9.0) == r.plateMm);
  // a root without times (not a 2D+t file) has no shape at an observation
  TracedRoot plain = r;
  plain.timeIndex.clear();
  CHECK(rootAtObservation(plain, 3.0).cols() == 0);
  // the same interpolation in hours
  const Eigen::Matrix3Xd at = polylineAtTime(r.plateMm, {10.0, 12.0, 14.0, 18.0}, 13.0);
  REQUIRE(at.cols() == 3);
  CHECK((at.col(2) - Eigen::Vector3d(0, 1.5, 0)).norm() < 1e-15);
}

TEST_CASE("trace growth: a point's time is its coord_t mapped linearly between the observation times around it") {
  TraceFile tf;
  tf.observationTimesH = {0.0, 6.0, 24.0};
  TracedRoot r;
  r.plateMm = Eigen::Matrix3Xd::Zero(3, 4);
  r.timeIndex = {0.0, 0.5, 1.5, 2.0};
  const std::vector<double> h = pointTimesH(tf, r);
  REQUIRE(h.size() == 4);
  CHECK(h[0] == 0.0);
  CHECK(h[1] == 3.0);
  CHECK(h[2] == 15.0);
  CHECK(h[3] == 24.0);
  tf.observationTimesH.clear();
  CHECK(pointTimesH(tf, r).empty());
}

TEST_CASE("trace growth: the tip angle is the direction over the last max(0.5 mm, 10 px), at most half the root, signed as theta") {
  CHECK(tipAngleSpanMm(0.01) == 0.5);
  CHECK(tipAngleSpanMm(0.2) == doctest::Approx(2.0).epsilon(1e-15));
  // a straight root 30 degrees from downhill towards +lateral
  const double a = 30.0 * std::numbers::pi / 180.0;
  Eigen::Matrix3Xd line(3, 2);
  line.col(0) = Eigen::Vector3d::Zero();
  line.col(1) = 5.0 * Eigen::Vector3d(std::sin(a), std::cos(a), 0.0);
  ROOTSIM_CHECK_REL("straight root at 30 deg", tipAngleDeg(line, 0.01), 30.0, 1e-13);
  line.row(0) *= -1.0;
  ROOTSIM_CHECK_REL("its mirror image", tipAngleDeg(line, 0.01), -30.0, 1e-13);
  // an L: 4 mm downhill, then 1 mm towards +lateral
  Eigen::Matrix3Xd ell(3, 3);
  ell.col(0) = Eigen::Vector3d(0, 0, 0);
  ell.col(1) = Eigen::Vector3d(0, 4, 0);
  ell.col(2) = Eigen::Vector3d(1, 4, 0);
  ROOTSIM_CHECK_REL("span 0.5 mm inside the last leg", tipAngleDeg(ell, 0.01), 90.0, 1e-13);
  // 15 um pixels: a 1.5 mm span reaches 0.5 mm into the downhill leg: atan2(1, 0.5)
  ROOTSIM_CHECK_REL("span 1.5 mm", tipAngleDeg(ell, 0.15), std::atan2(1.0, 0.5) * 180.0 / std::numbers::pi, 1e-13);
  // 1 mm pixels: 10 mm, cut to half the 5 mm root: 1.5 mm into the downhill leg
  ROOTSIM_CHECK_REL("span cut to half the root", tipAngleDeg(ell, 1.0), std::atan2(1.0, 1.5) * 180.0 / std::numbers::pi, 1e-13);
  CHECK(std::isnan(tipAngleDeg(Eigen::Matrix3Xd::Zero(3, 2), 0.01)));
}

TEST_CASE("trace growth: the matching assumes one pixel of noise, 0.05 mm in a file in a physical unit") {
  TraceFile tf;
  CHECK(matchSigmaMm(tf) == 0.05);
  tf.pixelMm = 0.02;
  CHECK(matchSigmaMm(tf) == 0.02);
}
