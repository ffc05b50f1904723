// contact beyond the paper (src/sim/contact.cpp, docs/model.md, Contact and friction): self-contact, Coulomb
// friction with stick-slip, obstacles, against closed forms and invariants
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "physics_support.hpp"
#include "rootsim/contact.hpp"
#include "rootsim/contact_newton.hpp"
#include "rootsim/growth.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/model.hpp"
#include "rootsim/relax.hpp"
#include "rootsim/relax_newton.hpp"
#include "rootsim/rotation.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/stability.hpp"
#include "rootsim/tolerance.hpp"
#include "rootsim/units.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;

namespace {

// a rod through the given nodes, straight elements, directors d3 along each element and d1 as close to
// `up` x d3 as possible, material coordinates from the lengths (stress-free in stretch)
RodState rodThrough(const std::vector<Vec3>& pts, const Vec3& up) {
  RodState s;
  const int n = static_cast<int>(pts.size()) - 1;
  s.resize(n);
  s.S[0] = 0;
  for (int i = 0; i <= n; ++i) s.x.col(i) = pts[static_cast<size_t>(i)];
  for (int i = 0; i < n; ++i) {
    const Vec3 d3 = (pts[static_cast<size_t>(i + 1)] - pts[static_cast<size_t>(i)]).normalized();
    Vec3 d1 = up.cross(d3);
    if (d1.norm() < 1e-9) d1 = d3.unitOrthogonal();
    d1.normalize();
    Mat3 Q;
    Q.row(0) = d1.transpose();
    Q.row(1) = d3.cross(d1).transpose();
    Q.row(2) = d3.transpose();
    s.Q[static_cast<size_t>(i)] = Q;
    s.l0[i] = (pts[static_cast<size_t>(i + 1)] - pts[static_cast<size_t>(i)]).norm();
    s.S[i + 1] = s.S[i] + s.l0[i];
  }
  s.clampFrame = s.Q[0];
  s.v.setZero();
  s.w.setZero();
  s.kappa0.setZero();
  s.anchor = s.x;
  return s;
}

// a straight rod of n elements from `from` along unit `dir`, lying with d2 = `up`
RodState straightRod(const Vec3& from, const Vec3& dir, const Vec3& up, int n, double L) {
  std::vector<Vec3> pts;
  for (int i = 0; i <= n; ++i) pts.push_back(from + (L * i / n) * dir);
  return rodThrough(pts, up);
}

// smallest centreline distance between elements that self-contact considers (not neighbours), / R,
// by brute force
double minDistantGap(const RodParams& p, const RodState& s) {
  double best = 1e300;
  for (int i = 0; i < s.elements(); ++i)
    for (int j = i + 2; j < s.elements(); ++j) {
      if (s.S[j] - s.S[i + 1] < kSelfExclusionRadii * p.radius) continue;
      double a = 0, b = 0;
      closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), a, b);
      const Vec3 d = (s.x.col(i) + a * (s.x.col(i + 1) - s.x.col(i))) - (s.x.col(j) + b * (s.x.col(j + 1) - s.x.col(j)));
      best = std::min(best, d.norm() / p.radius);
    }
  return best;
}

// two straight rods crossing at right angles, rod A along x at height 0, rod B along y at height h
// above it, crossing at the middle of an element of each; joined into one chain by a connector that
// climbs far above (so that only the crossing is in contact). Returns the state and the node ranges.
struct Crossing {
  RodState s;
  int bFirst = 0;  // first node of rod B
};
Crossing crossing(double R, double h) {
  const int m = 20;
  const double l = 0.5 * R, L = m * l;
  std::vector<Vec3> pts;
  for (int i = 0; i <= m; ++i) pts.push_back(Vec3((i - 10) * l, 0, 0));  // A: x = 0.5 l is mid-element
  pts.push_back(Vec3(10 * l, 0, 10 * L));
  pts.push_back(Vec3(0.5 * l, -9.5 * l, 10 * L));
  Crossing c;
  c.bFirst = static_cast<int>(pts.size());
  for (int j = 0; j <= m; ++j) pts.push_back(Vec3(0.5 * l, (j - 9.5) * l, h));  // B: y = 0 mid-element
  c.s = rodThrough(pts, Vec3::UnitZ());
  return c;
}

// the total contact force on rod B by brute force over all A-B element pairs (the closed form of the
// pair law: k (2R - d) along the closest-point line, for every pair closer than 2R)
Vec3 bruteForceOnB(const RodParams& p, double k, const Crossing& c) {
  Vec3 F = Vec3::Zero();
  const RodState& s = c.s;
  for (int i = 0; i < c.bFirst - 3; ++i)
    for (int j = c.bFirst; j < s.elements(); ++j) {
      double a = 0, b = 0;
      closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), a, b);
      const Vec3 d = (s.x.col(j) + b * (s.x.col(j + 1) - s.x.col(j))) - (s.x.col(i) + a * (s.x.col(i + 1) - s.x.col(i)));
      if (d.norm() < 2 * p.radius) F += k * (2 * p.radius - d.norm()) * d.normalized();
    }
  return F;
}

}  // namespace

TEST_CASE("self-contact: two rods pressed across each other stop at 2R apart, forces and moments sum to zero") {
  RodParams p;
  Environment env;
  env.plane.enabled = false;
  const double R = p.radius, k = env.selfContact.k;
  ContactWorkspace cw;
  // forces of a crossing 0.3 R deep: what the brute-force pair law gives, no net force, no net moment
  {
    Crossing c = crossing(R, 1.7 * R);
    Eigen::Matrix3Xd f = Eigen::Matrix3Xd::Zero(3, c.s.nodes());
    addSelfContact(p, env, c.s, false, cw, f);
    Vec3 F = Vec3::Zero(), M = Vec3::Zero(), onB = Vec3::Zero();
    const Vec3 o(0.3e-3, -0.7e-3, 0.2e-3);  // moments about an arbitrary point
    for (int i = 0; i < c.s.nodes(); ++i) {
      F += f.col(i);
      M += (c.s.x.col(i) - o).cross(f.col(i));
      if (i >= c.bFirst) onB += f.col(i);
    }
    const Vec3 want = bruteForceOnB(p, k, c);
    CHECK(want.z() >= k * 0.3 * R);  // the crossing pair, and the neighbours that also overlap
    CHECK((onB - want).norm() < 1e-12 * want.norm());
    CHECK(std::abs(onB.x()) < 1e-12 * onB.z());  // symmetric crossing: straight up
    CHECK(std::abs(onB.y()) < 1e-12 * onB.z());
    CHECK(F.norm() < 1e-12 * onB.z());
    CHECK(M.norm() < 1e-12 * onB.z() * R);
  }
  // rod B pressed down onto A with a total force P (rigid rods): equilibrium where the contact force
  // equals P, found by bisection on the height; the centrelines stop at 2R - P/k, i.e. 2R to 1e-3
  const double P = 1e-3 * k * R;
  double lo = 1.0 * R, hi = 2.5 * R;
  for (int it = 0; it < 80; ++it) {
    const double h = 0.5 * (lo + hi);
    Crossing c = crossing(R, h);
    Eigen::Matrix3Xd f = Eigen::Matrix3Xd::Zero(3, c.s.nodes());
    addSelfContact(p, env, c.s, false, cw, f);
    double up = 0;
    for (int i = c.bFirst; i < c.s.nodes(); ++i) up += f(2, i);
    (up > P ? lo : hi) = h;
  }
  ROOTSIM_CHECK_REL("crossing rods: centreline distance / 2R", lo / (2 * R), 1.0, 1e-3);
  CHECK(lo < 2 * R);
  CHECK(lo >= (2 * R - P / k) * (1 - 1e-12));  // at most one pair's give
}

TEST_CASE("self-contact: a rod coiling under its own intrinsic curvature never brings distant parts within 1.9 R") {
  // a clamped rod, no plate, with intrinsic curvature 1/(4R) over 1.6 turns of length: without
  // self-contact it relaxes into a flat circle that runs through its own base (distance 0); with it,
  // the turns stand off each other at 2R less the penalty's give
  auto run = [](bool contact, double& gap, RodState* out) {
    test::Cantilever c(90, 1.6 * 2 * units::pi * 4e-4, 1e-5);
    c.env.selfContact.enabled = contact;
    c.opt.speedTol = 1e-6;
    c.s.kappa0.row(0).setConstant(1.0 / 4e-4);
    c.s.kappa0.row(2).setConstant(0.01 / 4e-4);  // a slight twist: a helix of pitch 0.25 R
    c.relax();
    gap = minDistantGap(c.p, c.s);
    if (out) *out = c.s;
  };
  double off = 0, on = 0;
  RodState coiled;
  run(false, off, nullptr);
  run(true, on, &coiled);
  INFO("closest distant approach / R: without self-contact " << off << ", with " << on);
  CHECK(off < 1.0);
  CHECK(on > 1.9);
  // the coiled equilibrium, contacts included, is stable: the stiffness check reads the off-band
  // contact couplings column by column
  test::Cantilever c(90, 1.6 * 2 * units::pi * 4e-4);
  c.s = coiled;
  markSelfContactNodes(c.p, c.env, c.s, c.ws.contact);
  int inContact = 0;
  for (auto m : c.ws.contact.contactNode) inContact += m;
  CHECK(inContact > 0);
  CHECK(checkStability(c.p, c.env, c.s, c.ws).negative == 0);
}

TEST_CASE("self-contact: changes nothing, to the bit, while no distant parts come within 2R") {
  Model m = defaultModel();
  m.initial.elementLength = 1e-4;
  m.env.plane.alpha = 40 * units::deg;
  completeModel(m);
  Model off = m;
  off.env.selfContact.enabled = false;
  Simulation a(m), b(off);
  for (int k = 0; k < 60; ++k) {
    a.growthStep();
    b.growthStep();
  }
  CHECK(a.last().selfContacts == 0);
  CHECK((a.state().x.array() == b.state().x.array()).all());
  CHECK(a.totalSubsteps() == b.totalSubsteps());
}

namespace {
// a free straight rod (0.05 mm elements, the paper's root) lying on a plate tilted by alpha, along `dir`
// (a plate direction), under its weight at physical gravity, with the default solver options (its
// tolerances included) but for the solver kind
struct Incline {
  RodParams p;
  Environment env;
  SolverOptions opt;
  RodState s;
  RelaxWorkspace ws;
  NewtonWorkspace nw;
  Incline(double alphaDeg, bool alongDownhill, SolverKind kind, double length = 2e-3) {
    env.plane.alpha = alphaDeg * units::deg;
    env.adhesion = false;
    env.base = BaseCondition::Free;
    env.gravity = Vec3(0, 0, -9.81);
    env.friction.enabled = true;
    opt.kind = kind;
    const PlateFrame f = env.plane.frame();
    const Vec3 dir = alongDownhill ? f.downhill : f.lateral;
    s = straightRod(p.radius * f.normal, dir, f.normal, static_cast<int>(std::lround(length / 5e-5)), length);
  }
  // one relaxation with the chosen solver, as a simulation runs it (Simulation::newtonOrExplain): where
  // Newton finds no equilibrium the explicit relaxation takes over (from where Newton started if Newton
  // wandered more than Lref away), then Newton confirms; throws RelaxError when the rod slides
  void relaxOnce() {
    if (opt.kind == SolverKind::Dynamic) {
      relax(p, env, opt, s, ws);
      return;
    }
    const RodState start = s;
    RelaxResult r = relaxNewton(p, env, opt, s, ws, nw, 0);
    if (!r.stalled) return;
    if (r.crawled || (s.x - start.x).colwise().norm().maxCoeff() > s.restLength()) s = start;
    relax(p, env, opt, s, ws);
    r = relaxNewton(p, env, opt, s, ws, nw, 0);
    REQUIRE_MESSAGE(r.converged, r.message);
  }
  // stick points where it lies, then relax
  void settle() {
    ws.resize(s.elements());
    commitFriction(p, env, s, ws.contact);
    relaxOnce();
  }
};

const char* solverName(SolverKind k) { return k == SolverKind::Dynamic ? "dynamic" : "newton"; }

// true when the rod stays put; false when the relaxation reports sliding (the message is checked: it
// names the node)
bool sticks(Incline& c) {
  const RodState before = c.s;
  try {
    c.settle();
  } catch (const RelaxError& e) {
    const std::string w = e.what();
    INFO(w);
    CHECK(std::regex_search(w, std::regex(R"(node \d+ slides: no static equilibrium)")));
    return false;
  }
  // it stays where it was, to a fraction of R (the stick springs' give)
  CHECK((c.s.x - before.x).colwise().norm().maxCoeff() < 1e-2 * c.p.radius);
  return true;
}
}  // namespace

// Physical gravity and the default tolerances throughout: the residual must see the weight (relax.hpp:
// equilibriumTolerance). At these values the downhill pull on a node is 1e-9 .. 1e-8 N, far below
// 1e-4 B1/Lref^2 = 9.8e-8 N, the tolerance that let these rods stay put whatever mu.
TEST_CASE("incline: a free rod under its weight sticks iff mu_s >= cot(alpha), 5 percent either side, both solvers") {
  for (SolverKind kind : {SolverKind::Dynamic, SolverKind::Newton})
    for (double alpha : {50.0, 70.0, 80.0}) {
      const double cot = 1.0 / std::tan(alpha * units::deg);
      for (double factor : {1.05, 0.95}) {
        INFO(solverName(kind) << ", alpha " << alpha << " deg, mu_s = " << factor << " cot(alpha)");
        Incline c(alpha, true, kind);
        c.env.friction.muStatic = factor * cot;
        c.env.friction.muKinetic = 0.8 * factor * cot;
        // sliding is reported by the slide check ("node i slides: no static equilibrium", checked in
        // sticks()), not by the sub-step cap; how long it takes is measured (docs/contact.md), not asserted
        const bool stuck = sticks(c);
        CHECK(stuck == (factor > 1.0));
      }
    }
}

TEST_CASE("incline: a free rod on a frictionless plate slides, both solvers") {
  for (SolverKind kind : {SolverKind::Dynamic, SolverKind::Newton})
    for (double alpha : {50.0, 80.0}) {
      INFO(solverName(kind) << ", alpha " << alpha << " deg");
      Incline c(alpha, true, kind);
      c.env.friction.enabled = false;
      CHECK(!sticks(c));
    }
}

TEST_CASE("anisotropic friction: a rod along the slope slides when axial_ratio mu < cot(alpha), sticks across it") {
  // mu across the rod 3 cot(alpha), along it axial_ratio * 3 cot(alpha) = 0.95 or 1.05 cot(alpha): lying
  // downhill it sticks iff the axial mu holds it; turned across the slope the cross mu holds it
  for (SolverKind kind : {SolverKind::Dynamic, SolverKind::Newton})
    for (double alpha : {50.0, 70.0, 80.0}) {
      const double cot = 1.0 / std::tan(alpha * units::deg);
      for (double factor : {1.05, 0.95})
        for (bool downhill : {true, false}) {
          INFO(solverName(kind) << ", alpha " << alpha << " deg, axial mu = " << factor << " cot(alpha), lying "
                                << (downhill ? "downhill" : "across the slope"));
          Incline c(alpha, downhill, kind);
          c.env.friction.muStatic = 3.0 * cot;
          c.env.friction.muKinetic = 2.0 * cot;
          c.env.friction.axialRatio = factor / 3.0;
          CHECK(sticks(c) == (!downhill || factor > 1.0));
        }
    }
}

TEST_CASE("stick-slip: a rod dragged by a slowly growing tip force saw-tooths between mu_s N and mu_k N") {
  // horizontal plate (alpha = 90 deg), a 1 mm rod along y under its weight (physical gravity, default
  // tolerances); its tip is pulled along the rod through a spring whose far end moves a little each
  // step; friction commits after each equilibrium.
  // The closed form is that of a rigid block: the rod must be stiff in stretch against its stick
  // springs. With the paper's k_t = 1000 N/m per node the rod's stretch compliance concentrates the
  // pull near the tip (shear-lag length sqrt(EA h / k_t) = 0.28 mm on a 1 mm rod), slip spreads from
  // there and the whole rod lets go at 0.66 mu_s N (measured; a physical precursor, as in frictional
  // interfaces). With k_t = 0.1 N/m that length is 28 mm: 0.1 % of shear lag. (Weight and stick springs
  // both scale the same way, so gravity does not enter that ratio.)
  // And the pull must be soft enough to stick-slip at all: with slip weakening over ell (Friction::
  // slipWeakening, 1e-7 m) sliding is steady (at mu_s N, no drop) unless the pulling spring is softer
  // than (mu_s - mu_k) N / ell, 0.9 N/m for this rod's weight of 3e-7 N (the spring-block stability
  // criterion of slip-weakening friction). kAdhesion = 0.1 N/m: the drop then slips 9 ell, and the trough
  // lies within exp(-9) of mu_k N.
  for (SolverKind kind : {SolverKind::Dynamic, SolverKind::Newton}) {
    INFO(solverName(kind));
    Incline c(90.0, true, kind, 1e-3);
    c.env.plane.k = 0.1;
    const double muS = 0.6, muK = 0.3;
    c.env.friction.muStatic = muS;
    c.env.friction.muKinetic = muK;
    c.settle();
    const int tip = c.s.nodes() - 1;
    c.env.adhesion = true;
    c.env.kAdhesion = 0.1;
    c.s.anchored[static_cast<size_t>(tip)] = 1;
    c.s.anchor.col(tip) = c.s.x.col(tip);
    // the normal force on the nodes that feel friction (all but the pulled tip): their weight
    const double rhoA = c.p.density * units::pi * c.p.radius * c.p.radius;
    const double g = c.env.gravity.norm();
    const double W = rhoA * c.s.restLength() * g, Wtip = 0.5 * rhoA * c.s.l0[c.s.elements() - 1] * g;
    const double N = W - Wtip;
    const Vec3 pull = c.env.plane.downhill();
    // 2 % of the breakaway force per step while stuck: the pulling spring in series with the stick
    // springs of the other nodes
    const double kStick = c.env.plane.k * (c.s.nodes() - 1);
    const double dAnchor = 0.02 * muS * N * (1.0 / c.env.kAdhesion + 1.0 / kStick);
    std::vector<double> F;
    long slips = 0;
    for (int k = 0; k < 150; ++k) {
      c.s.anchor.col(tip) += dAnchor * pull;
      c.relaxOnce();
      slips += commitFriction(c.p, c.env, c.s, c.ws.contact).slips;
      F.push_back(c.env.kAdhesion * (c.s.anchor.col(tip) - c.s.x.col(tip)).dot(pull));
    }
    // the saw-tooth: rises while stuck, drops on slip; peaks at mu_s N, troughs at mu_k N
    int drops = 0;
    double peak = 0, trough = 1e300;
    for (size_t k = 1; k < F.size(); ++k) {
      if (F[k] < F[k - 1] - 0.1 * muS * N) {
        ++drops;
        peak = std::max(peak, F[k - 1]);
        trough = std::min(trough, F[k]);
      }
    }
    INFO("drops " << drops << ", peak " << peak / N << " N, trough " << trough / N << " N");
    CHECK(drops >= 3);
    CHECK(slips > 0);
    ROOTSIM_CHECK_REL("stick-slip peak / (mu_s N)", peak / (muS * N), 1.0, 0.05);
    ROOTSIM_CHECK_REL("stick-slip trough / (mu_k N)", trough / (muK * N), 1.0, 0.05);
    for (double f : F) CHECK(f < muS * N * 1.01);
  }
}

TEST_CASE("obstacles: a root growing into a peg slightly off its line goes round it without entering it and grows on") {
  Model m = defaultModel();
  m.initial.elementLength = 1e-4;
  m.env.plane.alpha = 10 * units::deg;
  Obstacle peg;
  peg.from = peg.to = Eigen::Vector2d(0.1e-3, 2.0e-3);  // R to the side of the root's line, 2 mm down
  peg.radius = 0.3e-3;
  m.env.obstacles.push_back(peg);
  completeModel(m);
  Simulation sim(m);
  const PlateFrame f = m.env.plane.frame();
  double worst = 1e300;
  int touching = 0;
  for (int k = 0; k < 260; ++k) {
    sim.growthStep();
    const RodState& s = sim.state();
    for (int i = 0; i < s.nodes(); ++i) {
      const Vec3 c = f.coords(s.x.col(i));
      worst = std::min(worst, (Eigen::Vector2d(c.x(), c.y()) - peg.from).norm() - peg.radius - m.rod.radius);
    }
    touching = std::max(touching, sim.last().obstacleContacts);
  }
  const Vec3 tip = f.coords(sim.state().x.col(sim.state().nodes() - 1));
  INFO("deepest overlap " << -worst / m.rod.radius << " R, tip at (" << tip.x() * 1e3 << ", " << tip.y() * 1e3 << ") mm");
  CHECK(touching > 0);                                   // it met the peg
  CHECK(worst > -0.1 * m.rod.radius);                    // and never entered it (penalty give < 0.1 R)
  CHECK(tip.y() > peg.from.y() + peg.radius + 0.3e-3);   // it grew on past the peg
  CHECK(tip.x() < 0.0);                                  // round the side away from the peg's centre
}

TEST_CASE("obstacles: forces push out along the in-plane normal, split by the segment parameter") {
  RodParams p;
  Environment env;
  env.plane.alpha = 30 * units::deg;
  const PlateFrame f = env.plane.frame();
  const RodState s = straightRod(p.radius * f.normal, f.downhill, f.normal, 10, 1e-3);
  ContactWorkspace cw;
  const double k = env.plane.k;
  // a wall along the whole rod, its face 0.5 R into it: every element pushed by k * 0.5 R sideways,
  // shared equally by its nodes (parallel segments: the middle of the overlap)
  {
    Obstacle wall;
    wall.shape = Obstacle::Shape::Wall;
    wall.from = Eigen::Vector2d(0.25e-3, -1e-3);
    wall.to = Eigen::Vector2d(0.25e-3, 2e-3);
    wall.radius = 0.2e-3;
    env.obstacles = {wall};
    Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, s.nodes());
    addObstacleContact(p, env, s, false, cw, force);
    const double fn = k * 0.5 * p.radius;
    for (int i = 0; i < s.nodes(); ++i) {
      const double share = (i == 0 || i == s.nodes() - 1) ? 0.5 : 1.0;
      CHECK((force.col(i) + share * fn * f.lateral).norm() < 1e-9 * fn);
    }
  }
  // a thin peg 0.05 R into element 4 at 40 % of its length: 60 % of the push on node 4, 40 % on node 5
  {
    Obstacle peg;
    peg.from = peg.to = Eigen::Vector2d(0.105e-3, 0.44e-3);
    peg.radius = 0.01e-3;
    env.obstacles = {peg};
    Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, s.nodes());
    addObstacleContact(p, env, s, false, cw, force);
    const double fn = k * 0.005e-3;
    CHECK((force.col(4) + 0.6 * fn * f.lateral).norm() < 1e-9 * fn);
    CHECK((force.col(5) + 0.4 * fn * f.lateral).norm() < 1e-9 * fn);
    ROOTSIM_CHECK_CLOSE(force.norm(), std::sqrt(0.36 + 0.16) * fn, kRoundoff);
    ROOTSIM_CHECK_CLOSE(cw.obstacleN[4], 0.6 * fn, kRoundoff);
  }
}

TEST_CASE("friction in a growing root: stick points where it touches, none on adhered nodes, slips counted, nothing without friction") {
  Model m = defaultModel();
  m.initial.elementLength = 1e-4;
  m.env.friction.enabled = true;
  m.env.friction.muStatic = 0.3;
  m.env.friction.muKinetic = 0.2;
  completeModel(m);
  Simulation sim(m);
  for (int k = 0; k < 40; ++k) sim.growthStep();
  const RodState& s = sim.state();
  int sticks = 0;
  for (int i = 0; i < s.nodes(); ++i) {
    const auto u = static_cast<size_t>(i);
    sticks += s.hasPlateStick[u];
    CHECK(!(s.hasPlateStick[u] && s.anchored[u]));  // adhered nodes are glued, not rubbing
  }
  CHECK(sticks > 0);
  CHECK(static_cast<int>(s.hasPlateStick.size()) == s.nodes());
  CHECK(sim.last().slipEvents > 0);  // the growing tip slides over the plate
  CHECK(sim.last().frictionWork > 0.0);

  Model off = defaultModel();
  off.initial.elementLength = 1e-4;
  completeModel(off);
  Simulation b(off);
  for (int k = 0; k < 10; ++k) b.growthStep();
  CHECK(b.last().slipEvents == 0);
  CHECK(b.last().frictionWork == 0.0);
  for (auto h : b.state().hasPlateStick) CHECK(h == 0);
}

TEST_CASE("self-contact with the Newton solver: a coil in contact under a new load reaches the explicit equilibrium by Newton alone, with the stability check's inertia") {
  auto coil = [] {
    test::Cantilever c(90, 1.6 * 2 * units::pi * 4e-4, 1e-6);
    c.opt.speedTol = 1e-7;
    c.s.kappa0.row(0).setConstant(1.0 / 4e-4);
    c.s.kappa0.row(2).setConstant(0.01 / 4e-4);
    c.relax();
    return c;
  };
  test::Cantilever a = coil();
  test::Cantilever b = coil();
  markSelfContactNodes(a.p, a.env, a.s, a.ws.contact);
  int inContact = 0;
  for (auto m : a.ws.contact.contactNode) inContact += m;
  REQUIRE(inContact > 0);
  // a small tip load on both: explicit relaxation and Newton (with the off-band contact couplings, a
  // sparse Jacobian)
  const Vec3 F(0, 0, 2e-3 * a.B1() / (a.L * a.L));
  a.env.tipForce = b.env.tipForce = F;
  a.relax();
  NewtonWorkspace nw;
  b.opt.stabilityCheck = true;
  const RelaxResult r = relaxNewton(b.p, b.env, b.opt, b.s, b.ws, nw, 0);
  INFO("Newton: " << (r.converged ? "converged" : r.message) << " after " << r.iterations << " iterations");
  CHECK(r.converged);
  CHECK(!r.stalled);
  CHECK(r.iterations <= 6);  // quadratic convergence from a nearby equilibrium
  CHECK(nw.sparseActive);
  CHECK((a.s.x - b.s.x).colwise().norm().maxCoeff() < 1e-3 * a.p.radius);
  CHECK(minDistantGap(b.p, b.s) > 1.9);
  // the inertia of Newton's sparse LDL^T is the stability check's (which reads whole columns), and its
  // eigenvalue nearest zero is the dense symmetric stiffness's
  CHECK(nw.negative == checkStability(b.p, b.env, b.s, b.ws).negative);
  NewtonWorkspace dense;
  assembleStiffness(b.p, b.env, b.opt, b.s, b.ws, dense, 0);
  const Eigen::MatrixXd K = test::assembledStiffness(dense);
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (K + K.transpose())).eigenvalues();
  Eigen::Index nearest = 0;
  ev.cwiseAbs().minCoeff(&nearest);
  INFO("eigenvalue nearest zero: Newton " << nw.lowestEigenvalue << ", dense " << ev[nearest]);
  CHECK(nw.lowestEigenvalue == doctest::Approx(ev[nearest]).epsilon(1e-3));
}

TEST_CASE("self-contact: Newton's Jacobian, band and off-band entries, equals one-dof-at-a-time central differences on a coil in contact") {
  test::Cantilever c(90, 1.6 * 2 * units::pi * 4e-4, 1e-6);
  c.opt.speedTol = 1e-7;
  c.s.kappa0.row(0).setConstant(1.0 / 4e-4);
  c.s.kappa0.row(2).setConstant(0.01 / 4e-4);
  c.relax();
  NewtonWorkspace nw;
  assembleStiffness(c.p, c.env, c.opt, c.s, c.ws, nw, 0);
  REQUIRE(!nw.offBand.empty());
  const Eigen::MatrixXd K = test::assembledStiffness(nw);
  const Eigen::MatrixXd ref = test::oneDofStiffness(c.p, c.env, c.s, c.ws, 1);  // clamped: node 0 is held
  // the far (off-band) couplings are there and right, and nothing is lost anywhere else
  double farRef = 0;
  for (const OffBandEntry& e : nw.offBand) farRef = std::max(farRef, std::abs(ref(e.row, e.col)));
  INFO("largest entry " << ref.cwiseAbs().maxCoeff() << ", largest off-band entry " << farRef
                        << ", largest difference " << (K - ref).cwiseAbs().maxCoeff());
  CHECK(farRef > 1e-3 * ref.cwiseAbs().maxCoeff());
  CHECK((K - ref).cwiseAbs().maxCoeff() <= 1e-6 * ref.cwiseAbs().maxCoeff());
}

TEST_CASE("contact between roots: a force exactly where the contact points are closer than Ra + Rb") {
  // random element pairs at distances around the contact distance, apart along every axis in turn (the
  // law first rejects pairs whose boxes lie farther apart than that): the force exists exactly when the
  // distance between the pair's contact points is below Ra + Rb, and is k (Ra + Rb - d) there
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double ra = 0.1e-3, rb = 0.06e-3, k = 1000, len = 0.05e-3;
  const Vec3 up(0, 0, 1), origin(0.02, -0.013, 0.004);  // plate coordinates: away from zero, as on a plate
  int touching = 0, apart = 0;
  for (int t = 0; t < 20000; ++t) {
    const Vec3 a0 = origin + len * Vec3(u(rng), u(rng), u(rng));
    const Vec3 a1 = a0 + len * Vec3(u(rng), u(rng), u(rng));
    Vec3 shift = 0.3 * (ra + rb) * Vec3(u(rng), u(rng), u(rng));
    shift[t % 3] += (ra + rb + len) * (1.0 + 0.5 * u(rng));  // near the box test's threshold on that axis
    const Vec3 b0 = a0 + shift, b1 = b0 + len * Vec3(u(rng), u(rng), u(rng));
    double sa = 0, sb = 0;
    contactSegmentPoints(a0, a1, b0, b1, sa, sb);
    const double d = ((a0 + sa * (a1 - a0)) - (b0 + sb * (b1 - b0))).norm();
    RootPairForce pf;
    const bool force = rootPairForce(ra, rb, k, up, a0, a1, b0, b1, pf);
    INFO("pair " << t << ": d / (Ra + Rb) = " << d / (ra + rb));
    REQUIRE(force == (d < ra + rb));
    if (force) CHECK(pf.F.norm() == doctest::Approx(k * (ra + rb - d)).epsilon(1e-12));
    (force ? touching : apart) += 1;
  }
  INFO(touching << " pairs touching, " << apart << " apart");
  CHECK(touching > 1000);
  CHECK(apart > 1000);
}
