// the equilibrium tolerance of both solvers (src/sim/tolerance.cpp: equilibriumTolerance and
// appliedLoadScale; the rule: docs/model.md, Relaxation)
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics_support.hpp"
#include "rootsim/tolerance.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;
using rootsim::test::Cantilever;

TEST_CASE("equilibrium tolerance: the elastic scale without loads or above it, the applied loads below it") {
  Cantilever c(40, 1e-2, 1e-4);
  const double B1 = c.p.bendStiffness().x(), L = c.s.restLength();
  const double elastic = B1 / (L * L);
  // no load: the rod's own scale
  EquilibriumTolerance t = equilibriumTolerance(c.p, c.env, c.opt, c.s, 0);
  CHECK(t.force == c.opt.forceTol * elastic);
  CHECK(t.couple == c.opt.forceTol * B1 / L);
  // a tip force above the elastic scale: still the elastic scale
  c.env.tipForce = Vec3(0, 0, -3 * elastic);
  CHECK(appliedLoadScale(c.p, c.env, c.s, L, 0) == 3 * elastic);
  t = equilibriumTolerance(c.p, c.env, c.opt, c.s, 0);
  CHECK(t.force == c.opt.forceTol * elastic);
  // a tip force of a thousandth of it: the tolerance follows the load, far below the elastic scale
  const double P = 1e-3 * elastic;
  c.env.tipForce = Vec3(0, 0, -P);
  t = equilibriumTolerance(c.p, c.env, c.opt, c.s, 0);
  // the documented floor (relax.hpp): kResolvableResidual times the round-off r of a node force
  double kmax = 0;
  for (int i = 0; i < c.s.elements(); ++i) kmax = std::max(kmax, 1.0 / c.s.l0[i]);
  const double r = std::numeric_limits<double>::epsilon() * kmax * c.p.shearStiffness().maxCoeff() *
                   c.s.x.colwise().norm().maxCoeff();
  const double floor = std::min(c.opt.forceTol * elastic, kResolvableResidual * r);
  CHECK(floor < c.opt.forceTol * elastic);
  CHECK(t.force == doctest::Approx(std::max(c.opt.forceTol * P, floor)).epsilon(1e-12));
  CHECK(t.force < c.opt.forceTol * elastic);
  CHECK(t.couple == doctest::Approx(std::max(c.opt.forceTol * P * L, std::min(c.opt.forceTol * B1 / L, floor * L))).epsilon(1e-12));
  // a tip couple counts as the force couple / Lref
  c.env.tipForce = Vec3::Zero();
  c.env.tipTorque = Vec3(0, 2 * P * L, 0);
  CHECK(appliedLoadScale(c.p, c.env, c.s, L, 0) == doctest::Approx(2 * P).epsilon(1e-15));
  // with an explicit length scale the elastic scale is B1 / lengthScale^2
  c.env.tipTorque = Vec3::Zero();
  c.opt.lengthScale = 0.25 * L;
  t = equilibriumTolerance(c.p, c.env, c.opt, c.s, 0);
  CHECK(t.force == c.opt.forceTol * (B1 / (0.25 * L * 0.25 * L)));
}

TEST_CASE("equilibrium tolerance: weight is lumped half an element to each side, counted from the first free node") {
  Cantilever c(10, 1e-2, 1e-4);
  c.env.gravity = Vec3(0, 0, -9.81);
  const double L = c.s.restLength();
  const double rhoAg = c.p.density * units::pi * c.p.radius * c.p.radius * 9.81;
  // an interior node carries half of each neighbouring element: rho A g l
  double want = 0;
  for (int i = 0; i <= c.s.elements(); ++i) {
    const double l = (i > 0 ? c.s.l0[i - 1] : 0.0) + (i < c.s.elements() ? c.s.l0[i] : 0.0);
    want = std::max(want, 0.5 * rhoAg * l);
  }
  CHECK(appliedLoadScale(c.p, c.env, c.s, L, 0) == doctest::Approx(want).epsilon(1e-14));
  CHECK(want == doctest::Approx(rhoAg * L / c.s.elements()).epsilon(1e-12));
  // the tip node alone (first free node = n) carries half an element
  CHECK(appliedLoadScale(c.p, c.env, c.s, L, c.s.elements()) == doctest::Approx(0.5 * rhoAg * c.s.l0[c.s.elements() - 1]).epsilon(1e-14));
  // the weight of a 1 cm root is far below the elastic scale: the tolerance is a fraction of it, above
  // the round-off floor
  const EquilibriumTolerance t = equilibriumTolerance(c.p, c.env, c.opt, c.s, 0);
  CHECK(t.force >= c.opt.forceTol * want * (1 - 1e-12));
  CHECK(t.force < c.opt.forceTol * c.p.bendStiffness().x() / (L * L));
}
