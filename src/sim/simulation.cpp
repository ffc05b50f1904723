#include "rootsim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "rootsim/assert.hpp"
#include "rootsim/contact.hpp"
#include "rootsim/contact_newton.hpp"
#include "rootsim/contact_observe.hpp"
#include "rootsim/growth.hpp"
#include "rootsim/stability.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {
RelaxResult relaxOrExplain(const Model& m, RodState& s, RelaxWorkspace& ws, int step, int firstFreeNode = 0) {
  try {
    return relax(m.rod, m.env, m.solver, s, ws, firstFreeNode);
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
  // friction: stick points where the rod touches before it first relaxes (otherwise the first
  // relaxation would be frictionless)
  ws_.resize(s_.elements());
  commitFriction(m_.rod, m_.env, s_, ws_.contact);
  int unstable = 0;
  const RelaxResult r = relaxStable(0, unstable);
  commitStep();
  p_.totalSubsteps = r.substeps;
  p_.totalIterations = r.iterations;
  observe(r, 0, unstable);
}

Simulation::Simulation(const Model& m, const RodState& s, int step) : m_(m), s_(s) {
  p_.step = step;
  ws_.resize(s_.elements());
  p_.thetaUnwrapped = tipAngle(m_, s_);  // the tip angle's earlier turns are not known here
  observe(RelaxResult{}, 0, 0);
}

Simulation::Simulation(const Model& m, const RodState& s, const SimulationCarry& c)
    : Simulation(m, s, c.progress.step) {
  // the restart constructor recomputed the strains of the state (what observe() left in the
  // workspace); the rest comes from the carry, field list by field list (fields.hpp)
  p_ = c.progress;
  nw_.reserve(s_.elements());
  const bool restored = restore(nw_, c.newton);  // false: the sparse memory did not fit (then reset)
  // the last Jacobian's factors: sparse (restored with the pattern) or banded
  nw_.factorsValid = nw_.factorsValid && (nw_.sparseActive ? restored && nw_.sparse.hasFactors() : nw_.lu.size() > 0);
  ContactWorkspace& cw = ws_.contact;
  if (get<&ContactWorkspace::builtElements>(c.contact) == s_.elements() &&
      get<&ContactWorkspace::xBuilt>(c.contact).cols() == s_.nodes())
    restore(cw, c.contact);
  else
    cw.builds = get<&ContactWorkspace::builds>(c.contact);
}

SimulationCarry Simulation::carry() const {
  SimulationCarry c;
  c.progress = p_;
  c.newton = save(nw_);
  // the banded factors only where the next relaxation uses them (a checkpoint stays small)
  if (!(nw_.factorsValid && !nw_.sparseActive)) get<&NewtonWorkspace::lu>(c.newton) = BandLU{};
  const ContactWorkspace& cw = ws_.contact;
  if (cw.builtElements >= 0 && cw.xBuilt.cols() == cw.builtElements + 1) {
    c.contact = save(cw);
  } else {
    c.contact = save(ContactWorkspace{});
    get<&ContactWorkspace::builds>(c.contact) = cw.builds;
  }
  return c;
}

const StepRecord& Simulation::growthStep() {
  beginStep();
  return finishStep();
}

void Simulation::beginStep() {
  ++p_.step;
  const double dt = m_.growth.stepTime;
  // the kappa0 law reads the relaxed state of the previous step
  const RodStrains& k = ws_.strains;
  anchorMatureNodes(m_, s_);
  updateIntrinsicCurvature(m_, s_, k, dt);
  growRestLengths(m_, s_, dt);
  s_.time += dt;
  applyTwistProfile(m_, s_);
  open_ = Open{true, splitLongElements(m_, s_), 0, 0};
  nw_.coupledBlockDofs = -1;  // a plate's coupled Jacobian of an earlier step is not this step's
}

const StepRecord& Simulation::finishStep() {
  ROOTSIM_ASSERT(open_.open, "finishStep after beginStep");
  int unstable = 0;
  const RelaxResult r = relaxStable(p_.step, unstable);
  commitStep();
  p_.totalSubsteps += r.substeps;
  p_.totalIterations += r.iterations;
  observe(r, open_.splits, unstable);
  // what a plate's coupled or joint relaxation did before (already in the totals)
  p_.last.iterations += open_.iterations;
  p_.last.substeps += open_.substeps;
  open_ = Open{};
  return p_.last;
}

const StepRecord& Simulation::relaxAgain() {
  int unstable = 0;
  const RelaxResult r = relaxStable(p_.step, unstable);
  p_.totalSubsteps += r.substeps;
  p_.totalIterations += r.iterations;
  const StepRecord before = p_.last;
  observe(r, before.splits, before.unstable + unstable);
  p_.last.substeps += before.substeps;
  p_.last.iterations += before.iterations;
  return p_.last;
}

void Simulation::beginJoint() {
  joint_.emplace(m_.rod, m_.env, m_.solver, s_, ws_, windowStart());
}

bool Simulation::jointStep() {
  if (joint_->result().substeps >= m_.solver.maxSubsteps) {
    std::ostringstream os;
    os << "growth step " << p_.step << ": relaxing together with the roots it touches: " << joint_->describeFailure();
    throw RelaxError(os.str());
  }
  return joint_->step();
}

long Simulation::jointSubsteps() const { return joint_ ? joint_->result().substeps : 0; }

void Simulation::endJoint() {
  const long n = joint_->result().substeps;
  p_.totalSubsteps += n;
  (open_.open ? open_.substeps : p_.last.substeps) += n;
  joint_.reset();
}

CoupledRoot Simulation::coupled(int plateIndex) {
  return CoupledRoot{&m_.rod, &m_.env, &m_.solver, &s_, &ws_, &nw_, windowStart(), plateIndex};
}

void Simulation::addCoupled(const RelaxResult& r) {
  p_.totalIterations += r.iterations;
  (open_.open ? open_.iterations : p_.last.iterations) += r.iterations;
}

int Simulation::windowStart() {
  // the active window (docs/model.md, "Newton solver"): the growth zone, solver.window_mm of mature root behind
  // it, and the tip; the rest is adhered and frozen
  // (only where adhesion holds the mature root: a free organ or an unglued root has no frozen part)
  if (m_.solver.window <= 0.0 || !m_.growth.enabled || !m_.env.adhesion || !m_.env.plane.enabled) return 0;
  const double from = growthZoneStart(m_, s_) - m_.solver.window;
  int first = 0;
  while (first < s_.elements() - 2 && s_.S[first] < from) ++first;
  // and back to the oldest part that the window's part of a coil touches (or nearly): frozen turns
  // would not yield to the new ones. Turns that only older turns touch stay frozen: reaching back to the
  // oldest touch of all costs time for the same results (docs/numerics.md, "Active window")
  // other roots on a plate: back to the oldest element near one (the roots it presses on yield, as the
  // turns of a coil do)
  for (const auto& pr : ws_.contact.neighbours.pairs) first = std::min(first, pr[0]);
  return std::min(first, firstNodeNearContact(m_.rod, m_.env, s_, ws_.contact, first));
}

RelaxResult Simulation::newtonOrExplain(int step) {
  auto newton = [&] {
    try {
      return relaxNewton(m_.rod, m_.env, m_.solver, s_, ws_, nw_, windowStart());
    } catch (const RelaxError& e) {
      std::ostringstream os;
      os << "growth step " << step << " (t = " << s_.time / units::hour << " h, " << s_.elements()
         << " elements): " << e.what();
      throw RelaxError(os.str());
    }
  };
  start_ = s_;  // reuses its memory while the element count stays (scratch: not part of the state)
  RelaxResult r = newton();
  if (!r.stalled) return r;
  // no acceptable Newton step from here (far from equilibrium, indefinite): relax explicitly, then let
  // Newton confirm the equilibrium and check its stability. Where Newton wandered off (a node moved
  // more than the solver's length scale, as in a coiling snap, after which the explicit relaxation
  // slides away), the explicit relaxation starts again from where Newton started.
  const double Lref = m_.solver.lengthScale > 0.0 ? m_.solver.lengthScale : s_.restLength();
  auto restart = [&](const RelaxResult& failed) {
    if (failed.crawled || (s_.x - start_.x).colwise().norm().maxCoeff() > Lref) s_ = start_;
  };
  restart(r);
  // The explicit relaxation first moves the window only, the frozen part, twists included, staying
  // where it is: a growth step's snap happens inside the window, and Newton then solves the window and
  // the frozen twists together (the window's sub-steps cost a fraction of the whole rod's: docs/numerics.md,
  // "Fallback"). Where Newton still finds no equilibrium from there (the snap reached behind the window,
  // as on high-gain roots), the whole rod is relaxed explicitly.
  long its = r.iterations;
  const int window = windowStart();
  RelaxResult d = relaxOrExplain(m_, s_, ws_, step, window);
  r = newton();
  if (!r.converged && window > 0) {
    its += r.iterations;
    restart(r);
    d.substeps += relaxOrExplain(m_, s_, ws_, step, 0).substeps;
    r = newton();
  }
  if (!r.converged) {
    std::ostringstream os;
    os << "growth step " << step << " (t = " << s_.time / units::hour << " h, " << s_.elements()
       << " elements): after an explicit relaxation to equilibrium, Newton still finds none: " << r.message;
    throw RelaxError(os.str());
  }
  r.iterations += its;
  r.substeps += d.substeps;
  return r;
}

void Simulation::commitStep() {
  // friction is incremental: the stick points move once per growth step, at its equilibrium
  const FrictionCommit c = commitFriction(m_.rod, m_.env, s_, ws_.contact);
  p_.slipEvents += c.slips;
  p_.frictionWork += c.work;
}

RelaxResult Simulation::relaxStable(int step, int& unstable) {
  if (m_.solver.kind == SolverKind::Newton) return relaxNewtonStable(step, unstable);
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

RelaxResult Simulation::relaxNewtonStable(int step, int& unstable) {
  RelaxResult total = newtonOrExplain(step);
  if (!m_.solver.stabilityCheck || !m_.growth.enabled) return total;
  // stability from Newton's own factorisation; at a saddle, follow the unstable mode with a short
  // explicit relaxation to the stable branch, then let Newton confirm (as relaxStable does)
  const double amplitudes[] = {0.02, 0.1, 0.5};  // of R
  for (double a : amplitudes) {
    if (nw_.negative == 0) break;
    ++unstable;
    const Eigen::VectorXd mode = nw_.unstableMode(s_, m_.env);
    const int n = s_.elements();
    const double lean = s_.x(0, n) - s_.x(0, 0);
    const double tipMode = mode[6 * n];
    const double sign = (lean == 0.0 || tipMode == 0.0) ? 1.0 : (lean * tipMode > 0 ? 1.0 : -1.0);
    perturbAlong(s_, mode, sign * a * m_.rod.radius);
    const RelaxResult d = relaxOrExplain(m_, s_, ws_, step);
    const RelaxResult r = newtonOrExplain(step);
    total.substeps += d.substeps + r.substeps;
    total.iterations += r.iterations;
    total.residualForce = r.residualForce;
    total.residualTorque = r.residualTorque;
  }
  return total;
}

void Simulation::observe(const RelaxResult& res, int splits, int unstable) {
  // ws_.strains holds the strains of the relaxed state (computed at the last sub-step)
  computeStrains(m_.rod, s_, ws_.strains);
  StepRecord r;
  r.step = p_.step;
  r.timeH = s_.time / units::hour;
  r.length = s_.restLength();
  r.elements = s_.elements();
  const double th = tipAngle(m_, s_);
  if (p_.step == 0) p_.thetaUnwrapped = th;
  else p_.thetaUnwrapped += std::remainder(th - p_.thetaUnwrapped, 2.0 * std::numbers::pi);
  r.thetaTip = p_.thetaUnwrapped;
  if (m_.growth.enabled) r.zone = observeZone(m_, s_, ws_.strains);
  r.substeps = res.substeps;
  r.iterations = res.iterations;
  r.residualForce = res.residualForce;
  r.lowestEigenvalue = m_.solver.kind == SolverKind::Newton && m_.solver.stabilityCheck ? nw_.lowestEigenvalue : NAN;
  r.splits = splits;
  r.unstable = unstable;
  r.tip = s_.x.col(s_.nodes() - 1);
  if (m_.env.selfContact.enabled || !m_.env.obstacles.empty()) {
    const ContactCounts c = countContacts(m_.rod, m_.env, s_, observed_);
    r.selfContacts = c.selfContacts;
    r.minSelfDistance = c.minSelfDistance;
    r.obstacleContacts = c.obstacleContacts;
  }
  r.slipEvents = p_.slipEvents;
  r.frictionWork = p_.frictionWork;
  p_.last = r;
}

Snapshot Simulation::snapshot() const {
  Snapshot sn = makeSnapshot(m_.rod, s_, ws_.strains, p_.step);
  sn.timeH = s_.time / units::hour;
  sn.plateForce = plateNormalForce(m_.rod, m_.env.plane, s_);
  sn.contactForce = observeContacts(m_.rod, m_.env, s_).perNode;
  return sn;
}

}  // namespace rootsim
