// the explicit dynamic relaxation (src/sim/relax_dynamic.cpp; its computeForces moves to src/sim/forces.cpp):
// closed-form mechanics, a relaxation window, no heap allocation in a sub-step, errors that name step,
// node and quantity, physical masses with viscous damping.
// Validation of the rod core and the dynamic relaxation against closed-form mechanics (docs/model.md,
// Rod mechanics). Each case runs at two resolutions; with ROOTSIM_PRINT_RESIDUALS=1 the errors and the
// observed convergence order are printed (ROOTSIM_PRINT_RESIDUALS=1) and, for the second-order
// schemes, asserted.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "physics_support.hpp"
#include "rootsim/contact_observe.hpp"
#include "rootsim/simulation.hpp"

using namespace rootsim;
using rootsim::test::Cantilever;
using rootsim::test::gAllocs;
using rootsim::test::order;
using rootsim::test::relError;

namespace {
constexpr double pi = std::numbers::pi;

void printOrder(const char* what, int n1, double e1, int n2, double e2) {
  if (rootsim::test::printResiduals())
    std::printf("[order] %-40s n=%d err %.3e  n=%d err %.3e  order %.2f\n", what, n1, e1, n2, e2,
                order(e1, e2, n1, n2));
}
}  // namespace

TEST_CASE("cantilever, small tip load: Timoshenko deflection (bending + shear) within 1%") {
  double err[2];
  const int ns[2] = {25, 50};
  for (int r = 0; r < 2; ++r) {
    Cantilever c(ns[r]);
    const double P = 3e-3 * c.B1() / (c.L * c.L);  // tip deflection ~ 1e-3 L
    c.env.tipForce = Vec3(-P, 0, 0);              // along -d1
    c.relax();
    const double S1 = c.p.shearStiffness().x();
    const double want = P * std::pow(c.L, 3) / (3 * c.B1()) + P * c.L / S1;
    const double got = -c.tip().x();
    err[r] = relError(got, want);
    ROOTSIM_CHECK_REL("Timoshenko tip deflection", got, want, 0.01);
  }
  printOrder("Timoshenko tip deflection", ns[0], err[0], ns[1], err[1]);
  // second order in the element length (measured 2.06 and 1.94)
  CHECK(order(err[0], err[1], ns[0], ns[1]) >= 1.9);
}

TEST_CASE("explicit relaxation of a window: the frozen part stays, the free part is a cantilever clamped at the window's start") {
  // the Newton solver's fallback relaxes only the nodes and elements from firstFreeNode = k on; the rod
  // before stays exactly, so the free part is a cantilever clamped in element k - 1's frame. Its
  // bending starts at the Voronoi domain around node k, which reaches half an element back: the clamp
  // sits at the middle of element k - 1 (length L - (k - 1/2) l; measured: with L - k l the error is
  // first order, 10 % and 5 % at 25 and 50 elements). Timoshenko's deflection of that length, relative
  // to the frozen node k - 1.
  double err[2];
  const int ns[2] = {25, 50};
  for (int r = 0; r < 2; ++r) {
    Cantilever c(ns[r]);
    const int k = ns[r] * 2 / 5;  // the first 40 % frozen
    const double P = 3e-3 * c.B1() / (c.L * c.L);
    c.env.tipForce = Vec3(-P, 0, 0);
    const RodState before = c.s;
    rootsim::relax(c.p, c.env, c.opt, c.s, c.ws, k);
    for (int i = 0; i < k; ++i) {
      CHECK(c.s.x.col(i) == before.x.col(i));
      CHECK(c.s.Q[static_cast<size_t>(i)] == before.Q[static_cast<size_t>(i)]);
    }
    const double Lf = c.L * (ns[r] - k + 0.5) / ns[r];
    const double S1 = c.p.shearStiffness().x();
    const double want = P * std::pow(Lf, 3) / (3 * c.B1()) + P * Lf / S1;
    const double got = -(c.s.x.col(c.s.nodes() - 1) - c.s.x.col(k - 1)).x();
    err[r] = relError(got, want);
    ROOTSIM_CHECK_REL("Timoshenko deflection of the window", got, want, 0.01);
  }
  printOrder("window: Timoshenko deflection", ns[0], err[0], ns[1], err[1]);
  // second order in the element length (measured 2.06 and 1.94)
  CHECK(order(err[0], err[1], ns[0], ns[1]) >= 1.9);
}

TEST_CASE("cantilever, large tip load: elastica solution (shooting) within 1%") {
  const double load = 3.0;  // P L^2 / B
  const auto ref = rootsim::test::elasticaTip(load);
  double err[2];
  const int ns[2] = {25, 50};
  for (int r = 0; r < 2; ++r) {
    Cantilever c(ns[r]);
    const double P = load * c.B1() / (c.L * c.L);
    c.env.tipForce = Vec3(-P, 0, 0);
    c.relax();
    const Vec3 tip = c.tip() / c.L;
    // axis along -y, load along -x: xi = -y, eta = x
    const double gotEta = tip.x(), gotXi = -tip.y();
    ROOTSIM_CHECK_REL("elastica tip deflection", gotEta, ref.eta, 0.01);
    ROOTSIM_CHECK_REL("elastica tip axial position", gotXi, ref.xi, 0.01);
    err[r] = relError(gotEta, ref.eta);
  }
  printOrder("elastica tip deflection", ns[0], err[0], ns[1], err[1]);
  // converges, but below second order (measured 1.35 between 25 and 50 elements, against the shooting
  // reference); the cause is not established, so only the decrease is asserted
  CHECK(err[1] < err[0]);
}

TEST_CASE("end moment: the rod rolls into the exact circular arc, up to a full circle") {
  for (double turns : {0.25, 0.5, 1.0}) {
    double err[2];
    const int ns[2] = {40, 80};
    for (int r = 0; r < 2; ++r) {
      Cantilever c(ns[r]);
      // the closed form is the contact-free elastica: a full circle brings the tip back onto the base,
      // where self-contact (on by default) rightly holds it 2R off
      c.env.selfContact.enabled = false;
      const double M = 2 * pi * turns * c.B1() / c.L;  // curvature M / B2 = 2 pi turns / L
      c.env.tipTorque = Vec3(0, 0, M);                  // about d2 = z: bends in the x-y plane
      c.relax();
      const double k = M / c.p.bendStiffness().y();
      // exact arc from the clamp: tangent -y at the base, turning toward +x with curvature k about +z
      // every node: a full circle closes exactly in the discrete model too, so the tip alone cannot
      // show the order
      err[r] = 0.0;
      for (int i = 0; i < c.s.nodes(); ++i) {
        const double phi = k * c.s.S[i];
        const Vec3 want((1 - std::cos(phi)) / k, -std::sin(phi) / k, 0);
        const Vec3 got = c.s.x.col(i) - c.s.x.col(0);
        err[r] = std::max(err[r], (got - want).norm() / c.L);
      }
      INFO("turns " << turns << " n " << ns[r] << " tip " << c.tip().transpose());
      CHECK(err[r] < 0.01);
      const double kmid = c.ws.strains.kappa(1, ns[r] / 2) / c.ws.strains.ev[ns[r] / 2];
      ROOTSIM_CHECK_REL("arc curvature kappa2 = M/B2", kmid, k, 1e-4);
    }
    printOrder(turns == 1.0 ? "full circle, max node error" : "arc, max node error", ns[0], err[0], ns[1], err[1]);
    CHECK(order(err[0], err[1], ns[0], ns[1]) >= 1.9);  // second order (measured 2.00)
  }
}

TEST_CASE("end torque: uniform twist kappa3 = T / (G J), no bending") {
  for (int n : {20, 40}) {
    Cantilever c(n);
    const double B3 = c.p.bendStiffness().z();
    const double T = 0.5 * B3 / c.L;  // half a radian of twist over the rod
    c.env.tipTorque = Vec3(0, -T, 0);  // about d3 = -y: right-handed twist
    c.relax();
    for (int j = 1; j + 1 < n; ++j) {
      CHECK(c.ws.strains.kappa(2, j) == doctest::Approx(T / B3).epsilon(1e-5));
      CHECK(std::abs(c.ws.strains.kappa(0, j)) < 1e-6 * T / B3);
      CHECK(std::abs(c.ws.strains.kappa(1, j)) < 1e-6 * T / B3);
    }
    CHECK(std::abs(c.tip().x()) < 1e-9 * c.L);
    CHECK(std::abs(c.tip().z()) < 1e-9 * c.L);
  }
}

TEST_CASE("Euler buckling of a clamped-free rod: straight below 0.95 Pcr, buckled above 1.05 Pcr") {
  for (int n : {20, 40}) {
    double defl[2];
    const double ratios[2] = {0.95, 1.05};
    for (int r = 0; r < 2; ++r) {
      Cantilever c(n, 1e-2, 1e-7);
      const double Pcr = pi * pi * c.B1() / (4 * c.L * c.L);
      const double P = ratios[r] * Pcr;
      // compressive dead load along -d3 = +y, with a 1e-3 lateral imperfection load
      c.env.tipForce = Vec3(-1e-3 * P, P, 0);
      c.relax();
      defl[r] = -c.tip().x() / c.L;
    }
    INFO("n " << n << " lateral tip deflection / L at 0.95 Pcr: " << defl[0] << ", at 1.05 Pcr: " << defl[1]);
    if (rootsim::test::printResiduals())
      std::printf("[buckling] n=%d deflection/L at 0.95 Pcr %.3e, at 1.05 Pcr %.3e\n", n, defl[0], defl[1]);
    // linear theory with imperfection: 1e-3 * P L^2/(3B) / (1 - P/Pcr) ~ 0.016 at 0.95 Pcr
    CHECK(defl[0] < 0.03);
    // post-buckling: tip angle^2 ~ 8 (P/Pcr - 1) gives a deflection of order 0.3 L
    CHECK(defl[1] > 0.2);
  }
}

TEST_CASE("axial load: dilatation 1 + F/(E A) (exactly 1 / (1 - F/(E A)) with S -> S/e)") {
  for (int n : {10, 20}) {
    Cantilever c(n);
    const double EA = c.p.shearStiffness().z();
    const double F = 1e-3 * EA;
    c.env.tipForce = Vec3(0, -F, 0);  // tension along d3 = -y
    c.relax();
    const double Lnow = -c.tip().y();
    const double e = Lnow / c.L;
    ROOTSIM_CHECK_REL("axial dilatation - 1 vs F/EA", e - 1.0, F / EA, 2e-3);
    ROOTSIM_CHECK_REL("axial dilatation exact", e, 1.0 / (1.0 - F / EA), 1e-9);
  }
}

TEST_CASE("a relaxation sub-step allocates nothing") {
  Cantilever c(100);
  c.env.plane.enabled = true;  // contact, adhesion and loads all in play
  c.env.plane.alpha = 0.7;
  c.env.adhesion = true;
  c.s.anchored[5] = 1;
  c.env.tipForce = Vec3(1e-4, 0, 0);
  c.opt.maxSubsteps = std::numeric_limits<long>::max();
  DynamicRelaxation r(c.p, c.env, c.opt, c.s, c.ws);
  r.step();  // first step may size the workspace
  const long before = gAllocs.load();
  for (int i = 0; i < 1000; ++i) r.step();
  CHECK(gAllocs.load() - before == 0);
}

TEST_CASE("a relaxation sub-step with self-contact, friction and an obstacle in play allocates nothing") {
  Cantilever c(100, 1e-2);
  c.env.plane.enabled = true;
  c.env.plane.alpha = 0.7;
  c.env.friction.enabled = true;
  c.env.friction.muStatic = 0.5;
  c.env.friction.muKinetic = 0.3;
  Obstacle peg;
  peg.from = peg.to = Eigen::Vector2d(1.5e-4, 5e-3);  // overlaps the rod by half a radius
  peg.radius = 1e-4;
  c.env.obstacles.push_back(peg);
  // element 80 laid over element 20, R above it: a self-contact pair
  const Vec3 nh = c.env.plane.normal();
  c.s.x.col(80) = c.s.x.col(20) + 1.0 * c.p.radius * nh;
  c.s.x.col(81) = c.s.x.col(21) + 1.0 * c.p.radius * nh;
  c.env.gravity = Vec3(0, 0, -9.81e3);
  c.ws.resize(c.s.elements());
  commitFriction(c.p, c.env, c.s, c.ws.contact);
  c.opt.maxSubsteps = std::numeric_limits<long>::max();
  DynamicRelaxation r(c.p, c.env, c.opt, c.s, c.ws);
  r.step();
  ContactObservables seen = observeContacts(c.p, c.env, c.s);
  CHECK(seen.selfContacts > 0);
  CHECK(seen.obstacleContacts > 0);
  const long before = gAllocs.load();
  for (int i = 0; i < 1000; ++i) r.step();
  CHECK(gAllocs.load() - before == 0);
}

TEST_CASE("hitting the sub-step cap is an error naming node and residual") {
  Cantilever c(20);
  c.env.tipForce = Vec3(-1e-3, 0, 0);
  c.opt.maxSubsteps = 50;
  try {
    c.relax();
    FAIL("no error");
  } catch (const RelaxError& e) {
    const std::string w = e.what();
    CHECK(w.find("did not reach equilibrium in 50 sub-steps") != std::string::npos);
    CHECK(w.find("at node") != std::string::npos);
    CHECK(w.find("residual couple") != std::string::npos);
  }
}

TEST_CASE("a non-finite force stops the run with sub-step, node and quantity") {
  Cantilever c(20);
  c.env.tipForce = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  try {
    c.relax();
    FAIL("no error");
  } catch (const RelaxError& e) {
    CHECK(std::string(e.what()).find("diverged at sub-step 1: force on node 20 is not finite") != std::string::npos);
  }
}

TEST_CASE("physical masses with viscous damping reach the same equilibrium as scaled masses with FIRE") {
  Cantilever a(20), b(20);
  for (Cantilever* c : {&a, &b}) {
    c->env.tipForce = Vec3(-0.5 * c->B1() / (c->L * c->L), 0, 0);
    c->opt.forceTol = 1e-7;
  }
  b.opt.mass = MassModel::Physical;
  a.relax();
  const RelaxResult rb = b.relax();
  CHECK(rb.dt < 1e-6);  // the physical stability limit (~1e-7 s here)
  CHECK((a.tip() - b.tip()).norm() < 1e-6 * a.L);
}
