// Relaxation benchmarks: cost of one sub-step, sub-steps + wall time to settle a rod, and one growth
// step of each solver at several root lengths.
//   ./build/bench/bench_relax --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "../tests/physics_support.hpp"
#include "rootsim/model.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;

namespace {

// the rod: 10 mm, R = 0.1 mm, E = 50 MPa, density 1000, horizontal cantilever, no plane (the
// tests' cantilever, with the solver's default options)
struct Setup : rootsim::test::Cantilever {
  explicit Setup(int n) : Cantilever(n) { opt = SolverOptions{}; }
  // bends the rod so that its tip is displaced by d [m] (static tip load), then removes the load
  void displaceTip(double d) {
    const double B = p.bendStiffness().x();
    env.tipForce = Vec3(-3 * B * d / (L * L * L), 0, 0);
    SolverOptions o;
    o.forceTol = 1e-7;
    rootsim::relax(p, env, o, s, ws);
    env.tipForce.setZero();
  }
};

// one sub-step of a bent rod relaxing under a tip load (FIRE, scaled masses)
void BM_Substep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Setup st(n);
  st.env.tipForce = Vec3(-1e-3, 0, 1e-4);
  st.opt.maxSubsteps = 1L << 60;
  st.opt.forceTol = 0.0;  // never converges: every iteration is a full sub-step (kick, FIRE, drift)
  st.opt.speedTol = 0.0;
  DynamicRelaxation r(st.p, st.env, st.opt, st.s, st.ws);
  for (auto _ : state) benchmark::DoNotOptimize(r.step());
  state.counters["element_substeps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * n, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Substep)->Arg(50)->Arg(100)->Arg(200)->Arg(400)->Unit(benchmark::kMicrosecond);

// the cost of self-contact's broad phase where nothing touches. Arg 0: element count,
// arg 1: self-contact off (0) or on (1). The sub-step of a bent rod relaxing, as BM_Substep.
void BM_SubstepSelfContact(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Setup st(n);
  st.env.selfContact.enabled = state.range(1) != 0;
  st.env.tipForce = Vec3(-1e-3, 0, 1e-4);
  st.opt.maxSubsteps = 1L << 60;
  st.opt.forceTol = 0.0;
  st.opt.speedTol = 0.0;
  DynamicRelaxation r(st.p, st.env, st.opt, st.s, st.ws);
  for (auto _ : state) benchmark::DoNotOptimize(r.step());
  state.counters["list_builds"] = static_cast<double>(st.ws.contact.builds);
}
BENCHMARK(BM_SubstepSelfContact)
    ->Args({100, 0})->Args({100, 1})->Args({400, 0})->Args({400, 1})
    ->Unit(benchmark::kMicrosecond);

// a growing root with no contact (Fig. 2B scene, alpha = 40, beta = 0.2; 300 growth steps of
// the paper's resolution), self-contact off (0) or on (1): the whole run, grow + relax + observe
void BM_GrowthSelfContact(benchmark::State& state) {
  long substeps = 0;
  for (auto _ : state) {
    Model m = defaultModel();
    m.tropism.beta = 0.2;
    m.env.selfContact.enabled = state.range(0) != 0;
    completeModel(m);
    Simulation sim(m);
    for (int k = 0; k < 300; ++k) sim.growthStep();
    substeps = sim.totalSubsteps();
  }
  state.counters["substeps"] = static_cast<double>(substeps);
}
BENCHMARK(BM_GrowthSelfContact)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);

// settling of the 10 mm rod released from a 1 mm tip displacement; arg 0: element count,
// arg 1: 0 = scaled masses + FIRE (default), 1 = physical masses + viscous damping (PyElastica-like,
// nu = 2e4 1/s), 2 = physical masses + FIRE
void BM_Settle(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int mode = static_cast<int>(state.range(1));
  long substeps = 0;
  double dt = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Setup st(n);
    st.displaceTip(1e-3);
    st.opt.forceTol = 1e-5;   // residual force < 1e-5 B1/L^2, couple < 1e-5 B1/L
    st.opt.speedTol = 1e-6;
    st.opt.maxSubsteps = 20000000;
    if (mode >= 1) st.opt.mass = MassModel::Physical;
    if (mode == 1) st.opt.damping = Damping::Viscous;
    state.ResumeTiming();
    const RelaxResult r = relax(st.p, st.env, st.opt, st.s, st.ws);
    substeps = r.substeps;
    dt = r.dt;
    benchmark::DoNotOptimize(st.s.x.data());
  }
  state.counters["substeps"] = static_cast<double>(substeps);
  state.counters["dt"] = dt;
}
BENCHMARK(BM_Settle)
    ->Args({100, 0})
    ->Args({200, 0})
    ->Args({100, 1})
    ->Args({100, 2})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// one growth step of the Fig. 2B root (alpha 40, beta 0.2, gamma 0.1, 0.05 mm elements, 0.05 h steps)
// at a root length of arg 0 mm, with arg 1: 0 = dynamic (the paper's explicit relaxation with the
// stability check), 1 = newton on the whole rod (solver.window_mm = 0), 2 = newton with the default
// window. The root is grown to that length with the default solver first (not timed), then handed to the
// solver measured; each iteration is one growth step.
void BM_GrowthStep(benchmark::State& state) {
  const double lengthMm = static_cast<double>(state.range(0));
  Model m = defaultModel();
  m.env.plane.alpha = 40 * units::deg;
  m.tropism.beta = 0.2;
  m.solver.kind = SolverKind::Newton;
  completeModel(m);
  const int steps = static_cast<int>(std::lround((lengthMm - 1.1) / 0.2 / 0.05));
  Simulation grow(m);
  for (int k = 0; k < steps; ++k) grow.growthStep();
  m.solver.kind = state.range(1) == 0 ? SolverKind::Dynamic : SolverKind::Newton;
  if (state.range(1) == 1) m.solver.window = 0.0;
  Simulation sim(m, grow.state(), grow.step());
  long substeps = 0, iterations = 0;
  for (auto _ : state) {
    const StepRecord& r = sim.growthStep();
    substeps += r.substeps;
    iterations += r.iterations;
  }
  state.counters["elements"] = sim.state().elements();
  state.counters["substeps_per_step"] = static_cast<double>(substeps) / static_cast<double>(state.iterations());
  state.counters["newton_its_per_step"] = static_cast<double>(iterations) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_GrowthStep)
    ->ArgsProduct({{5, 10, 20, 30}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);

}  // namespace

BENCHMARK_MAIN();
