// the quasi-static Newton solver (src/sim/relax_newton.cpp): the same equilibria as the explicit solver,
// stability from the factorisation, relaxation windows, no allocation once warm. Its band algebra is in
// test_band.cpp, its Jacobian against plain finite differences in test_stiffness.cpp.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "physics_support.hpp"
#include "rootsim/band.hpp"
#include "rootsim/rotation.hpp"
#include "rootsim/stability.hpp"

using namespace rootsim;
using rootsim::test::Cantilever;
using rootsim::test::gAllocs;

TEST_CASE("Newton finds the explicit solver's cantilever equilibria (small and large load)") {
  for (double load : {1e-6, 1e-4}) {
    Cantilever a(40), b(40);
    a.env.tipForce = b.env.tipForce = Vec3(0, 0, -load);
    a.relax();
    b.opt.kind = SolverKind::Newton;
    NewtonWorkspace nw;
    const RelaxResult r = relaxNewton(b.p, b.env, b.opt, b.s, b.ws, nw, 0);
    INFO("load " << load << " N: " << r.iterations << " Newton iterations");
    CHECK(r.converged);
    // quadratic convergence from the straight start for the small load; the large one (P L^2 / B = 2.6,
    // tip rotation ~60 deg) from the straight start in one load step takes longer
    CHECK(r.iterations <= (load < 1e-5 ? 8 : 40));
    CHECK((a.tip() - b.tip()).norm() < 1e-6 * a.L);
  }
}

TEST_CASE("Newton's factorisation tells Euler buckling, as the stability check does") {
  for (double ratio : {0.9, 1.1}) {
    Cantilever c(30);
    const double Pcr = std::numbers::pi * std::numbers::pi * c.B1() / (4 * c.L * c.L);
    c.env.tipForce = Vec3(0, ratio * Pcr, 0);
    NewtonWorkspace nw;
    const RelaxResult r = relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, 0);
    REQUIRE(r.converged);
    CHECK(std::abs(c.tip().x()) < 1e-12);  // the straight column is an equilibrium either way
    CHECK(nw.negative == checkStability(c.p, c.env, c.s, c.ws).negative);
    CHECK(nw.negative == (ratio < 1 ? 0 : 2));
    if (ratio > 1) {
      CHECK(nw.lowestEigenvalue < 0);
      // following the mode with a short explicit relaxation reaches the buckled branch
      perturbAlong(c.s, nw.unstableMode(c.s, c.env), 1e-2 * c.p.radius);
      c.relax();
      REQUIRE(relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, 0).converged);
      CHECK(nw.negative == 0);
      CHECK(std::hypot(c.tip().x(), c.tip().z()) / c.L > 0.3);
    } else {
      CHECK(nw.lowestEigenvalue > 0);
    }
  }
}

TEST_CASE("a window freezes the positions of the rest of the rod exactly and leaves its twist free") {
  Cantilever c(30);
  c.env.tipForce = Vec3(0, 0, -1e-5);
  const RodState before = c.s;
  NewtonWorkspace nw;
  const RelaxResult r = relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, 20);
  CHECK(r.converged);
  for (int i = 0; i < 20; ++i) CHECK(c.s.x.col(i) == before.x.col(i));  // node 20 is the first free one
  // mature elements may only turn about their own axis: d3 stays where it was
  for (int i = 0; i < 20; ++i)
    CHECK((c.s.Q[static_cast<size_t>(i)].row(2) - before.Q[static_cast<size_t>(i)].row(2)).norm() < 1e-12);
  CHECK(c.s.x.col(30) != before.x.col(30));
}

TEST_CASE("a window carries torsion through the frozen root: the tip twists by T L / C under a tip couple") {
  // a clamped straight rod under a couple T about its axis: uniform twist rate T / C (C = B3), tip twist
  // T L / C. With the window from node 20 of 30, the twist of elements 0-19 is solved for, not frozen.
  for (int first : {0, 20}) {
    Cantilever c(30);
    const double C = c.p.bendStiffness().z();
    const Vec3 axis = (c.s.x.col(30) - c.s.x.col(0)).normalized();
    const double T = 1e-3 * C / c.L;  // tip twist 1e-3 rad
    c.env.tipTorque = T * axis;
    const Vec3 d1 = c.s.Q.back().row(0).transpose();
    NewtonWorkspace nw;
    const RelaxResult r = relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, first);
    CHECK(r.converged);
    const Vec3 d1n = c.s.Q.back().row(0).transpose();
    const double twist = std::atan2(d1.cross(d1n).dot(axis), d1.dot(d1n));
    // the last element's d1 sits at the middle of the element: L - lbar / 2 of twisting length
    const double lbar = c.L / 30;
    INFO("window from node " << first << ": tip twist " << twist << " rad, T (L - lbar/2) / C = " << T * (c.L - 0.5 * lbar) / C);
    CHECK(twist == doctest::Approx(T * (c.L - 0.5 * lbar) / C).epsilon(1e-3));
  }
}

TEST_CASE("a Newton relaxation allocates nothing once its workspace has seen the rod") {
  Cantilever c(60);
  c.env.plane.enabled = true;
  c.env.plane.alpha = 0.7;
  c.env.adhesion = true;
  c.s.anchored[5] = 1;
  c.env.tipForce = Vec3(1e-6, 0, -1e-6);
  c.opt.stabilityCheck = true;
  NewtonWorkspace nw;
  REQUIRE(relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, 0).converged);  // warm-up sizes everything
  c.env.tipForce = Vec3(2e-6, 0, -1e-6);
  const long before = gAllocs.load();
  const RelaxResult r = relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, 10);
  const long allocs = gAllocs.load() - before;
  CHECK(r.converged);
  CHECK(r.iterations > 0);
  CHECK(allocs == 0);
}
