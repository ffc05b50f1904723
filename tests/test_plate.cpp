// a plate of roots (src/sim/plate.cpp; docs/plate.md): roots apart are the single root's run, roots
// that meet push each other and never pass through, the contact between roots is action and reaction
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "rootsim/analysis.hpp"
#include "rootsim/contact.hpp"
#include "rootsim/growth.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/tolerance.hpp"
#include "rootsim/units.hpp"
#include "physics_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
using rootsim::test::relError;
using rootsim::test::report;

namespace {

// the paper's waving root (Fig. 2B: alpha = 40 deg, beta = 0.2, gamma = 0.1) at its physical parameters
Model waving() {
  Model m = defaultModel();
  m.env.plane.alpha = 40 * units::deg;
  m.tropism.beta = 0.2;
  m.tropism.gamma = 0.1;
  m.initial.elementLength = 0.05 * units::mm;
  completeModel(m);
  return m;
}

// the waving root on a vertical plate (alpha = 0): a primary grows straight down, a lateral turns to its
// set-point angle from gravity
Model verticalWaving() {
  Model m = waving();
  m.env.plane.alpha = 0.0;
  completeModel(m);
  return m;
}

// a plate whose primaries grow laterals: sites from first at spacing, each opening once the tip is
// apical beyond it, at insertion from the parent's tangent [mm, deg]
PlateParams lateralPlate(double firstMm, double spacingMm, double apicalMm, double insertionDeg) {
  PlateParams pp;
  LateralParams& lp = pp.laterals;
  lp.enabled = true;
  lp.first = firstMm * units::mm;
  lp.spacing = spacingMm * units::mm;
  lp.apicalUnbranched = apicalMm * units::mm;
  lp.insertion = insertionDeg * units::deg;
  return pp;
}

Seedling sow(const std::string& name, double lateralMm, double downhillMm, const Model& m, double angleDeg = 0) {
  Seedling s;
  s.name = name;
  s.position = Eigen::Vector2d(lateralMm, downhillMm) * units::mm;
  s.model = m;
  s.model.initial.angle = angleDeg * units::deg;
  return s;
}

}  // namespace

TEST_CASE("plate: contact between roots is the self-contact law with the sum of the radii") {
  // two crossing segments, one above the other along the normal: the force is k (Ra + Rb - d) along it
  const double ra = 0.1e-3, rb = 0.06e-3, k = 1000, d = 0.12e-3;
  const Vec3 up(0, 0, 1);
  RootPairForce pf;
  REQUIRE(rootPairForce(ra, rb, k, up, Vec3(-1e-3, 0, d), Vec3(1e-3, 0, d), Vec3(0, -1e-3, 0), Vec3(0, 1e-3, 0), pf));
  CHECK(pf.F.x() == doctest::Approx(0).epsilon(1e-12));
  CHECK(pf.F.z() == doctest::Approx(k * (ra + rb - d)).epsilon(1e-12));
  ROOTSIM_CHECK_CLOSE(pf.sa, 0.5, kRoundoff);
  ROOTSIM_CHECK_CLOSE(pf.sb, 0.5, kRoundoff);
  // just out of reach: no force
  CHECK_FALSE(rootPairForce(ra, rb, k, up, Vec3(-1e-3, 0, ra + rb + 1e-12), Vec3(1e-3, 0, ra + rb + 1e-12),
                            Vec3(0, -1e-3, 0), Vec3(0, 1e-3, 0), pf));
}

TEST_CASE("plate: N identical seedlings far apart grow N copies of the single root's run") {
  const Model m = waving();
  const int steps = 700;  // 35 h: the root waves (its first snap comes at ~10 h)
  Simulation single(m);
  for (int k = 0; k < steps; ++k) single.growthStep();
  const ShapeAnalysis want = analyseShape(m, single.state());
  REQUIRE(want.peaks >= 3);
  PlateSimulation plate(PlateParams{}, {sow("a", 10, 5, m), sow("b", 40, 5, m), sow("c", 70, 20, m)});
  for (int k = 0; k < steps; ++k) plate.growthStep();
  CHECK(plate.last().sweeps == 2);          // one sweep grew them, one found nobody within reach
  CHECK(std::isnan(plate.last().minGap));  // never within reach
  for (int r = 0; r < plate.size(); ++r) {
    const RodState& s = plate.root(r).state();
    REQUIRE(s.nodes() == single.state().nodes());
    // in plate coordinates: the single root's nodes moved to the seedling's place
    const Eigen::Matrix3Xd onPlate = s.x.colwise() + plate.offset(r);
    const Eigen::Matrix3Xd expected = single.state().x.colwise() + plate.offset(r);
    const double diffMm = (onPlate - expected).cwiseAbs().maxCoeff() / units::mm;
    INFO("root " << plate.seedling(r).name << ": largest difference " << diffMm << " mm");
    CHECK(diffMm <= 1e-12);
    const ShapeAnalysis got = analyseShape(plate.seedling(r).model, s);
    CHECK(got.pattern == want.pattern);
    CHECK(got.wavelength == want.wavelength);
    CHECK(got.amplitude == want.amplitude);
  }
}

TEST_CASE("plate: a root alone as a plate of one steps bit for bit as its own Simulation, tropism changed too") {
  // what `rootsim run` of a scene of one root steps (plateOfOne): the same bits in every record and node
  const Model m = waving();
  const int steps = 400;  // 20 h: past the first snap
  Simulation single(m);
  const PlateSpec one = plateOfOne(m);
  REQUIRE(one.seedlings.size() == 1);
  CHECK(one.seedlings[0].name.empty());
  PlateSimulation plate(one.params, one.seedlings);
  REQUIRE(plate.size() == 1);
  CHECK(plate.offset(0).norm() == 0.0);
  auto same = [](const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
    return a.cols() == b.cols() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
  };
  auto sameRecord = [](const StepRecord& a, const StepRecord& b) {
    return a.step == b.step && a.elements == b.elements && a.substeps == b.substeps && a.iterations == b.iterations &&
           a.splits == b.splits && a.unstable == b.unstable &&
           std::memcmp(&a.thetaTip, &b.thetaTip, sizeof(double)) == 0 &&
           std::memcmp(&a.residualForce, &b.residualForce, sizeof(double)) == 0 &&
           std::memcmp(&a.lowestEigenvalue, &b.lowestEigenvalue, sizeof(double)) == 0 && a.tip == b.tip;
  };
  CHECK(same(single.state().x, plate.root(0).state().x));
  int differ = 0;
  for (int k = 0; k < steps; ++k) {
    single.growthStep();
    const PlateStepRecord& pr = plate.growthStep();
    CHECK(pr.sweeps == 1);
    CHECK(plate.emerged().empty());
    const RodState& s = plate.root(0).state();
    if (!same(single.state().x, s.x) || !same(single.state().kappa0, s.kappa0) || !sameRecord(single.last(), plate.root(0).last()))
      ++differ;
  }
  CHECK(differ == 0);
  CHECK(single.totalIterations() == plate.root(0).totalIterations());
  CHECK(analyseShape(m, plate.root(0).state()).peaks >= 1);
  // gravity's effect changed half-way (Python's Simulation.set): the root's and its seedling's, the same bits
  TropismParams t = m.tropism;
  t.beta *= 2.0;
  single.setTropism(t);
  plate.setTropism(0, t);
  CHECK(plate.seedling(0).model.tropism.beta == t.beta);
  for (int k = 0; k < 40; ++k) {
    single.growthStep();
    plate.growthStep();
    if (!same(single.state().x, plate.root(0).state().x) || !sameRecord(single.last(), plate.root(0).last())) ++differ;
  }
  CHECK(differ == 0);
  CHECK(std::memcmp(&single.last().thetaTip, &plate.root(0).last().thetaTip, sizeof(double)) == 0);
}

TEST_CASE("plate: two roots grown into each other push each other and never pass through") {
  // one root grows downhill; the other, sown 3 mm to its right pointing across the plate with a weak
  // gravitropism (beta = 0.02), grows into it (the shipped scene plate_collision.toml)
  const Model m = waving();
  Model across = m;
  across.tropism.beta = 0.02;
  PlateSimulation plate(PlateParams{}, {sow("down", 20, 5, m), sow("across", 23, 7, across, -90)});
  double closest = 1e300;
  int touching = 0;
  for (int k = 0; k < 330; ++k) {
    const PlateStepRecord& r = plate.growthStep();
    if (!std::isnan(r.minGap)) closest = std::min(closest, r.minGap);
    touching = std::max(touching, r.touchingPairs);
  }
  INFO("closest approach of the centrelines: " << closest << " (Ra + Rb); most element pairs touching: " << touching);
  REQUIRE(touching > 0);  // they did meet
  // a penalty contact: they overlap by the contact depth F/k only (measured: 1.5 % of Ra + Rb)
  CHECK(closest >= 0.95);
  // action and reaction: the forces between the two roots have no net force and no net moment
  const RootPairForces f = plate.pairForces(0, 1);
  REQUIRE(f.contacts > 0);
  Vec3 net = Vec3::Zero(), moment = Vec3::Zero();
  double largest = 0;
  auto add = [&](const Eigen::Matrix3Xd& force, int r) {
    const Eigen::Matrix3Xd x = plate.root(r).state().x.colwise() + plate.offset(r);
    for (int i = 0; i < force.cols(); ++i) {
      net += force.col(i);
      moment += Vec3(x.col(i)).cross(Vec3(force.col(i)));
      largest = std::max(largest, force.col(i).norm());
    }
  };
  add(f.onA, 0);
  add(f.onB, 1);
  INFO("net force " << net.transpose() << " N, net moment " << moment.transpose() << " N m, largest node force " << largest);
  CHECK(net.norm() <= 1e-12 * largest);
  CHECK(moment.norm() <= 1e-12 * largest * 0.1);  // positions ~ 0.03 m from the plate's origin
}

TEST_CASE("plate: where the coupled Newton crawls, a short joint relaxation hands the roots back to it") {
  // the collision scene's roots pressed together: on the steps where the coupled Newton stalls, the roots
  // relax together explicitly for PlateSimulation::kJointBudget sub-steps and the coupled Newton takes
  // over again; every step still ends with each root within its own equilibrium tolerance
  const Model m = waving();
  Model across = m;
  across.tropism.beta = 0.02;
  PlateSimulation plate(PlateParams{}, {sow("down", 20, 5, m), sow("across", 23, 7, across, -90)});
  int met = -1, joint = 0, handedBack = 0;
  double worst = 0;  // largest residual force over its tolerance, of every root after a joint relaxation
  for (int k = 0; k < 300; ++k) {
    const PlateStepRecord& r = plate.growthStep();
    if (met < 0 && r.touchingPairs > 0) met = k;
    if (met < 0) continue;
    const long substeps = plate.root(0).last().substeps;
    if (substeps == 0) continue;
    ++joint;
    handedBack += substeps <= PlateSimulation::kJointBudget;
    for (int q = 0; q < plate.size(); ++q) {
      const Model& mq = q == 0 ? m : across;
      const double tol = equilibriumTolerance(mq.rod, mq.env, mq.solver, plate.root(q).state()).force;
      worst = std::max(worst, plate.root(q).last().residualForce / tol);
    }
  }
  INFO("the roots met at step " << met << "; " << joint << " steps with a joint relaxation, " << handedBack
                                 << " of them handed back after " << PlateSimulation::kJointBudget
                                 << " sub-steps; largest residual over tolerance " << worst);
  REQUIRE(met > 0);
  REQUIRE(joint > 0);
  CHECK(handedBack > 0);
  CHECK(worst <= 1.0);
}

TEST_CASE("plate: the coupled Jacobian of two roots in contact is the central difference of their residual") {
  // the collision scene's roots once they press on each other: the coupled system's Jacobian (each root's
  // band and the contact blocks between them) against central differences of the joint residual, column
  // by column over every unknown of both roots
  const Model m = waving();
  Model across = m;
  across.tropism.beta = 0.02;
  PlateSimulation plate(PlateParams{}, {sow("down", 20, 5, m), sow("across", 23, 7, across, -90)});
  int touching = 0, k = 0;
  for (; k < 330 && touching < 2; ++k) touching = plate.growthStep().touchingPairs;
  INFO("growth step " << k << ": " << touching << " element pairs touching");
  REQUIRE(touching >= 2);
  const Eigen::MatrixXd K = plate.coupledJacobian();
  REQUIRE(plate.coupledRoots() == std::vector<int>{0, 1});
  const int n = static_cast<int>(K.rows());
  const Eigen::VectorXd r0 = plate.coupledResidual(-1, 0.0);
  REQUIRE(r0.size() == n);
  const double h = 1e-6 * m.initial.elementLength;
  Eigen::MatrixXd D(n, n);
  for (int j = 0; j < n; ++j) D.col(j) = -(plate.coupledResidual(j, h) - plate.coupledResidual(j, -h)) / (2.0 * h);
  // the state is restored after each nudge: the residual is the same
  CHECK((plate.coupledResidual(-1, 0.0) - r0).cwiseAbs().maxCoeff() == 0.0);
  const double scale = K.cwiseAbs().maxCoeff();
  const double err = relError((D - K).cwiseAbs().maxCoeff(), 0.0, scale);
  report("coupled Jacobian vs central differences", (D - K).cwiseAbs().maxCoeff(), 0.0, err);
  CHECK(err <= 1e-6);
  // the blocks that couple the two roots: present in both (each root's contact forces depend on the
  // other's nodes) and equal to the differences there too, against their own scale
  const int split = plate.coupledFirst()[1];  // root 1's first unknown
  REQUIRE(split > 0);
  REQUIRE(split < n);
  const Eigen::MatrixXd cross01 = K.topRightCorner(split, n - split), cross10 = K.bottomLeftCorner(n - split, split);
  const double crossScale = std::max(cross01.cwiseAbs().maxCoeff(), cross10.cwiseAbs().maxCoeff());
  INFO("largest coupling entry " << crossScale << " N/m, largest entry " << scale);
  REQUIRE(cross01.cwiseAbs().maxCoeff() > 0.0);
  REQUIRE(cross10.cwiseAbs().maxCoeff() > 0.0);
  const double crossErr =
      std::max((D.topRightCorner(split, n - split) - cross01).cwiseAbs().maxCoeff(),
               (D.bottomLeftCorner(n - split, split) - cross10).cwiseAbs().maxCoeff()) / crossScale;
  report("coupling blocks vs central differences", crossErr, 0.0, crossErr);
  CHECK(crossErr <= 1e-5);
}

TEST_CASE("plate: lateral roots emerge at the asked spacing and, on a vertical plate, settle at their set-point angle") {
  // a vertical plate (alpha = 0): the primary grows straight down; its laterals start at 85 degrees from
  // it, alternating sides, and turn to their gravitropic set-point angle of 50 degrees from gravity
  const Model m = verticalWaving();
  PlateParams pp = lateralPlate(3, 2, 4, 85);
  LateralParams& lp = pp.laterals;
  lp.setPoint = 50 * units::deg;
  PlateSimulation plate(pp, {sow("p", 20, 3, m)});
  for (int k = 0; k < 2600; ++k) plate.growthStep();
  REQUIRE(plate.size() >= 4);
  const double h = m.initial.elementLength;
  for (int r = 1; r < plate.size(); ++r) {
    const Seedling& sd = plate.seedling(r);
    CHECK(sd.parent == 0);
    CHECK(sd.order == 1);
    // the k-th site at first + k spacing along the parent, at its nearest node: within half an element
    // (elements are split beyond growth.split_factor h)
    CHECK(std::abs(sd.siteS - (lp.first + (r - 1) * lp.spacing)) <= 0.5 * m.growth.splitFactor * h);
    // alternating sides: +85, -85, +85 ... degrees from the parent (straight down here)
    CHECK(sd.model.initial.angle / units::deg == doctest::Approx((r % 2 == 1 ? 1 : -1) * 85.0).epsilon(1e-3));
    // the lateral's base sits where the parent's node at the site is (the parent grew straight down)
    const double depth = (plate.offset(r) - plate.offset(0)).dot(Vec3(0, 0, -1));
    CHECK(std::abs(depth - sd.siteS) <= 1e-3 * sd.siteS);
  }
  // the laterals long enough to have turned (grown 5 mm) point at the set-point angle, on their own side
  int judged = 0;
  for (int r = 1; r < plate.size(); ++r) {
    const RodState& s = plate.root(r).state();
    if (s.restLength() < 5e-3) continue;
    ++judged;
    const double theta = plate.root(r).last().thetaTip / units::deg;
    INFO(plate.seedling(r).name << ": tip angle " << theta << " deg after " << s.restLength() / units::mm << " mm");
    CHECK(std::abs(std::abs(theta) - 50.0) <= 5.0);
    CHECK(theta * plate.seedling(r).model.initial.angle > 0.0);
  }
  CHECK(judged >= 2);
}

TEST_CASE("plate: on a vertical plate a lateral's tip follows its set-point angle drifting with the lateral's age") {
  // one lateral, emerging 22.5 h into the run (a 24 h delay), inserted at 70 degrees from its vertical
  // parent, its set-point angle drifting from 70 to 30 degrees over 48 h: its tip angle is the law's at
  // its age (not at the run's time: that differs by 2-3 degrees in the last 40 h of the exponential)
  const Model m = verticalWaving();
  PlateParams pp = lateralPlate(0.3, 1000, 0.5, 70);
  LateralParams& lp = pp.laterals;
  lp.delay = 24 * units::hour;
  lp.setPoint = 70 * units::deg;
  lp.setPointFinal = 30 * units::deg;
  lp.setPointDriftTime = 48 * units::hour;
  for (const SetPointDrift law : {SetPointDrift::Linear, SetPointDrift::Exponential}) {
    lp.setPointDrift = law;
    const bool linear = law == SetPointDrift::Linear;
    PlateSimulation plate(pp, {sow("p", 20, 3, m)});
    double during = 0.0, after = 0.0, lastAge = 0.0;  // largest |tip angle - law| [deg]
    for (int k = 0; k < 2800; ++k) {
      plate.growthStep();
      if (plate.size() < 2) continue;
      REQUIRE(plate.size() == 2);
      const double age = plate.root(1).state().time - plate.seedling(1).emergedH * units::hour;
      const double theta = plate.root(1).last().thetaTip;
      const double off = std::abs(theta - setPointAt(plate.seedling(1).model.tropism, age)) / units::deg;
      // linear: the tip lags the ramp by up to 4.4 degrees, then rings about 30 once it is reached;
      // exponential: from one time constant on it is on the law within 0.6 degrees
      if (age <= lp.setPointDriftTime) during = std::max(during, linear ? off : 0.0);
      if (age >= (linear ? 1.5 : 1.0) * lp.setPointDriftTime) after = std::max(after, off);
      lastAge = age;
    }
    INFO((linear ? "linear" : "exponential") << ": off the law by " << during << " deg during the drift, " << after
                                             << " deg after it; age at the end " << lastAge / units::hour << " h");
    REQUIRE(plate.seedling(1).emergedH == doctest::Approx(22.5).epsilon(0.01));
    CHECK(lastAge > 2.0 * lp.setPointDriftTime);
    CHECK(during <= 5.0);
    CHECK(after <= (linear ? 2.0 : 1.0));
  }
}

TEST_CASE("plate: a plate restored from its carry mid-drift continues bit for bit") {
  // the age a drifting set point reads is the run's time less the emergence time, both carried: a plate
  // rebuilt 20 h into its lateral's drift grows the same bits as the one that ran through
  const Model m = verticalWaving();
  PlateParams pp = lateralPlate(0.3, 1000, 0.5, 70);
  pp.laterals.delay = 2 * units::hour;
  pp.laterals.setPoint = 70 * units::deg;
  pp.laterals.setPointFinal = 30 * units::deg;
  pp.laterals.setPointDriftTime = 48 * units::hour;
  const std::vector<Seedling> seedlings{sow("p", 20, 3, m)};
  PlateSimulation plate(pp, seedlings);
  for (int k = 0; k < 440; ++k) plate.growthStep();
  REQUIRE(plate.size() == 2);
  CHECK(plate.seedling(1).emergedH > 0.0);  // its age is not the run's time
  PlateSimulation resumed(pp, seedlings, plate.carry());
  for (int k = 0; k < 200; ++k) {
    plate.growthStep();
    resumed.growthStep();
  }
  for (int r = 0; r < 2; ++r) {
    CHECK((plate.root(r).state().x - resumed.root(r).state().x).cwiseAbs().maxCoeff() == 0.0);
    CHECK((plate.root(r).state().kappa0 - resumed.root(r).state().kappa0).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("plate: laterals inserted from downhill start at the insertion angle whatever their waving parent's tangent") {
  // the waving primary of plate_wildtype (alpha = 40): its tangent at the sites swings about downhill, so
  // laterals inserted at 65 degrees from it start anywhere in 65 +- 50 degrees; from downhill, at +-65
  const Model m = waving();
  const PlateParams pp = lateralPlate(3, 0.7, 2, 65);
  PlateParams fromDownhill = pp;
  fromDownhill.laterals.fromParent = false;
  PlateSimulation parent(pp, {sow("p", 20, 3, m)});
  PlateSimulation downhill(fromDownhill, {sow("p", 20, 3, m)});
  for (int k = 0; k < 1500; ++k) {
    parent.growthStep();
    downhill.growthStep();
  }
  REQUIRE(parent.size() >= 5);
  REQUIRE(downhill.size() == parent.size());
  double widest = 0.0;
  for (int r = 1; r < parent.size(); ++r) {
    const double side = r % 2 == 1 ? 1.0 : -1.0;
    INFO(parent.seedling(r).name);
    // the same sites (the primaries are the same until then), the same sides
    CHECK(downhill.seedling(r).siteS == parent.seedling(r).siteS);
    CHECK(downhill.seedling(r).model.initial.angle == doctest::Approx(side * 65 * units::deg).epsilon(1e-12));
    widest = std::max(widest, std::abs(std::abs(parent.seedling(r).model.initial.angle) - 65 * units::deg));
  }
  // from the parent's tangent, the wave shows: some lateral starts at least 10 degrees off 65
  CHECK(widest > 10 * units::deg);
}

TEST_CASE("plate: a plate restored from its carry continues bit for bit with roots in contact and laterals") {
  // the collision scene's roots with laterals drawn to random sides: at step 250 they press on each other
  // and six laterals have emerged; a plate rebuilt from carry() there and the original grow 40 more steps
  // (through the emergence of more laterals) to the same bits
  const Model m = waving();
  Model across = m;
  across.tropism.beta = 0.02;
  PlateParams pp;
  LateralParams& lp = pp.laterals;
  lp.enabled = true;
  lp.first = 1e-3;
  lp.spacing = 0.4e-3;
  lp.apicalUnbranched = 0.6e-3;
  lp.alternate = false;
  lp.seed = 3;
  const std::vector<Seedling> seedlings{sow("down", 20, 5, m), sow("across", 23, 7, across, -90)};
  PlateSimulation plate(pp, seedlings);
  int touching = 0;
  for (int k = 0; k < 250; ++k) touching = std::max(touching, plate.growthStep().touchingPairs);
  const int before = plate.size();
  INFO(before << " roots at step 250, " << touching << " element pairs touching at most");
  REQUIRE(touching > 0);
  REQUIRE(before > 2);
  const PlateCarry carry = plate.carry();
  PlateSimulation resumed(pp, seedlings, carry);
  REQUIRE(resumed.size() == before);
  for (int k = 0; k < 40; ++k) {
    const PlateStepRecord& a = plate.growthStep();
    const PlateStepRecord& b = resumed.growthStep();
    REQUIRE(a.step == b.step);
    CHECK(a.touchingPairs == b.touchingPairs);
    CHECK(a.sweeps == b.sweeps);
    CHECK(std::memcmp(&a.minGap, &b.minGap, sizeof(double)) == 0);
  }
  CHECK(plate.size() > before);  // laterals emerged after the carry was taken
  REQUIRE(resumed.size() == plate.size());
  for (int r = 0; r < plate.size(); ++r) {
    const RodState& a = plate.root(r).state();
    const RodState& b = resumed.root(r).state();
    INFO(plate.seedling(r).name);
    CHECK(resumed.seedling(r).name == plate.seedling(r).name);
    REQUIRE(a.nodes() == b.nodes());
    CHECK((a.x - b.x).cwiseAbs().maxCoeff() == 0.0);
    CHECK((a.S - b.S).cwiseAbs().maxCoeff() == 0.0);
    for (int i = 0; i < a.elements(); ++i) CHECK((a.Q[static_cast<size_t>(i)] - b.Q[static_cast<size_t>(i)]).cwiseAbs().maxCoeff() == 0.0);
    CHECK(plate.root(r).totalIterations() == resumed.root(r).totalIterations());
    CHECK(std::memcmp(&plate.root(r).last().lowestEigenvalue, &resumed.root(r).last().lowestEigenvalue, sizeof(double)) == 0);
  }
}

TEST_CASE("plate: a growth step of two roots pressed together allocates nothing once their contact has set in") {
  // the collision scene's roots: after warm-up (the roots have met and their contact lists, the coupled
  // system and its sparse pattern have reached their size) no growth step allocates, whether the coupled
  // Newton converges, its pattern changes with the contacts and the windows, or it stalls and the roots
  // relax together explicitly. Steps that split elements are not counted (a split rebuilds the roots'
  // states, as a single root's step does: test_simulation.cpp)
  const Model m = waving();
  Model across = m;
  across.tropism.beta = 0.02;
  PlateSimulation plate(PlateParams{}, {sow("down", 20, 5, m), sow("across", 23, 7, across, -90)});
  constexpr int kSetIn = 20;  // steps after the roots first touch
  int met = -1, checked = 0, touchingChecked = 0, jointChecked = 0;
  for (int k = 0; k < 600; ++k) {
    const long before = rootsim::test::gAllocs.load();
    const PlateStepRecord& r = plate.growthStep();
    const long allocs = rootsim::test::gAllocs.load() - before;
    if (met < 0 && r.touchingPairs > 0) met = k;
    int splits = 0;
    long substeps = 0;
    for (int q = 0; q < plate.size(); ++q) {
      splits += plate.root(q).last().splits;
      substeps += plate.root(q).last().substeps;
    }
    if (met < 0 || k < met + kSetIn || splits > 0) continue;
    INFO("growth step " << r.step << ": " << allocs << " allocations, " << r.touchingPairs << " element pairs touching, "
                        << r.sweeps << " sweeps");
    CHECK(allocs == 0);
    ++checked;
    touchingChecked += r.touchingPairs > 0;
    jointChecked += substeps > 0;  // the coupled Newton stalled: the roots relaxed together explicitly
  }
  INFO("the roots met at step " << met << "; " << checked << " steps counted, " << touchingChecked
                                 << " with roots touching, " << jointChecked << " with a joint relaxation");
  REQUIRE(met > 0);
  CHECK(touchingChecked > 200);
  CHECK(jointChecked > 0);
}

TEST_CASE("plate: each lateral site's delay is drawn from its own stream - normal around delay_h, repeatable") {
  LateralParams lp;
  lp.delay = 10 * units::hour;
  lp.seed = 4;
  // no spread: the delay itself at every site
  CHECK(siteDelay(lp, 0, 0) == lp.delay);
  CHECK(siteDelay(lp, 3, 17) == lp.delay);
  lp.delaySpread = 2 * units::hour;
  // the same root and site draw the same delay; another site, root or seed another
  CHECK(siteDelay(lp, 1, 5) == siteDelay(lp, 1, 5));
  CHECK(siteDelay(lp, 1, 5) != siteDelay(lp, 1, 6));
  CHECK(siteDelay(lp, 1, 5) != siteDelay(lp, 2, 5));
  LateralParams other = lp;
  other.seed = 5;
  CHECK(siteDelay(lp, 1, 5) != siteDelay(other, 1, 5));
  // 4000 sites: mean and standard deviation of a normal of sd 2 h around 10 h (its truncation at 0, 5 sd
  // below, is beyond these draws); tolerances 4 standard errors: sd/sqrt(n) for the mean,
  // sd/sqrt(2n) for the standard deviation
  const int n = 4000;
  double sum = 0, sum2 = 0;
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < n / 4; ++k) {
      const double d = siteDelay(lp, r, k) / units::hour;
      CHECK(d >= 0.0);
      sum += d;
      sum2 += d * d;
    }
  const double mean = sum / n, sd = std::sqrt((sum2 - n * mean * mean) / (n - 1));
  INFO("mean " << mean << " h, sd " << sd << " h");
  CHECK(std::abs(mean - 10.0) < 4 * 2.0 / std::sqrt(n));
  CHECK(std::abs(sd - 2.0) < 4 * 2.0 / std::sqrt(2.0 * n));
  // near delay 0 a negative draw is drawn again: every delay >= 0
  lp.delay = 0.0;
  for (int k = 0; k < 200; ++k) CHECK(siteDelay(lp, 0, k) >= 0.0);
}

TEST_CASE("plate: with a delay spread identical seedlings' laterals emerge at different times, without one at the same") {
  const Model m = waving();
  auto emergence = [&](double spreadH, std::vector<double>& a, std::vector<double>& b) {
    PlateParams pp;
    LateralParams& lp = pp.laterals;
    lp.enabled = true;
    lp.first = 1e-3;
    lp.spacing = 0.4e-3;
    lp.apicalUnbranched = 0.6e-3;
    lp.delay = 1 * units::hour;
    lp.delaySpread = spreadH * units::hour;
    PlateSimulation plate(pp, {sow("a", 10, 5, m), sow("b", 40, 5, m)});
    for (int k = 0; k < 200; ++k) plate.growthStep();
    for (int r = 2; r < plate.size(); ++r)
      (plate.seedling(r).parent == 0 ? a : b).push_back(plate.seedling(r).emergedH);
  };
  std::vector<double> a, b;
  emergence(0.0, a, b);
  REQUIRE(a.size() >= 3);
  CHECK(a == b);  // the same sites at the same times
  std::vector<double> c, d;
  emergence(0.5, c, d);
  REQUIRE(c.size() >= 2);
  REQUIRE(d.size() >= 2);
  INFO("a's laterals emerged at " << c[0] << ", " << c[1] << " h; b's at " << d[0] << ", " << d[1] << " h");
  CHECK(c[0] != d[0]);
  CHECK(c[1] != d[1]);
}
