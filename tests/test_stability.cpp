// stability of equilibria (src/sim/stability.cpp): the inertia of K finds Euler buckling
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "physics_support.hpp"
#include "rootsim/stability.hpp"
#include <Eigen/Dense>

using rootsim::test::kRoundoff;

using namespace rootsim;
using rootsim::test::Cantilever;

TEST_CASE("a straight clamped-free column is stable below Pcr and has one unstable pair above it") {
  for (int n : {20, 40}) {
    for (double ratio : {0.9, 1.1}) {
      Cantilever c(n);
      const double Pcr = std::numbers::pi * std::numbers::pi * c.B1() / (4 * c.L * c.L);
      c.env.tipForce = Vec3(0, ratio * Pcr, 0);  // compression along -d3 = +y, no imperfection
      c.relax();                                 // stays straight: the straight state is an equilibrium
      CHECK(std::abs(c.tip().x()) < 1e-12);
      const StabilityReport r = checkStability(c.p, c.env, c.s, c.ws);
      INFO("n " << n << " P/Pcr " << ratio << " negative pivots " << r.negative);
      if (ratio < 1) {
        CHECK(r.negative == 0);
      } else {
        // buckling in x and in z (the section is round): two unstable directions
        CHECK(r.negative == 2);
        REQUIRE(r.mode.size() > 0);
        CHECK(r.lowest < 0);
        // the mode is a lateral deflection growing toward the tip
        const Vec3 tipMode = r.mode.segment<3>(6 * n);
        CHECK(std::abs(tipMode.y()) < 1e-3 * tipMode.norm());
        CHECK(tipMode.norm() == doctest::Approx(1.0).epsilon(1e-6));
      }
    }
  }
}

TEST_CASE("following the unstable mode leads to the buckled equilibrium") {
  Cantilever c(20);
  const double Pcr = std::numbers::pi * std::numbers::pi * c.B1() / (4 * c.L * c.L);
  c.env.tipForce = Vec3(0, 1.1 * Pcr, 0);
  c.relax();
  const StabilityReport r = checkStability(c.p, c.env, c.s, c.ws);
  REQUIRE(r.negative > 0);
  perturbAlong(c.s, r.mode, 1e-2 * c.p.radius);
  c.relax();
  const double defl = std::hypot(c.tip().x(), c.tip().z()) / c.L;
  CHECK(defl > 0.3);  // post-buckling at 1.1 Pcr: tip angle^2 ~ 8 (P/Pcr - 1)
  CHECK(checkStability(c.p, c.env, c.s, c.ws).negative == 0);
}

TEST_CASE("the softest modes are the eigenpairs of the symmetric stiffness nearest zero") {
  Cantilever c(12);
  const double Pcr = std::numbers::pi * std::numbers::pi * c.B1() / (4 * c.L * c.L);
  c.env.tipForce = Vec3(0, 0.5 * Pcr, 0);  // half the buckling load: stable, soft in bending
  c.relax();
  const StiffnessModes sm = softestModes(c.p, c.env, c.s, 3);
  REQUIRE(sm.eigenvalues.size() == 3);
  // the same matrix, dense
  NewtonWorkspace nw;
  RodState s = c.s;
  assembleStiffness(c.p, c.env, c.opt, s, c.ws, nw, 0);
  const int N = nw.lu.size();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      if (nw.lu.inBand(i, j) && nw.lu.inBand(j, i)) K(i, j) = 0.5 * (nw.lu.at(i, j) + nw.lu.at(j, i));
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();  // ascending
  CHECK(ev[0] > 0);
  for (int q = 0; q < 3; ++q) CHECK(sm.eigenvalues[q] == doctest::Approx(ev[q]).epsilon(1e-8));
  // the two softest are the bending pair (round section: equal), the third is stiffer
  CHECK(sm.eigenvalues[1] == doctest::Approx(sm.eigenvalues[0]).epsilon(1e-6));
  CHECK(sm.eigenvalues[2] > 2 * sm.eigenvalues[1]);
  ROOTSIM_CHECK_CLOSE(sm.modes[0].segment<3>(6 * 12).norm(), 1.0, kRoundoff);  // tip moves most
}
