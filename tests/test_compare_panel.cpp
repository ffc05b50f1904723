// A fit's landscape picture (src/figure/compare_panel.cpp, landscapeFigure): the zoom around the answer
// stays inside the box the keys were searched in, and the ellipse is the covariance it is given.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/compare_panel.hpp"
#include "tolerance_support.hpp"

using namespace rootsim;

namespace {

// the box of the docs' worked example: beta 0.05-0.5, R tau 0-0.8, a 7 x 7 start design, the answer
// (0.1866, 0.3704)
constexpr double kXLo = 0.05, kXHi = 0.5, kYLo = 0.0, kYHi = 0.8, kX = 0.1866, kY = 0.3704;

std::vector<LandscapePoint> design() {
  std::vector<LandscapePoint> pts;
  for (int a = 0; a < 7; ++a)
    for (int b = 0; b < 7; ++b)
      pts.push_back(LandscapePoint{kXLo + (kXHi - kXLo) * (a + 0.5) / 7, kYLo + (kYHi - kYLo) * (b + 0.5) / 7, 100.0 + a + b, true});
  pts.push_back(LandscapePoint{kX, kY, 30.0, false});
  return pts;
}

const Series* ellipseOf(const Axes& ax) {
  for (const Series& s : ax.series)
    if (s.label == "1σ") return &s;
  return nullptr;
}

}  // namespace

TEST_CASE("landscape: the zoom lies inside the box, is cut to it, and is left out when it would be the whole box") {
  Eigen::Matrix2d cov;
  cov << 0.0899 * 0.0899, 0.3 * 0.0899 * 0.0893, 0.3 * 0.0899 * 0.0893, 0.0893 * 0.0893;
  SUBCASE("a zoom of 4 sigma, wider than the box in beta and near its low edge") {
    const Figure f = landscapeFigure(design(), "tropism.beta", "tropism.twist_r_tau", kXLo, kXHi, kYLo, kYHi, 7, kX, kY, &cov,
                                     4 * 0.0899, 4 * 0.0893, "t");
    REQUIRE(f.axes.size() == 2);
    const Axes& b = f.axes[1];
    // beta: the whole box (4 sigma is wider than it); R tau: +- 4 sigma, inside the box
    ROOTSIM_CHECK_CLOSE(b.xmin, kXLo, test::kRoundoff);
    ROOTSIM_CHECK_CLOSE(b.xmax, kXHi, test::kRoundoff);
    ROOTSIM_CHECK_CLOSE(b.ymin, kY - 4 * 0.0893, test::kRoundoff);
    ROOTSIM_CHECK_CLOSE(b.ymax, kY + 4 * 0.0893, test::kRoundoff);
  }
  SUBCASE("a small zoom at the box's edge is shifted into the box, keeping its width") {
    const Figure f = landscapeFigure(design(), "tropism.beta", "tropism.twist_r_tau", kXLo, kXHi, kYLo, kYHi, 7, 0.06, 0.79, &cov,
                                     0.02, 0.03, "t");
    REQUIRE(f.axes.size() == 2);
    const Axes& b = f.axes[1];
    ROOTSIM_CHECK_CLOSE(b.xmin, kXLo, test::kRoundoff);
    ROOTSIM_CHECK_CLOSE(b.xmax, kXLo + 0.04, test::kRoundoff);
    ROOTSIM_CHECK_CLOSE(b.ymin, kYHi - 0.06, test::kRoundoff);
    ROOTSIM_CHECK_CLOSE(b.ymax, kYHi, test::kRoundoff);
  }
  SUBCASE("a zoom wider than the box in both keys: the whole box alone") {
    const Figure f = landscapeFigure(design(), "tropism.beta", "tropism.twist_r_tau", kXLo, kXHi, kYLo, kYHi, 7, kX, kY, &cov,
                                     1.0, 1.0, "t");
    CHECK(f.axes.size() == 1);
  }
}

TEST_CASE("landscape: the ellipse reaches exactly sigma along each key, the covariance given") {
  const double sx = 0.0899, sy = 0.0893, rho = 0.6;
  Eigen::Matrix2d cov;
  cov << sx * sx, rho * sx * sy, rho * sx * sy, sy * sy;
  const Figure f = landscapeFigure(design(), "tropism.beta", "tropism.twist_r_tau", kXLo, kXHi, kYLo, kYHi, 7, kX, kY, &cov,
                                   0.1, 0.1, "t");
  for (const Axes& ax : f.axes) {
    const Series* el = ellipseOf(ax);
    REQUIRE(el != nullptr);
    // the extent of (x - best)' C^-1 (x - best) = 1 along a key is that key's sigma; 96 points on the
    // ellipse find it to (1 - cos(pi / 96)) of it
    const auto [x0, x1] = std::minmax_element(el->x.begin(), el->x.end());
    const auto [y0, y1] = std::minmax_element(el->y.begin(), el->y.end());
    ROOTSIM_CHECK_REL("half width in beta", 0.5 * (*x1 - *x0), sx, 6e-4);
    ROOTSIM_CHECK_REL("half width in R tau", 0.5 * (*y1 - *y0), sy, 6e-4);
  }
}
