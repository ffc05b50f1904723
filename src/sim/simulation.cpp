#include "rootsim/simulation.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "rootsim/growth.hpp"
#include "rootsim/stability.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {
RelaxResult relaxOrExplain(const Model& m, RodState& s, RelaxWorkspace& ws, int step) {
  try {
    return relax(m.rod, m.env, m.solver, s, ws);
  } catch (const RelaxError& e) {
    std::ostringstream os;
    os << "growth step " << step << " (t = " << s.time / units::hour << " h, " << s.elements()
       << " elements): " << e.what();
    throw RelaxError(os.str());
  }
}
}  // namespace

Simulation::Simulation(const Model& m) : m_(m) {
  s_ = makeInitialRod(m_.rod, m_.env.plane, m_.initial);
  if (m_.growth.enabled) {
    applyTwistProfile(m_, s_);
    anchorMatureNodes(m_, s_);
  }
  int unstable = 0;
  const RelaxResult r = relaxStable(0, unstable);
  totalSubsteps_ = r.substeps;
  observe(r.substeps, r.residualForce, 0, unstable);
}

const StepRecord& Simulation::growthStep() {
  ++step_;
  const double dt = m_.growth.stepTime;
  // the kappa0 law reads the relaxed state of the previous step
  const RodStrains& k = ws_.strains;
  anchorMatureNodes(m_, s_);
  updateIntrinsicCurvature(m_, s_, k, dt);
  growRestLengths(m_, s_, dt);
  s_.time += dt;
  applyTwistProfile(m_, s_);
  const int splits = splitLongElements(m_, s_);
  int unstable = 0;
  const RelaxResult r = relaxStable(step_, unstable);
  totalSubsteps_ += r.substeps;
  observe(r.substeps, r.residualForce, splits, unstable);
  return rec_;
}

RelaxResult Simulation::relaxStable(int step, int& unstable) {
  RelaxResult total = relaxOrExplain(m_, s_, ws_, step);
  if (!m_.solver.stabilityCheck || !m_.growth.enabled) return total;
  // An explicit relaxation can settle on a saddle point (the straight root just past the loss of
  // stability): the residual vanishes there too. The inertia of the stiffness matrix tells; when it
  // has negative pivots, the state is pushed along the unstable mode and relaxed again, so the
  // sideways snap happens at the step where stability is lost, not when round-off gets around to it.
  const double amplitudes[] = {0.02, 0.1, 0.5};  // of R
  for (double a : amplitudes) {
    const StabilityReport st = checkStability(m_.rod, m_.env, s_, ws_);
    if (st.negative == 0) break;
    ++unstable;
    // go the way the root already leans (the seeded perturbation decides a symmetric snap)
    const int n = s_.elements();
    const double lean = s_.x(0, n) - s_.x(0, 0);
    const double tipMode = st.mode[6 * n];
    const double sign = (lean == 0.0 || tipMode == 0.0) ? 1.0 : (lean * tipMode > 0 ? 1.0 : -1.0);
    perturbAlong(s_, st.mode, sign * a * m_.rod.radius);
    const RelaxResult r = relaxOrExplain(m_, s_, ws_, step);
    total.substeps += r.substeps;
    total.residualForce = r.residualForce;
    total.residualTorque = r.residualTorque;
  }
  return total;
}

void Simulation::observe(long substeps, double residual, int splits, int unstable) {
  // ws_.strains holds the strains of the relaxed state (computed at the last sub-step)
  computeStrains(m_.rod, s_, ws_.strains);
  StepRecord r;
  r.step = step_;
  r.timeH = s_.time / units::hour;
  r.length = s_.restLength();
  r.elements = s_.elements();
  const double th = tipAngle(m_, s_);
  if (step_ == 0) thetaUnwrapped_ = th;
  else thetaUnwrapped_ += std::remainder(th - thetaUnwrapped_, 2.0 * std::numbers::pi);
  r.thetaTip = thetaUnwrapped_;
  if (m_.growth.enabled) r.zone = observeZone(m_, s_, ws_.strains);
  r.substeps = substeps;
  r.residualForce = residual;
  r.splits = splits;
  r.unstable = unstable;
  r.tip = s_.x.col(s_.nodes() - 1);
  rec_ = r;
}

Snapshot Simulation::snapshot() const {
  Snapshot sn = makeSnapshot(m_.rod, s_, ws_.strains, step_);
  sn.timeH = s_.time / units::hour;
  return sn;
}

}  // namespace rootsim
