// growth (src/sim/growth.cpp) and coarse versions of the paper's patterns
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>
#include <numbers>

#include "physics_support.hpp"
#include "rod_fields_support.hpp"
#include "rootsim/growth.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/theory.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;

namespace {
constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;

// a coarse growth model: 0.1 mm elements (10 in the zone), 0.1 h steps
using rootsim::test::coarse;

ShapeAnalysis grow(const Model& m, Simulation** out = nullptr) {
  static Simulation* keep = nullptr;
  delete keep;
  keep = new Simulation(m);
  for (int i = 0; i < m.growth.steps; ++i) keep->growthStep();
  if (out) *out = keep;
  return analyseShape(m, keep->state());
}
}  // namespace

TEST_CASE("sign of Eq. 17: a free horizontal root under gravitropism alone bends its tip down") {
  Model m = coarse(90, 0.2, 20);
  m.env.plane.enabled = false;
  m.env.adhesion = false;
  m.tropism.gamma = 0.0;
  Simulation sim(m);
  for (int i = 0; i < 20; ++i) sim.growthStep();
  const RodState& s = sim.state();
  const int n = s.elements();
  const Vec3 t = (s.x.col(n) - s.x.col(n - 1)).normalized();
  INFO("tip tangent " << t.transpose());
  CHECK(t.z() < -0.1);                   // pointing down, toward gravity
  CHECK(std::abs(t.x()) < 1e-6);         // and not sideways
  CHECK(s.kappa0.row(0).maxCoeff() > 0);  // kappa1 > 0 about d1 = x bends d3 toward -z
}

TEST_CASE("kinematics: the rest length grows at v_tip = eps0 Lgz and elements split at 2h") {
  Model m = coarse(40, 0.1, 50);
  Simulation sim(m);
  const double L0 = sim.state().restLength();
  for (int i = 0; i < 50; ++i) sim.growthStep();
  const double vtip = m.growth.rate * m.growth.zoneLength;
  CHECK(sim.state().restLength() == doctest::Approx(L0 + vtip * 50 * m.growth.stepTime).epsilon(1e-12));
  CHECK(sim.state().l0.maxCoeff() <= m.growth.splitFactor * m.initial.elementLength * (1 + 1e-12));
  // material outside the zone never grows: the first element keeps its length
  CHECK(sim.state().l0[0] == doctest::Approx(L0 / 11).epsilon(1e-12));
}

TEST_CASE("splitting keeps the centreline, directors, kappa0 and the total rest length") {
  Model m = coarse(40, 0.1, 0);
  Simulation sim(m);
  RodState s = sim.state();
  const int n = s.elements();
  for (int j = 0; j + 1 < n; ++j) s.kappa0.col(j) = Vec3(0.1 * j, -0.2 * j, 0.05);
  s.l0[5] *= 2.5;  // make element 5 long
  s.S[0] = 0;
  for (int i = 0; i < n; ++i) s.S[i + 1] = s.S[i] + s.l0[i];
  const RodState before = s;
  CHECK(splitLongElements(m, s) == 1);
  CHECK(s.elements() == n + 1);
  CHECK(s.restLength() == doctest::Approx(before.restLength()).epsilon(1e-15));
  CHECK((s.x.col(5) - before.x.col(5)).norm() == 0.0);
  CHECK((s.x.col(7) - before.x.col(6)).norm() == 0.0);
  CHECK((s.x.col(6) - 0.5 * (before.x.col(5) + before.x.col(6))).norm() < 1e-18);
  CHECK((s.Q[5] - before.Q[5]).norm() == 0.0);
  CHECK((s.Q[6] - before.Q[5]).norm() == 0.0);
  CHECK((s.kappa0.col(4) - before.kappa0.col(4)).norm() == 0.0);   // node left of the split element
  CHECK((s.kappa0.col(6) - before.kappa0.col(5)).norm() == 0.0);   // node right of it
  CHECK((s.kappa0.col(5) - 0.5 * (before.kappa0.col(4) + before.kappa0.col(5))).norm() < 1e-15);
}

TEST_CASE("splitting carries every field of the rod state's list by the rule its entry names") {
  Model m = coarse(40, 0.1, 0);
  Simulation sim(m);
  RodState base = sim.state();
  test::fillDistinct(base);
  const int n = base.elements();
  for (int i = 0; i < n; ++i) base.l0[i] = m.initial.elementLength;
  // the first, an inner and the last element long: both ends' Voronoi rules and an inner one
  for (int i : {0, 5, n - 1}) base.l0[i] *= 2.5;
  RodState split = base;
  REQUIRE(splitLongElements(m, split) == 3);
  REQUIRE(split.elements() == n + 3);
  CHECK(fieldOffElementCount(split) == nullptr);

  forEachRodField([&](auto index) {
    constexpr std::size_t I = decltype(index)::value;
    constexpr auto f = test::rodField<I>();
    CAPTURE(f.name);
    // the field changed on its own (rest lengths by less than would change which elements split)
    RodState changed = base;
    test::perturbField<I>(changed, 1e-7);
    REQUIRE(splitLongElements(m, changed) == 3);
    const std::vector<std::string> d = test::differingFields(split, changed);
    if constexpr (f.split == OnSplit::Zero || f.split == OnSplit::Recompute) {
      // reset or recomputed: the split state does not depend on it
      CHECK(std::find(d.begin(), d.end(), std::string(f.name)) == d.end());
    } else {
      // carried: the split state changes in it, and otherwise only in what is recomputed from it
      CHECK(std::find(d.begin(), d.end(), std::string(f.name)) != d.end());
      for (const std::string& other : d) {
        bool recomputed = other == f.name;
        forEachRodField([&](auto j) {
          constexpr auto g = test::rodField<decltype(j)::value>();
          if (other == g.name && g.split == OnSplit::Recompute) recomputed = true;
        });
        CHECK_MESSAGE(recomputed, other, " changed with ", f.name);
      }
    }
  });

  // the rules' values at the inner split element 5 (output elements 6 and 7, new node 7)
  const RodState& t = split;
  CHECK((t.anchor.col(7) == 0.5 * (base.anchor.col(5) + base.anchor.col(6))));
  CHECK((t.plateStick.col(7) == 0.5 * (base.plateStick.col(5) + base.plateStick.col(6))));
  CHECK((t.obstacleStick.col(7) == 0.5 * (base.obstacleStick.col(5) + base.obstacleStick.col(6))));
  using Flags = std::vector<std::uint8_t> RodState::*;
  for (Flags flags : {&RodState::anchored, &RodState::hasPlateStick, &RodState::hasObstacleStick}) {
    const auto &got = t.*flags, &from = base.*flags;
    CHECK(got[7] == (from[5] && from[6] ? 1 : 0));
    CHECK(got[6] == from[5]);
    CHECK(got[8] == from[6]);
  }
  CHECK(t.l0[6] == 0.5 * base.l0[5]);
  CHECK(t.l0[7] == 0.5 * base.l0[5]);
  CHECK((t.Q[6] == base.Q[5]));
  CHECK((t.Q[7] == base.Q[5]));
  CHECK(t.v.isZero(0.0));
  CHECK(t.w.isZero(0.0));
  CHECK((t.clampFrame == base.clampFrame));
  CHECK(t.time == base.time);
  // the end domains: the first split element's new domain takes its one neighbour's value, the last's too
  CHECK((t.kappa0.col(0) == base.kappa0.col(0)));
  CHECK((t.kappa0.col(t.elements() - 2) == base.kappa0.col(n - 2)));
  // material coordinates recomputed from the split rest lengths
  CHECK(t.S[0] == 0.0);
  for (int i = 0; i < t.elements(); ++i) CHECK(t.S[i + 1] == t.S[i] + t.l0[i]);
}

TEST_CASE("twist profile (Eqs. 20-21): zero at the apex, tau at the zone start and beyond") {
  Model m = coarse(30, 0.2, 0);
  m.tropism.rTau = 0.4;
  Simulation sim(m);
  RodState s = sim.state();
  applyTwistProfile(m, s);
  const double tau = 0.4 / m.rod.radius, L = s.restLength();
  for (int j = 0; j + 1 < s.elements(); ++j) {
    const double u = std::clamp((L - s.S[j + 1]) / m.growth.zoneLength, 0.0, 1.0);
    ROOTSIM_CHECK_CLOSE(s.kappa0(2, j), tau * u, kRoundoff);
  }
  ROOTSIM_CHECK_CLOSE(s.kappa0(2, 0), tau, kRoundoff);  // node at 0.1 mm: mature
}

TEST_CASE("coarse Fig. 2A: alpha = 0 grows straight, 40 waves, 80 coils, and contact depth stays < R/10") {
  SUBCASE("alpha 0: straight") {
    const ShapeAnalysis a = grow(coarse(0, 0.1, 150));
    CHECK(a.pattern == "straight");
  }
  SUBCASE("alpha 40, beta 0.2: waving with theta_tip swinging both ways") {
    Simulation* sim = nullptr;
    Model m = coarse(40, 0.2, 350);
    const ShapeAnalysis a = grow(m, &sim);
    INFO("pattern " << a.pattern << " peaks " << a.peaks << " lambda " << a.wavelength << " theta ["
                    << a.thetaMin / deg << ", " << a.thetaMax / deg << "]");
    CHECK(a.pattern == "waving");
    CHECK(a.thetaMin < -20 * deg);
    CHECK(a.thetaMax > 20 * deg);
    // wavelength within a factor 2 of Eq. 9 (the coarse mesh and the short run are not the paper's)
    const Theory t = theoryFor(m);
    CHECK(a.wavelength > 0.5 * t.wavelength);
    CHECK(a.wavelength < 2.0 * t.wavelength);
    // contact: the plane penalty keeps the surface within R/10 of the plate
    const RodState& s = sim->state();
    double depth = 0;
    for (int i = 0; i < s.elements(); ++i) {
      const Vec3 mid = 0.5 * (s.x.col(i) + s.x.col(i + 1));
      depth = std::max(depth, m.rod.radius - mid.dot(m.env.plane.normal()));
    }
    CHECK(depth < 0.1 * m.rod.radius);
  }
  SUBCASE("alpha 80: coiling") {
    const ShapeAnalysis a = grow(coarse(80, 0.1, 350));
    INFO("theta [" << a.thetaMin / deg << ", " << a.thetaMax / deg << "]");
    CHECK(a.pattern == "coiling");
  }
}

TEST_CASE("intrinsic twist skews the root, and -tau mirrors it (Fig. 4A)") {
  Model m = coarse(30, 0.2, 250);
  m.tropism.rTau = 0.4;
  const double skewPlus = grow(m).skew;
  m.tropism.rTau = -0.4;
  const double skewMinus = grow(m).skew;
  INFO("skew +tau " << skewPlus / deg << " deg, -tau " << skewMinus / deg << " deg");
  CHECK(skewPlus > 10 * deg);
  CHECK(skewMinus == doctest::Approx(-skewPlus).epsilon(1e-3));
  // large omega T0: sin<theta> -> tan(alpha) (Eq. 15) within 25 %
  CHECK(std::sin(skewPlus) == doctest::Approx(std::tan(30 * deg)).epsilon(0.25));
}

TEST_CASE("free organ (Fig. 2C): the tip overshoots vertical and its oscillation decays") {
  Model m = coarse(40, 0.2, 300);
  m.env.plane.enabled = false;
  m.env.adhesion = false;
  Simulation sim(m);
  std::vector<double> th{sim.last().thetaTip};
  for (int i = 0; i < m.growth.steps; ++i) th.push_back(sim.growthStep().thetaTip);
  CHECK(th.front() == doctest::Approx(-40 * deg).epsilon(1e-6));
  // successive extrema (the largest |theta| between crossings of the vertical) shrink
  std::vector<double> ext;
  for (size_t i = 1; i < th.size(); ++i) {
    if (th[i] * th[i - 1] < 0) ext.push_back(th[i]);  // a crossing starts a new lobe
    else if (!ext.empty() && std::abs(th[i]) > std::abs(ext.back())) ext.back() = th[i];
  }
  if (!ext.empty()) ext.pop_back();  // the last lobe may still be growing
  INFO("extrema (deg): " << (ext.size() > 0 ? ext[0] / deg : 0) << ", " << (ext.size() > 1 ? ext[1] / deg : 0)
                         << ", " << (ext.size() > 2 ? ext[2] / deg : 0));
  REQUIRE(ext.size() >= 3);
  CHECK(ext[0] > 0);
  CHECK(ext[1] < 0);
  CHECK(std::abs(ext[1]) < std::abs(ext[0]));
  CHECK(std::abs(ext[2]) < std::abs(ext[1]));
  // first crossing of the vertical within a factor 2 of the turning time T0 (Eq. 7)
  size_t k = 0;
  while (k < th.size() && th[k] < 0) ++k;
  const double tCross = k * m.growth.stepTime;
  const double T0 = theoryFor(m).T0;
  CHECK(tCross > 0.5 * T0);
  CHECK(tCross < 2.0 * T0);
}

TEST_CASE("apical sensing: a free horizontal root also bends its tip down") {
  Model m = coarse(90, 0.2, 20);
  m.env.plane.enabled = false;
  m.env.adhesion = false;
  m.tropism.gamma = 0.0;
  m.tropism.sensing = Sensing::Apical;
  Simulation sim(m);
  for (int i = 0; i < 20; ++i) sim.growthStep();
  const RodState& s = sim.state();
  const Vec3 t = (s.x.col(s.elements()) - s.x.col(s.elements() - 1)).normalized();
  CHECK(t.z() < -0.1);
}

TEST_CASE("circumnutation (Eq. 19) swings the free tip sideways with the nutation period") {
  Model m = coarse(90, 0.0, 60);
  m.env.plane.enabled = false;
  m.env.adhesion = false;
  m.tropism.cnGain = 0.05;
  m.tropism.cnPeriod = 2.0 * 3600;  // 20 growth steps of 0.1 h
  Simulation sim(m);
  std::vector<double> lateral;
  for (int i = 0; i < 60; ++i) {
    sim.growthStep();
    const RodState& s = sim.state();
    lateral.push_back((s.x.col(s.elements()) - s.x.col(s.elements() - 1)).normalized().x());
  }
  int signChanges = 0;
  for (size_t i = 1; i < lateral.size(); ++i) signChanges += lateral[i] * lateral[i - 1] < 0;
  double amp = 0;
  for (double v : lateral) amp = std::max(amp, std::abs(v));
  INFO("sign changes " << signChanges << ", max lateral tangent component " << amp);
  CHECK(amp > 0.01);
  // 6 h of growth = 3 periods: about 6 sign changes of the lateral tip direction
  CHECK(signChanges >= 4);
  CHECK(signChanges <= 8);
}

TEST_CASE("proprioception alone drives kappa0 toward zero") {
  Model m = coarse(40, 0.0, 30);
  m.tropism.gamma = 1.0;
  m.env.plane.enabled = false;
  m.env.adhesion = false;
  Simulation sim(m);
  // give the zone an intrinsic curvature, then let it grow with proprioception only
  RodState& s = const_cast<RodState&>(sim.state());
  for (int j = 0; j + 1 < s.elements(); ++j) s.kappa0.col(j) = Vec3(200.0, -100.0, 0.0);
  double before = 0;
  for (int j = 0; j + 1 < s.elements(); ++j) before += s.kappa0.col(j).head<2>().norm();
  for (int i = 0; i < 30; ++i) sim.growthStep();
  const RodState& t = sim.state();
  const double S0 = growthZoneStart(m, t);
  double after = 0, maxZone = 0;
  for (int j = 0; j + 1 < t.elements(); ++j) {
    after += t.kappa0.col(j).head<2>().norm();
    if (t.S[j + 1] >= S0) maxZone = std::max(maxZone, t.kappa0.col(j).head<2>().norm());
  }
  INFO("sum |kappa0| before " << before << " after " << after << "; max in zone " << maxZone);
  // free organ, kappa = kappa0: d kappa0/dt = -eps0 gamma kappa0, so after 3 h a factor exp(-0.6)
  CHECK(maxZone == doctest::Approx(std::hypot(200.0, 100.0) * std::exp(-0.2 * 1.0 * 3.0)).epsilon(0.1));
}


TEST_CASE("set-point drift: phi_s(age) follows its law exactly at emergence, at the drift time and long after") {
  TropismParams tp;
  tp.setPoint = 70 * deg;
  tp.setPointFinal = 30 * deg;
  tp.setPointDriftTime = 48 * 3600.0;
  const double T = tp.setPointDriftTime;
  // linear: 70 at 0, the midpoint at T/2, 30 at T and held after; a negative age (before emergence) is 0
  tp.setPointDrift = SetPointDrift::Linear;
  CHECK(setPointAt(tp, 0.0) == tp.setPoint);
  CHECK(setPointAt(tp, -5.0) == tp.setPoint);
  ROOTSIM_CHECK_CLOSE(setPointAt(tp, 0.5 * T), 50 * deg, kRoundoff);
  ROOTSIM_CHECK_CLOSE(setPointAt(tp, 0.25 * T), 60 * deg, kRoundoff);
  CHECK(setPointAt(tp, T) == 30 * deg);
  CHECK(setPointAt(tp, 10 * T) == 30 * deg);
  // exponential: 70 at 0, 30 + 40/e at T, 30 + 40/e^3 at 3T, 30 exactly once the exponential underflows
  tp.setPointDrift = SetPointDrift::Exponential;
  CHECK(setPointAt(tp, 0.0) == tp.setPoint);
  ROOTSIM_CHECK_CLOSE(setPointAt(tp, T), (30 + 40 / std::numbers::e) * deg, kRoundoff);
  ROOTSIM_CHECK_CLOSE(setPointAt(tp, 3 * T), (30 + 40 * std::exp(-3.0)) * deg, kRoundoff);
  CHECK(setPointAt(tp, 1000 * T) == 30 * deg);
  // drifting up works the same way
  tp.setPointFinal = 90 * deg;
  ROOTSIM_CHECK_CLOSE(setPointAt(tp, T), (90 - 20 / std::numbers::e) * deg, kRoundoff);
  // no drift (no final angle, or final = initial): the constant bit for bit at every age, whatever the
  // law and time
  for (SetPointDrift law : {SetPointDrift::Linear, SetPointDrift::Exponential}) {
    tp.setPointDrift = law;
    tp.setPointFinal = tp.setPoint;
    for (double age : {0.0, 0.3 * T, T, 50 * T}) CHECK(setPointAt(tp, age) == tp.setPoint);
    tp.setPointFinal.reset();
    for (double age : {0.0, 0.3 * T, T, 50 * T}) CHECK(setPointAt(tp, age) == tp.setPoint);
  }
}

TEST_CASE("set-point drift: without drift the law and its time change no bit of a growing organ") {
  // a free horizontal organ (plane off) turning to a set point of 40 deg: no final angle, and a final angle
  // equal to it under another law and time, grow the same bits; a final angle of 0 grows others
  Model m = coarse(90, 0.2, 20);
  m.env.plane.enabled = false;
  m.tropism.setPoint = 40 * deg;
  completeModel(m);
  Model same = m, drifting = m;
  same.tropism.setPointFinal = 40 * deg;
  same.tropism.setPointDrift = SetPointDrift::Linear;
  same.tropism.setPointDriftTime = 1.0;
  drifting.tropism.setPointFinal = 0.0;
  Simulation a(m), b(same), c(drifting);
  for (int i = 0; i < m.growth.steps; ++i) {
    a.growthStep();
    b.growthStep();
    c.growthStep();
  }
  CHECK((a.state().x - b.state().x).cwiseAbs().maxCoeff() == 0.0);
  CHECK((a.state().kappa0 - b.state().kappa0).cwiseAbs().maxCoeff() == 0.0);
  CHECK((a.state().kappa0 - c.state().kappa0).cwiseAbs().maxCoeff() > 0.0);
}
