// unit tests of the discrete rod operators and the state's field list walkers (src/sim/rod.cpp)
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <string>

#include "physics_support.hpp"
#include "rootsim/rod_fields.hpp"
#include "rootsim/rotation.hpp"

using namespace rootsim;
using rootsim::test::Cantilever;

TEST_CASE("a straight rod at rest carries no force and no couple") {
  Cantilever c(20);
  computeForces(c.p, c.env, c.s, false, c.ws);
  CHECK(c.ws.force.norm() < 1e-12 * c.p.shearStiffness().z());
  CHECK(c.ws.torque.norm() < 1e-12 * c.p.bendStiffness().x() / c.s.l0[0]);
}

TEST_CASE("curvature sign: directors turning about d2 along s give kappa2 > 0 (d d_j/ds = kappa x d_j)") {
  Cantilever c(10);
  const double k = 50.0;  // [1/m]
  const double l = c.s.l0[0];
  // element i rotated about d2 (lab z) by k * s_mid, so dd_j/ds = (k z) x d_j
  Cantilever ref(10);
  for (int i = 0; i < c.s.elements(); ++i) {
    const Mat3 R = Eigen::AngleAxisd(k * (i + 0.5) * l, Vec3::UnitZ()).toRotationMatrix();
    c.s.Q[i] = (R * ref.s.Q[0].transpose()).transpose();
  }
  c.ws.resize(c.s.elements());
  computeStrains(c.p, c.s, c.ws.strains);
  for (int j = 0; j + 1 < c.s.elements(); ++j) {
    CHECK(c.ws.strains.kappa(0, j) == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(c.ws.strains.kappa(1, j) == doctest::Approx(k).epsilon(1e-12));  // d2 = lab z
    CHECK(std::abs(c.ws.strains.kappa(2, j)) < 1e-9);
  }
}

TEST_CASE("curvature equals the rotation vector of Q_j Q_{j+1}^T / D0 at small, moderate and large bends") {
  // relativeRotation's series branch (|theta| < 13 deg) and its atan2 branch against rotationToVector
  Cantilever c(2);
  c.ws.resize(c.s.elements());
  const Vec3 axis = Vec3(0.3, -0.5, 0.8).normalized();
  for (double theta : {1e-6, 1e-3, 0.05, 0.1, 0.2, 0.2249, 0.2251, 0.3, 1.0, 2.5}) {
    CAPTURE(theta);
    c.s.Q[1] = Eigen::AngleAxisd(-theta, axis).toRotationMatrix() * c.s.Q[0];  // Q_0 Q_1^T = exp(theta axis)
    computeStrains(c.p, c.s, c.ws.strains);
    const Vec3 ref = rotationToVector(c.s.Q[0] * c.s.Q[1].transpose()) / c.ws.strains.D0[0];
    const Vec3 got = c.ws.strains.kappa.col(0);
    CHECK((got - ref).norm() <= 1e-14 * theta / c.ws.strains.D0[0]);
    CHECK(got.norm() * c.ws.strains.D0[0] == doctest::Approx(theta).epsilon(1e-14));
  }
}

TEST_CASE("frame invariance: a rigidly rotated, deformed rod gives rotated forces and equal couples") {
  Cantilever a(16);
  // deform: random-ish node displacements and director rotations
  std::uint64_t rng = 7;
  for (int i = 0; i < a.s.nodes(); ++i)
    for (int d = 0; d < 3; ++d) a.s.x(d, i) += 2e-5 * splitmixUniform(rng);
  for (int i = 0; i < a.s.elements(); ++i) {
    Vec3 phi(splitmixUniform(rng), splitmixUniform(rng), splitmixUniform(rng));
    a.s.Q[i] = rotationFromVector(0.2 * phi) * a.s.Q[i];
  }
  a.env.base = BaseCondition::Free;
  a.env.tipForce = Vec3(1e-4, -2e-4, 3e-5);
  Cantilever b = a;
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (int i = 0; i < b.s.nodes(); ++i) b.s.x.col(i) = R * a.s.x.col(i);
  for (int i = 0; i < b.s.elements(); ++i) b.s.Q[i] = a.s.Q[i] * R.transpose();
  b.env.tipForce = R * a.env.tipForce;
  computeForces(a.p, a.env, a.s, false, a.ws);
  computeForces(b.p, b.env, b.s, false, b.ws);
  const double fs = a.ws.force.cwiseAbs().maxCoeff(), ts = a.ws.torque.cwiseAbs().maxCoeff();
  CHECK(fs > 1e-6);
  CHECK((b.ws.force - R * a.ws.force).cwiseAbs().maxCoeff() < 1e-12 * fs);
  CHECK((b.ws.torque - a.ws.torque).cwiseAbs().maxCoeff() < 1e-12 * ts);
}

TEST_CASE("internal forces balance: no net force or couple on a free rod") {
  Cantilever a(12);
  a.env.base = BaseCondition::Free;
  std::uint64_t rng = 3;
  for (int i = 0; i < a.s.nodes(); ++i)
    for (int d = 0; d < 3; ++d) a.s.x(d, i) += 1e-5 * splitmixUniform(rng);
  for (int i = 0; i < a.s.elements(); ++i)
    a.s.Q[i] = rotationFromVector(0.1 * Vec3(splitmixUniform(rng), splitmixUniform(rng), 0)) * a.s.Q[i];
  computeForces(a.p, a.env, a.s, false, a.ws);
  // sum of forces vanishes; total moment about the origin: sum x_i x F_i + sum Q_i^T tau_i
  Vec3 F = a.ws.force.rowwise().sum();
  Vec3 M = Vec3::Zero();
  for (int i = 0; i < a.s.nodes(); ++i) M += Vec3(a.s.x.col(i)).cross(Vec3(a.ws.force.col(i)));
  for (int i = 0; i < a.s.elements(); ++i) M += a.s.Q[i].transpose() * a.ws.torque.col(i);
  const double fs = a.ws.force.cwiseAbs().maxCoeff();
  CHECK(F.norm() < 1e-12 * fs);
  CHECK(M.norm() < 1e-8 * fs * a.L);  // round-off: stretch forces cancel
}

TEST_CASE("resize sizes every field of the rod state's list along its nodes, elements or Voronoi domains") {
  for (int n : {1, 2, 7}) {
    RodState s;
    s.resize(n);
    CAPTURE(n);
    CHECK(s.elements() == n);
    forEachRodField([&](auto index) {
      constexpr auto f = std::get<decltype(index)::value>(FieldsOf<RodState>::list());
      CAPTURE(f.name);
      CHECK(valueCount(s.*f.member) == valuesAlong(f.along, n));
    });
    CHECK(fieldOffElementCount(s) == nullptr);
    // flags start cleared
    for (auto b : s.anchored) CHECK(b == 0);
  }
  CHECK(valuesAlong(Along::Node, 5) == 6);
  CHECK(valuesAlong(Along::Element, 5) == 5);
  CHECK(valuesAlong(Along::Voronoi, 5) == 4);
  CHECK(valuesAlong(Along::Voronoi, 1) == 0);
  CHECK(valuesAlong(Along::Rod, 5) == 1);
}

TEST_CASE("the element-count check names each listed array whose length does not fit") {
  forEachRodField([&](auto index) {
    constexpr auto f = std::get<decltype(index)::value>(FieldsOf<RodState>::list());
    if constexpr (f.along != Along::Rod) {
      RodState s;
      s.resize(6);
      // one value too many in this field alone
      RodState longer;
      longer.resize(7);
      s.*f.member = longer.*f.member;
      if (std::string(f.name) == "l0") {
        // the rest lengths set the count: every other array is then off, the first one named
        CHECK(std::string(fieldOffElementCount(s)) == "x");
      } else {
        CAPTURE(f.name);
        REQUIRE(fieldOffElementCount(s) != nullptr);
        CHECK(std::string(fieldOffElementCount(s)) == f.name);
      }
    }
  });
}
