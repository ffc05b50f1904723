// the environment (src/sim/environment.cpp): the plate frame, and each outside force piece against its
// closed form
#include <doctest/doctest.h>

#include "physics_support.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/rotation.hpp"
#include "rootsim/units.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
using rootsim::test::Cantilever;

TEST_CASE("plate frame: right-handed orthonormal, docs/model.md frame vectors, exact at 0 and 90 deg") {
  for (double deg : {0.0, 10.0, 40.0, 80.0, 90.0}) {
    INFO(deg);
    const PlateFrame f = PlateFrame::tilted(deg * units::deg);
    const double a = deg * units::deg;
    CHECK((f.normal - Vec3(0, -std::cos(a), std::sin(a))).norm() < 1e-15);
    CHECK((f.downhill - Vec3(0, -std::sin(a), -std::cos(a))).norm() < 1e-15);
    CHECK(f.lateral == Vec3::UnitX());
    // d1 = lateral, d2 = normal, d3 = downhill is right-handed (the initial directors)
    CHECK((f.lateral.cross(f.normal) - f.downhill).norm() < 1e-15);
    // gravity makes -sin(alpha) with the normal (docs/model.md, Frames and signs)
    ROOTSIM_CHECK_CLOSE(Vec3(0, 0, -1).dot(f.normal), -std::sin(a), kRoundoff);
  }
  // no round-off at the axis angles: cos(pi/2) would be 6e-17
  CHECK(PlateFrame::tilted(90 * units::deg).normal == Vec3(0, 0, 1));
  CHECK(PlateFrame::tilted(0).downhill == Vec3(0, 0, -1));
  // plate coordinates: a point 2 mm downhill, 0.5 mm to the side and R above the plate
  const PlateFrame f = PlateFrame::tilted(30 * units::deg);
  const Vec3 p = 2e-3 * f.downhill + 0.5e-3 * f.lateral + 1e-4 * f.normal;
  CHECK((f.coords(p) - Vec3(0.5e-3, 2e-3, 1e-4)).norm() < 1e-18);
  CHECK((f.toPlateMm(p) - Vec3(0.5, -2.0, 0.1)).norm() < 1e-12);
  CHECK((f.dirToPlate(f.downhill) - Vec3(0, -1, 0)).norm() < 1e-15);
}

TEST_CASE("plane contact: the penalty force k * depth along the normal, shared by the two nodes") {
  Cantilever c(4, 1e-3);
  c.env.plane.enabled = true;
  c.env.plane.alpha = 40 * units::deg;
  const Vec3 nh = c.env.plane.normal();
  // place the straight rod on the plate, then push element 2 (nodes 2, 3) 0.1 R into it
  const PlateFrame f = c.env.plane.frame();
  for (int i = 0; i < c.s.nodes(); ++i) c.s.x.col(i) = c.p.radius * nh + (i * 2.5e-4) * f.downhill;
  c.s.x.col(2) -= 0.1 * c.p.radius * nh;
  c.s.x.col(3) -= 0.1 * c.p.radius * nh;
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, c.s.nodes());
  addPlaneContact(c.p, c.env.plane, c.s, false, force);
  // elements 1 and 3 touch with half the depth (one node pushed in), element 2 with the full depth
  const double k = c.env.plane.k, d = 0.1 * c.p.radius;
  CHECK(force.col(0).norm() < 1e-9 * k * d);  // the surface touches: round-off of R n . n only
  const double tol = 1e-9 * k * d;
  CHECK((force.col(1) - 0.5 * k * 0.5 * d * nh).norm() < tol);
  CHECK((force.col(2) - 0.5 * k * (0.5 * d + d) * nh).norm() < tol);
  CHECK((force.col(3) - 0.5 * k * (d + 0.5 * d) * nh).norm() < tol);
  CHECK((force.col(4) - 0.5 * k * 0.5 * d * nh).norm() < tol);
  // material above the plate feels nothing
  for (int i = 0; i < c.s.nodes(); ++i) c.s.x.col(i) += 0.2 * c.p.radius * nh;
  force.setZero();
  addPlaneContact(c.p, c.env.plane, c.s, false, force);
  CHECK(force.norm() == 0.0);
}

TEST_CASE("adhesion pulls an anchored node back with k times its offset, and free nodes feel nothing") {
  Cantilever c(4, 1e-3);
  c.s.anchored.assign(static_cast<size_t>(c.s.nodes()), 0);
  c.s.anchored[2] = 1;
  c.s.anchor = c.s.x;
  c.s.x.col(2) += Vec3(1e-6, -2e-6, 0);
  c.s.x.col(3) += Vec3(5e-6, 0, 0);
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, c.s.nodes());
  addAdhesion(1000.0, c.s, force);
  CHECK((force.col(2) - 1000.0 * Vec3(-1e-6, 2e-6, 0)).norm() < 1e-15);
  CHECK(force.col(3).norm() == 0.0);
}

TEST_CASE("weight: total rho A L g lumped half to each node of an element") {
  Cantilever c(5, 1e-2);
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, c.s.nodes());
  const Vec3 g(0, 0, -9.81);
  addWeight(c.p, g, c.s, force);
  const double W = c.p.density * units::pi * c.p.radius * c.p.radius * 1e-2 * 9.81;
  CHECK(force.rowwise().sum().z() == doctest::Approx(-W).epsilon(1e-12));
  CHECK(force.col(0).z() == doctest::Approx(-W / 10).epsilon(1e-12));
  CHECK(force.col(1).z() == doctest::Approx(-W / 5).epsilon(1e-12));
}

TEST_CASE("the clamp: no couple on an undeformed base, a restoring couple when element 0 turns") {
  Cantilever c(10, 1e-2);
  RelaxWorkspace ws;
  computeForces(c.p, c.env, c.s, false, ws);
  CHECK(clampCouple(c.p, c.s, 1.0).torque.norm() == 0.0);
  // turn element 0 by a small angle about d1: the clamp's curvature is -angle / (l0/2) about d1 and
  // its couple B1 kappa pulls back
  const double th = 1e-3;
  const Vec3 d1 = c.s.Q[0].row(0).transpose();
  c.s.Q[0] = c.s.Q[0] * rotationFromVector(th * d1).transpose();
  const ClampCouple cc = clampCouple(c.p, c.s, 1.0);
  CHECK(std::abs(cc.kappa.norm() - th / (0.5 * c.s.l0[0])) < 1e-9 / c.s.l0[0]);
  CHECK(cc.m.norm() == doctest::Approx(c.p.bendStiffness().x() * cc.kappa.norm()).epsilon(1e-9));
  // holdClampedBase removes the reaction on node 0 only
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Ones(3, c.s.nodes());
  holdClampedBase(c.env, force);
  CHECK(force.col(0).norm() == 0.0);
  CHECK(force.col(1) == Vec3::Ones());
  c.env.base = BaseCondition::Free;
  force.setOnes();
  holdClampedBase(c.env, force);
  CHECK(force.col(0) == Vec3::Ones());
}
