// the relaxation loop: no heap allocation in a sub-step, errors that name step, node and quantity
#include <doctest/doctest.h>

#include <atomic>
#include <cstdlib>
#include <limits>
#include <new>
#include <string>

#include "rod_fixture.hpp"
#include "rootsim/contact_observe.hpp"
#include "rootsim/simulation.hpp"

namespace {
std::atomic<long> gAllocs{0};
}
// counting global allocator (this test binary only)
void* operator new(std::size_t n) {
  ++gAllocs;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace rootsim;
using rootsim::test::Cantilever;

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

TEST_CASE("a growth step with the Newton solver allocates nothing after warm-up, unless it splits") {
  Model m = defaultModel();
  m.initial.elementLength = 1e-4;
  m.growth.stepTime = 0.1 * 3600;
  m.solver.kind = SolverKind::Newton;
  completeModel(m);
  Simulation sim(m);
  for (int k = 0; k < 20; ++k) sim.growthStep();  // warm-up
  int checked = 0;
  for (int k = 0; k < 40; ++k) {
    const long before = gAllocs.load();
    const StepRecord& r = sim.growthStep();
    const long allocs = gAllocs.load() - before;
    if (r.splits > 0 || r.unstable > 0) continue;  // remeshing rebuilds the state; a snap relaxes explicitly
    INFO("step " << r.step << ": " << allocs << " allocations");
    CHECK(allocs == 0);
    ++checked;
  }
  CHECK(checked > 10);
}
