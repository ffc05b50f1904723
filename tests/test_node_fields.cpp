// per-node quantities of a snapshot (src/sim/node_fields.cpp): the node frames, the material-frame angle,
// the bends, the stretch and the growth zone, on a snapshot whose answers are known: an arc of radius rho
// on a tilted plate whose material frame turns at a constant rate about the tangent
#include <doctest/doctest.h>

#include <cmath>

#include "rootsim/environment.hpp"
#include "rootsim/node_fields.hpp"
#include "rootsim/units.hpp"
#include "tolerance_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;

namespace {
constexpr double kRho = 5e-3;     // arc radius [m]
constexpr double kDelta = 0.02;   // turn of the tangent per element [rad]
constexpr double kTwist = 300.0;  // turn of d1 about the tangent per length [rad/m]
constexpr double kPhi0 = 0.7;     // material angle of the first element [rad]
constexpr double kR = 1e-4;       // rest radius [m]
constexpr int kN = 40;            // elements

// the arc in the plate of a plate tilted by 40 deg, the root lying on it (height R), d1 at the material
// angle kPhi0 + kTwist s (s: arc length at the element's middle), the element radii those of stretches
// 1 + 0.01 e
struct Arc {
  PlateFrame plate = PlateFrame::tilted(40 * units::deg);
  Snapshot s;
  Eigen::VectorXd phi;  // each element's material angle [rad]
  Arc() {
    s.x.resize(3, kN + 1);
    s.d1.resize(3, kN);
    s.d3.resize(3, kN);
    s.radius.resize(kN);
    phi.resize(kN);
    for (int i = 0; i <= kN; ++i) {
      const double th = kDelta * i;
      s.x.col(i) = kRho * std::sin(th) * plate.lateral + kRho * (1 - std::cos(th)) * plate.downhill + kR * plate.normal;
    }
    const double chord = 2 * kRho * std::sin(kDelta / 2);
    for (int e = 0; e < kN; ++e) {
      const Eigen::Vector3d t = (s.x.col(e + 1) - s.x.col(e)).normalized();
      phi[e] = kPhi0 + kTwist * chord * (e + 0.5);
      // the plate normal is normal to every tangent of an arc in the plate: the angle's reference
      s.d1.col(e) = std::cos(phi[e]) * plate.normal + std::sin(phi[e]) * t.cross(plate.normal);
      s.d3.col(e) = t;
      s.radius[e] = kR / std::sqrt(1 + 0.01 * e);
    }
  }
};
}  // namespace

TEST_CASE("node frames: unit and orthogonal and right-handed with the ends taking their one element") {
  const Arc a;
  const std::vector<NodeFrame> f = nodeFrames(a.s);
  REQUIRE(f.size() == kN + 1);
  for (const NodeFrame& g : f) {
    CHECK(g.t.norm() == doctest::Approx(1).epsilon(1e-14));
    CHECK(g.d1.norm() == doctest::Approx(1).epsilon(1e-14));
    CHECK(std::abs(g.t.dot(g.d1)) < 1e-14);
    CHECK((g.d2 - g.t.cross(g.d1)).norm() < 1e-15);
  }
  CHECK((f[0].d1 - a.s.d1.col(0)).norm() < 1e-14);
  CHECK((f[kN].t - a.s.d3.col(kN - 1)).norm() < 1e-14);
  CHECK(f[0].radius == a.s.radius[0]);
  CHECK(f[5].radius == doctest::Approx(0.5 * (a.s.radius[4] + a.s.radius[5])).epsilon(1e-15));
  // the map is applied before the averages: the plate coordinates of the lab frame's answer
  const std::vector<NodeFrame> p = nodeFrames(a.s, [&](const Eigen::Vector3d& d) { return a.plate.dirToPlate(d); });
  for (int i = 0; i <= kN; ++i) CHECK((p[static_cast<size_t>(i)].d1 - a.plate.dirToPlate(f[static_cast<size_t>(i)].d1)).norm() < 1e-14);
}

TEST_CASE("material angle: from the in-plate direction n x t to d1 right-handed about the tangent") {
  const Arc a;
  const std::vector<NodeFrame> f = nodeFrames(a.s);
  // the arc's d1 is kPhi0 + kTwist s from the plate normal, which is +90 deg from the reference n x t
  auto expected = [](double fromNormal) { return std::remainder(fromNormal + units::pi / 2, 2 * units::pi); };
  // the first node has one element: exactly its angle
  CHECK(materialAngle(f[0].t, f[0].d1, a.plate) == doctest::Approx(expected(a.phi[0])).epsilon(1e-12));
  for (int i = 0; i <= kN; ++i) {
    const NodeFrame& g = f[static_cast<size_t>(i)];
    const double ang = materialAngle(g.t, g.d1, a.plate);
    CAPTURE(i);
    CHECK(ang > -units::pi);
    CHECK(ang <= units::pi);
    // d1 = cos(angle) e + sin(angle) t x e, with e = n x t and n the plate normal made normal to t
    const Eigen::Vector3d n = (a.plate.normal - a.plate.normal.dot(g.t) * g.t).normalized(), e = n.cross(g.t);
    CHECK((std::cos(ang) * e + std::sin(ang) * g.t.cross(e) - g.d1).norm() < 1e-13);
    // between two elements: their mean angle, to the order of the tangent's turn
    if (i > 0 && i < kN) CHECK(ang == doctest::Approx(expected(0.5 * (a.phi[i - 1] + a.phi[i]))).epsilon(1e-4));
  }
  // quarter turns of a root growing along the lateral axis: d1 in the plate to its right is 0, away
  // from the plate +90 deg, into it -90 deg; a tangent along the normal measures from the lateral axis
  const Eigen::Vector3d t = a.plate.lateral;
  ROOTSIM_CHECK_CLOSE(materialAngle(t, a.plate.normal.cross(t), a.plate), 0.0, kRoundoff);
  ROOTSIM_CHECK_CLOSE(materialAngle(t, a.plate.normal, a.plate), units::pi / 2, kRoundoff);
  ROOTSIM_CHECK_CLOSE(materialAngle(t, -a.plate.normal, a.plate), -units::pi / 2, kRoundoff);
  ROOTSIM_CHECK_CLOSE(materialAngle(t, -a.plate.normal.cross(t), a.plate), units::pi, kRoundoff);
  ROOTSIM_CHECK_CLOSE(materialAngle(a.plate.normal, a.plate.lateral, a.plate), 0.0, kRoundoff);
  // the initial root grows downhill with d1 along the lateral axis: 0
  ROOTSIM_CHECK_CLOSE(materialAngle(a.plate.downhill, a.plate.lateral, a.plate), 0.0, kRoundoff);
}

TEST_CASE("bends: the arc's curvature 1/rho and the material frame's twist per length") {
  const Arc a;
  const std::vector<VoronoiBend> b = voronoiBends(a.s);
  REQUIRE(b.size() == kN - 1);
  const double chord = 2 * kRho * std::sin(kDelta / 2);
  for (const VoronoiBend& v : b) {
    CHECK(v.length == doctest::Approx(chord).epsilon(1e-12));
    // the log map's angle over the chord: 1/rho to O(delta^2); twist positive for d1 turning
    // right-handed towards the tip
    CHECK(std::hypot(v.kappa.x(), v.kappa.y()) / v.length == doctest::Approx(1 / kRho).epsilon(1e-3));
    CHECK(v.kappa.z() / v.length == doctest::Approx(kTwist).epsilon(1e-3));
  }
  Eigen::VectorXd vor(kN - 1);
  for (int j = 0; j < kN - 1; ++j) vor[j] = j;
  const Eigen::VectorXd nodes = voronoiToNodes(vor, kN);
  CHECK(nodes[0] == 0);
  CHECK(nodes[1] == 0);
  CHECK(nodes[kN - 1] == kN - 2);
  CHECK(nodes[kN] == kN - 2);
}

TEST_CASE("stretch from the radius and the growth zone from the rest lengths") {
  const Arc a;
  const Eigen::VectorXd l = nodeStretch(a.s, kR);
  REQUIRE(l.size() == kN + 1);
  CHECK(l[0] == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(l[kN] == doctest::Approx(1 + 0.01 * (kN - 1)).epsilon(1e-14));
  CHECK(l[10] == doctest::Approx(1 + 0.01 * 9.5).epsilon(1e-14));
  // rest lengths: chord / (1 + 0.01 e); the zone holds the nodes within Lgz of rest length of the tip
  const double chord = 2 * kRho * std::sin(kDelta / 2);
  const double zone = 1e-3;
  const Eigen::VectorXd z = growthZoneNodes(a.s, kR, zone);
  double fromTip = 0;
  int inZone = 0;
  for (int i = kN; i >= 0; --i) {
    if (i < kN) fromTip += chord / (1 + 0.01 * i);
    CHECK(z[i] == (fromTip <= zone ? 1.0 : 0.0));
    inZone += z[i] > 0;
  }
  CHECK(inZone > 5);
  CHECK(inZone < kN);
  CHECK(z[kN] == 1.0);
  CHECK(z[0] == 0.0);
}
