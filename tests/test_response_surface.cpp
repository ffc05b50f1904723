// The fit's quadratic response surfaces (src/analysis/response_surface.cpp) against closed forms: an
// exact quadratic comes back with its gradient, a scatter orthogonal to the quadratics is the model's
// noise R'R / (points - terms), chi-square with a known covariance, and the linearised parameters'
// uncertainty sqrt((J' C^-1 J)^-1) with its flat directions.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>

#include "physics_support.hpp"
#include "rootsim/response_surface.hpp"

using namespace rootsim;

namespace {
// two outputs of u = (a, b): a full quadratic and a linear one
Eigen::VectorXd truth(const Eigen::VectorXd& u) {
  const double a = u(0), b = u(1);
  Eigen::VectorXd y(2);
  y << 0.5 - 1.2 * a + 0.7 * b + 2.0 * a * a - 0.4 * a * b + 1.5 * b * b, 3.0 * a - 2.0 * b;
  return y;
}
Eigen::MatrixXd truthJacobian(const Eigen::VectorXd& u) {
  const double a = u(0), b = u(1);
  Eigen::MatrixXd J(2, 2);
  J << -1.2 + 4.0 * a - 0.4 * b, 0.7 - 0.4 * a + 3.0 * b, 3.0, -2.0;
  return J;
}
// a 4 x 4 grid over [0.2, 0.8]^2
std::vector<Eigen::VectorXd> grid() {
  std::vector<Eigen::VectorXd> u;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) u.push_back(Eigen::Vector2d(0.2 + 0.2 * i, 0.2 + 0.2 * j));
  return u;
}
}  // namespace

TEST_CASE("response surface: 1 + n + n (n + 1) / 2 terms, the basis 1, u_i, then u_i u_j for i <= j") {
  CHECK(quadraticTerms(1) == 3);
  CHECK(quadraticTerms(2) == 6);
  CHECK(quadraticTerms(3) == 10);
  CHECK(quadraticTerms(4) == 15);
  const Eigen::VectorXd b = quadraticBasis(Eigen::Vector2d(2.0, 3.0));
  REQUIRE(b.size() == 6);
  CHECK(b == (Eigen::VectorXd(6) << 1, 2, 3, 4, 6, 9).finished());
}

TEST_CASE("response surface: an exact quadratic is recovered, value and gradient, with no scatter, whatever the centre and scale") {
  const std::vector<Eigen::VectorXd> u = grid();
  std::vector<Eigen::VectorXd> y;
  for (const auto& p : u) y.push_back(truth(p));
  for (const double scale : {1.0, 0.3}) {
    const ResponseSurface s = fitResponseSurface(u, y, Eigen::Vector2d(0.5, 0.5), scale);
    CHECK(s.points == 16);
    CHECK(s.noiseCov.cwiseAbs().maxCoeff() < 1e-24);
    for (const Eigen::Vector2d& at : {Eigen::Vector2d(0.33, 0.71), Eigen::Vector2d(0.9, 0.1)}) {
      CHECK((s.value(at) - truth(at)).norm() < 1e-12);
      CHECK((s.jacobian(at) - truthJacobian(at)).norm() < 1e-11);
    }
  }
}

TEST_CASE("response surface: a scatter orthogonal to every quadratic is the noise, |r|^2 / (points - terms), and its covariance between outputs") {
  const std::vector<Eigen::VectorXd> u = grid();
  const int N = 16, terms = 6;
  Eigen::MatrixXd A(N, terms);
  for (int k = 0; k < N; ++k) A.row(k) = quadraticBasis(u[static_cast<size_t>(k)]).transpose();
  // a fixed vector with its projection on the quadratics removed
  Eigen::VectorXd v(N);
  for (int k = 0; k < N; ++k) v(k) = std::sin(1.7 * k + 0.3) + 0.5 * std::cos(3.1 * k);
  const Eigen::VectorXd r = v - A * A.colPivHouseholderQr().solve(v);
  std::vector<Eigen::VectorXd> y;
  for (int k = 0; k < N; ++k) {
    Eigen::VectorXd yk = truth(u[static_cast<size_t>(k)]);
    yk(0) += r(k);
    yk(1) -= 2.0 * r(k);  // the same scatter, doubled and reversed: correlation -1
    y.push_back(yk);
  }
  const ResponseSurface s = fitResponseSurface(u, y, Eigen::Vector2d(0.0, 0.0), 1.0);
  const double var = r.squaredNorm() / (N - terms);
  ROOTSIM_CHECK_REL("noise variance of output 0", s.noiseCov(0, 0), var, 1e-12);
  ROOTSIM_CHECK_REL("noise variance of output 1", s.noiseCov(1, 1), 4.0 * var, 1e-12);
  ROOTSIM_CHECK_REL("noise covariance", s.noiseCov(0, 1), -2.0 * var, 1e-12);
  ROOTSIM_CHECK_REL("noiseVar", s.noiseVar()(1), 4.0 * var, 1e-12);
  // the trend is untouched by the scatter
  CHECK((s.value(Eigen::Vector2d(0.4, 0.6)) - truth(Eigen::Vector2d(0.4, 0.6))).norm() < 1e-12);
  // the measurement's own covariance adds to it
  const Eigen::MatrixXd traceCov = Eigen::Vector2d(0.01, 0.02).asDiagonal();
  CHECK((totalCovariance(s, traceCov) - (s.noiseCov + traceCov)).norm() == 0.0);
}

TEST_CASE("response surface: chi-square is d' C^-1 d, the sum of (d_i / sigma_i)^2 for a diagonal C") {
  const Eigen::Vector3d y(1.0, 2.0, 3.0), m(1.5, 1.0, 3.0);
  const Eigen::MatrixXd C = Eigen::Vector3d(0.25, 4.0, 9.0).asDiagonal();
  ROOTSIM_CHECK_REL("chi-square", chiSquareOf(y, m, C), 0.25 / 0.25 + 1.0 / 4.0, 1e-15);
  // a correlated pair: C = [[1, rho], [rho, 1]], d = (1, 1): 2 / (1 + rho)
  Eigen::MatrixXd C2(2, 2);
  C2 << 1.0, 0.6, 0.6, 1.0;
  ROOTSIM_CHECK_REL("chi-square, correlated", chiSquareOf(Eigen::Vector2d(1, 1), Eigen::Vector2d(0, 0), C2), 2.0 / 1.6, 1e-14);
}

TEST_CASE("response surface: the parameters' uncertainty is sqrt((J' C^-1 J)^-1) at a perfect fit, and an output-free direction is flat") {
  // three linear outputs of two parameters, measured with sigma = 0.01 each
  Eigen::MatrixXd J(3, 2);
  J << 2.0, 0.5, -1.0, 1.0, 0.3, 3.0;
  const std::vector<Eigen::VectorXd> u = grid();
  std::vector<Eigen::VectorXd> y;
  for (const auto& p : u) y.push_back(J * p);
  const ResponseSurface s = fitResponseSurface(u, y, Eigen::Vector2d(0.5, 0.5), 0.5);
  const Eigen::Vector2d at(0.4, 0.6);
  const double sigma = 0.01;
  const Eigen::MatrixXd traceCov = Eigen::MatrixXd::Identity(3, 3) * sigma * sigma;
  const FitUncertainty f = uncertaintyAt(s, at, J * at, traceCov);
  const Eigen::Matrix2d want = (J.transpose() * J / (sigma * sigma)).inverse();
  CHECK(f.dof == 1);
  CHECK(f.chi2 < 1e-12);
  CHECK(f.scale == 1.0);
  CHECK(f.flat.empty());
  REQUIRE(f.covariance.rows() == 2);
  ROOTSIM_CHECK_REL("sigma of u_1", f.sigma[0], std::sqrt(want(0, 0)), 1e-9);
  ROOTSIM_CHECK_REL("sigma of u_2", f.sigma[1], std::sqrt(want(1, 1)), 1e-9);
  // a fit worse than its uncertainties widens them by sqrt(chi2 / dof)
  const Eigen::Vector3d off = J * at + Eigen::Vector3d(0.05, -0.05, 0.02);
  const FitUncertainty g = uncertaintyAt(s, at, off, traceCov);
  const double chi2 = chiSquareOf(J * at, off, traceCov);
  ROOTSIM_CHECK_REL("chi-square at u", g.chi2, chi2, 1e-9);
  REQUIRE(chi2 > 1.0);
  ROOTSIM_CHECK_REL("widened sigma", g.sigma[0], std::sqrt(want(0, 0) * chi2), 1e-9);

  // outputs that do not depend on u_2: that direction is flat, its sigma unknown (NaN)
  Eigen::MatrixXd K = J;
  K.col(1).setZero();
  std::vector<Eigen::VectorXd> z;
  for (const auto& p : u) z.push_back(K * p);
  const ResponseSurface t = fitResponseSurface(u, z, Eigen::Vector2d(0.5, 0.5), 0.5);
  const FitUncertainty h = uncertaintyAt(t, at, K * at, traceCov);
  REQUIRE(h.flat.size() == 1);
  CHECK(std::abs(std::abs(h.flat[0](1)) - 1.0) < 1e-9);
  CHECK(std::isnan(h.sigma[1]));
}

TEST_CASE("response surface: no more points than terms, or points without values, are refused") {
  std::vector<Eigen::VectorXd> u = grid();
  u.resize(6);
  std::vector<Eigen::VectorXd> y(6, Eigen::VectorXd::Zero(1));
  CHECK_THROWS_AS(fitResponseSurface(u, y, Eigen::Vector2d(0, 0), 1.0), std::invalid_argument);
  u = grid();
  CHECK_THROWS_AS(fitResponseSurface(u, y, Eigen::Vector2d(0, 0), 1.0), std::invalid_argument);
}
