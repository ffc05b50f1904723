// The force evaluation every solver shares (src/sim/forces.cpp): strains, internal forces, external
// pieces and the clamp, checked against closed forms: the lumped weight of a straight rod, Newton's third
// law for the internal forces of a bent free rod, and the clamp holding only node 0.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "physics_support.hpp"
#include "rootsim/forces.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;
using namespace rootsim::test;

TEST_CASE("forces: a straight stress-free rod under gravity carries its lumped weight, rho A g l per interior node, none on the clamped node 0") {
  Cantilever c(10);
  const Vec3 g(0, 0, -9.81);
  c.env.gravity = g;
  computeForces(c.p, c.env, c.s, false, c.ws);
  const double rhoA = c.p.density * units::pi * c.p.radius * c.p.radius;
  const double l = c.s.l0[0];
  // the rod is straight to round-off: its strain is 1 +- a few ulp, times the stretch stiffness E A
  const double roundOff = 32.0 * std::numeric_limits<double>::epsilon() * c.p.shearStiffness().z();
  CHECK(c.ws.force.col(0).norm() == 0.0);
  for (int i = 1; i <= c.s.elements(); ++i) {
    const double share = i < c.s.elements() ? l : 0.5 * l;
    const Vec3 want = rhoA * share * g;
    INFO("node " << i << ": weight " << want.norm() << " N, round-off of the stretch force " << roundOff << " N");
    CHECK((c.ws.force.col(i) - want).norm() <= roundOff);
  }
  CHECK(roundOff < 1e-6 * rhoA * l * 9.81);  // the check above resolves the weight to a millionth
  // no strain, so no couple
  CHECK(c.ws.torque.cwiseAbs().maxCoeff() < 1e-12 * rhoA * l * l * 9.81);
}

TEST_CASE("forces: the internal forces of a bent free rod sum to zero (Newton's third law), and the clamp zeroes node 0 only") {
  Cantilever c(16);
  c.env.base = BaseCondition::Free;
  // an intrinsic curvature about d1 the straight rod does not have: it pulls and bends
  for (int j = 0; j < c.s.kappa0.cols(); ++j) c.s.kappa0(0, j) = 200.0;
  // and a stretch of one element
  c.s.x.rightCols(c.s.nodes() - 5).colwise() += Vec3(0, 0, 2e-6);
  computeForces(c.p, c.env, c.s, false, c.ws);
  const Eigen::Matrix3Xd freeForce = c.ws.force;
  const double scale = freeForce.colwise().norm().maxCoeff();
  REQUIRE(scale > 0.0);
  ROOTSIM_CHECK_REL("net internal force", freeForce.rowwise().sum().norm(), 0.0, 1e-12 * scale);

  c.env.base = BaseCondition::Clamped;
  computeForces(c.p, c.env, c.s, false, c.ws);
  CHECK(c.ws.force.col(0).norm() == 0.0);
  // the clamp's couple acts on element 0's torque, the other nodes feel the same forces
  CHECK((c.ws.force.rightCols(c.s.nodes() - 1) - freeForce.rightCols(c.s.nodes() - 1)).norm() <= 1e-12 * scale);
}

TEST_CASE("forces: the overload of a first element is the span overload from it") {
  Cantilever c(16);
  c.env.gravity = Vec3(0, 0, -9.81);
  for (int j = 0; j < c.s.kappa0.cols(); ++j) c.s.kappa0(1, j) = 150.0;
  RelaxWorkspace a, b;
  // the entries before `first` are not written: start both from the same zeros
  for (RelaxWorkspace* w : {&a, &b}) {
    w->resize(c.s.elements());
    w->force.setZero();
    w->torque.setZero();
  }
  computeForces(c.p, c.env, c.s, false, a, 6);
  computeForces(c.p, c.env, c.s, false, b, ForceSpan{6, -1, 6});
  CHECK((a.force - b.force).norm() == 0.0);
  CHECK((a.torque - b.torque).norm() == 0.0);
}
