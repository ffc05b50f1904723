// Explicit damped relaxation (docs/model.md, Relaxation; relax_dynamic.hpp).
//
// One sub-step, in this fixed order (position Verlet, as ref. 37 / PyElastica), each a short function:
//   1. drift       x += h v, Q <- exp(-h [w]x) Q  (h = dt/2; merged with the previous sub-step's
//                  closing half drift, the leapfrog form of position Verlet)
//   2. strains     shear/stretch and bend/twist of the mid-step configuration        (rod.cpp)
//   3. internal    forces and couples from the strains                               (rod.cpp)
//   4. external    plate contact, obstacles, self-contact, friction, adhesion, weight, clamp couple, tip
//                  loads, each a piece (environment.cpp, contact.cpp)
//   5. constraints the clamped base holds node 0: its force is a reaction and is removed (the one place
//                  the clamp acts on motion; node 0's velocity then stays zero through kick and drift)
//   6. residual    largest force, couple and speed; finiteness; stop if in equilibrium; every
//                  kSlideCheckEvery sub-steps, a node sliding away (no static equilibrium) is an error
//   7. damping     FIRE's power test (or the viscous factor)
//   8. kick        v += dt F/m, w += dt tau/J, mixed toward the force direction by FIRE
//   9. half drift, deferred to the next sub-step (a converged state is the one forces were checked at)
//
// Only the equilibrium matters, so the masses are fictitious by default ("scaled"): each degree of
// freedom gets a mass proportional to a bound on its stiffness (row sum of the stiffness matrix with
// translations and rotations put in comparable units), which equalises the stability limit of every dof
// at dt = 1 (dynamic relaxation, Underwood 1983). FIRE (Bitzek et al., PRL 97, 170201, 2006) then
// removes kinetic energy: velocities are mixed toward the force direction while the power F.v stays
// positive and zeroed when it turns negative. The paper's physical masses (density, dt from the stiffest
// spring) and PyElastica-style viscous damping remain available as options.
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "rootsim/assert.hpp"
#include "rootsim/forces.hpp"
#include "rootsim/relax_dynamic.hpp"
#include "rootsim/tolerance.hpp"
#include "rootsim/rotation.hpp"

namespace rootsim {

namespace {

constexpr double kMassSafety = 2.0;
constexpr long kSlideCheckEvery = 512;  // sub-steps between checks for a node sliding away  // scaled masses m = kMassSafety * k / 4: omega dt <= sqrt(2) < 2

// FIRE constants (Bitzek et al. 2006, Table I)
constexpr int kFireNmin = 5;
constexpr double kFireInc = 1.1, kFireDec = 0.5, kFireAlpha0 = 0.1, kFireAlphaDec = 0.99;

// stiffness bound of every dof: kx per node [N/m], kth per element and material axis [N m/rad].
// One element with shear/stretch stiffness S and rest length l couples its two nodes (S/l each) and its
// rotation (S l for d1, d2); a Voronoi domain couples its two elements' rotations (B/D0 each).
void stiffnessBounds(const RodParams& p, const Environment& env, const RodState& s,
                     Eigen::VectorXd& kx, Eigen::Matrix3Xd& kth) {
  const int n = s.elements();
  const Vec3 Sd = p.shearStiffness(), Bd = p.bendStiffness();
  const double Smax = Sd.maxCoeff();
  kx.setZero();
  kth.setZero();
  for (int i = 0; i < n; ++i) {
    const double l = s.l0[i];
    const double kt = (2.0 * Smax + Sd.x()) / l;
    kx[i] += kt;
    kx[i + 1] += kt;
    kth(0, i) += 3.0 * Sd.x() * l;
    kth(1, i) += 3.0 * Sd.y() * l;
    if (env.plane.enabled) {
      kx[i] += 0.5 * env.plane.k;
      kx[i + 1] += 0.5 * env.plane.k;
    }
  }
  // friction's stick springs and obstacle contact (stiffness plane.k each) where they may act. Self-
  // contact is not added, so that a run without contacts keeps its masses, and its results, to the bit:
  // its 1e4 N/m per pair is below the stretch bound that dominates kx (2 (2 Smax + S1) / l = 1.8e5 N/m
  // per node for the paper's root at h = 0.05 mm, 9e4 at 0.1 mm), and scaled masses m = kx / 2 stay
  // stable (omega dt = sqrt(2 (1 + k_contact / kx)) < 2) while a node carries less than kx of contact
  // stiffness, i.e. up to 9 (h = 0.1 mm: 18) pairs at once.
  const bool obstacles = !env.obstacles.empty();
  const double kContact = env.plane.k * ((env.friction.enabled ? 1.0 : 0.0) + (obstacles ? 1.0 : 0.0) +
                                         (env.friction.enabled && obstacles ? 1.0 : 0.0));
  if (kContact > 0.0) kx.array() += kContact;
  for (int j = 0; j + 1 < n; ++j) {
    const double D0 = 0.5 * (s.l0[j] + s.l0[j + 1]);
    const Vec3 kb = 2.0 * Bd / D0;
    kth.col(j) += kb;
    kth.col(j + 1) += kb;
  }
  if (env.base == BaseCondition::Clamped) kth.col(0) += 2.0 * Bd / (0.5 * s.l0[0]);
  if (env.adhesion)
    for (int i = 0; i <= n; ++i)
      if (s.anchored[static_cast<size_t>(i)]) kx[i] += env.kAdhesion;
  // a dof with no stiffness of its own (twist of a single element) borrows the smallest positive one
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      if (kth(a, i) <= 0.0) kth(a, i) = kth.col(i).maxCoeff();
}

// masses and sub-step for the chosen mass model; returns dt
double setMasses(const RodParams& p, const Environment& env, const SolverOptions& opt,
                 const RodState& s, RelaxWorkspace& ws) {
  const int n = s.elements();
  stiffnessBounds(p, env, s, ws.mass, ws.inertia);  // stiffness first, turned into masses below
  if (opt.mass == MassModel::Scaled) {
    ws.mass *= kMassSafety / 4.0;
    ws.inertia *= kMassSafety / 4.0;
    return 1.0;
  }
  const double A = std::numbers::pi * p.radius * p.radius;
  const double I = 0.25 * std::numbers::pi * std::pow(p.radius, 4);
  double dt = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    const double lsum = (i > 0 ? s.l0[i - 1] : 0.0) + (i < n ? s.l0[i] : 0.0);
    const double m = 0.5 * p.density * A * lsum;
    dt = std::min(dt, 2.0 * std::sqrt(m / ws.mass[i]));
    ws.mass[i] = m;
  }
  for (int i = 0; i < n; ++i) {
    const Vec3 J = p.density * I * s.l0[i] * Vec3(1.0, 1.0, 2.0);
    for (int a = 0; a < 3; ++a) dt = std::min(dt, 2.0 * std::sqrt(J[a] / ws.inertia(a, i)));
    ws.inertia.col(i) = J;
  }
  return opt.cfl * dt;
}

// restores orthonormal directors (round-off drift over millions of rotations), outside the sub-step
void reorthonormalise(RodState& s) {
  for (Mat3& Q : s.Q) {
    Vec3 d3 = Q.row(2).transpose().normalized();
    Vec3 d1 = Q.row(0).transpose();
    d1 = (d1 - d1.dot(d3) * d3).normalized();
    Q.row(0) = d1.transpose();
    Q.row(1) = d3.cross(d1).transpose();
    Q.row(2) = d3.transpose();
  }
}

[[noreturn]] void failNonFinite(long step, const char* what, int index, const Vec3& val) {
  std::ostringstream os;
  os << "relaxation diverged at sub-step " << step << ": " << what << " " << index
     << " is not finite (" << val.transpose() << ")";
  throw RelaxError(os.str());
}

}  // namespace

DynamicRelaxation::DynamicRelaxation(const RodParams& p, const Environment& env,
                                     const SolverOptions& opt, RodState& s, RelaxWorkspace& ws,
                                     int firstFreeNode)
    : p_(p), env_(env), opt_(opt), s_(s), ws_(ws) {
  const int n = s.elements();
  if (n < 2) throw RelaxError("relaxation needs at least 2 elements");
  ROOTSIM_ASSERT(firstFreeNode >= 0 && firstFreeNode <= n, "a window inside the rod");
  free_ = std::min(firstFreeNode, n - 1);
  const int first = std::max(0, free_ - 1);
  span_ = ForceSpan{first, -1, first};
  if (ws.force.cols() != n + 1) ws.resize(n);
  reorthonormalise(s);
  s.v.setZero();
  s.w.setZero();
  // tolerances relative to the rod's elastic scale and the applied loads (relax.hpp: equilibriumTolerance)
  const double Lref = opt.lengthScale > 0.0 ? opt.lengthScale : s.restLength();
  const EquilibriumTolerance tol = equilibriumTolerance(p, env, opt, s, free_);
  ftol2_ = std::pow(tol.force, 2);
  mtol2_ = std::pow(tol.couple, 2);
  xtol_ = opt.speedTol * p.radius;  // displacement per sub-step [m]
  rtol_ = opt.speedTol;             // rotation per sub-step [rad]
  dtMax_ = setMasses(p, env, opt, s, ws);
  ws.invMass = ws.mass.cwiseInverse();
  ws.invInertia = ws.inertia.cwiseInverse();
  ws.xStart = s.x;
  slideLimit_ = kSlideLengths * Lref;
  dt_ = dtMax_;
  alpha_ = kFireAlpha0;
  viscousFactor_ = std::exp(-opt.viscousRate * dtMax_);
}

bool DynamicRelaxation::step() {
  ++res_.substeps;
  if (pendingDrift_ > 0.0) drift(pendingDrift_ + 0.5 * dt_);        // 1. (and 9. of the previous sub-step)
  pendingDrift_ = 0.0;
  computeForces(p_, env_, s_, opt_.mass == MassModel::Physical, ws_, span_);  // 2. - 5.
  if (inEquilibrium()) {                                               // 6.
    s_.v.setZero();
    s_.w.setZero();
    return true;
  }
  if (res_.substeps % kSlideCheckEvery == 0) checkSliding();
  if (opt_.damping == Damping::Fire) {
    const FirePowers pw = firePowers();
    fireDamping(pw.P);                                                 // 7.
    fireKick(pw);                                                      // 8.
  } else {
    viscousKick();                                                     // 7. + 8.
  }
  pendingDrift_ = 0.5 * dt_;                                           // 9.
  return false;
}

void DynamicRelaxation::drift(double h) {
  RodState& s = s_;
  for (int i = free_; i < s.nodes(); ++i) s.x.col(i) += h * s.v.col(i);
  for (int i = free_; i < s.elements(); ++i) rotateInPlace(-h * Vec3(s.w.col(i)), s.Q[static_cast<size_t>(i)]);
}

bool DynamicRelaxation::inEquilibrium() {
  const RodState& s = s_;
  const RelaxWorkspace& ws = ws_;
  const int n = s.elements();
  double maxF2 = 0, maxM2 = 0, maxV2 = 0, maxW2 = 0;
  for (int i = free_; i <= n; ++i) {
    const double f2 = ws.force.col(i).squaredNorm();
    if (!std::isfinite(f2)) failNonFinite(res_.substeps, "force on node", i, ws.force.col(i));
    if (f2 > maxF2) { maxF2 = f2; argF_ = i; }
    maxV2 = std::max(maxV2, s.v.col(i).squaredNorm());
  }
  for (int i = free_; i < n; ++i) {
    const double m2 = ws.torque.col(i).squaredNorm();
    if (!std::isfinite(m2)) failNonFinite(res_.substeps, "couple on element", i, ws.torque.col(i));
    if (m2 > maxM2) { maxM2 = m2; argM_ = i; }
    maxW2 = std::max(maxW2, s.w.col(i).squaredNorm());
  }
  res_.residualForce = std::sqrt(maxF2);
  res_.residualTorque = std::sqrt(maxM2);
  res_.maxSpeed = std::sqrt(maxV2);
  res_.dt = dt_;
  return maxF2 < ftol2_ && maxM2 < mtol2_ && maxV2 * dtMax_ * dtMax_ < xtol_ * xtol_ &&
         maxW2 * dtMax_ * dtMax_ < rtol_ * rtol_;
}

void DynamicRelaxation::checkSliding() const {
  double far2 = 0;
  int arg = 0;
  for (int i = free_; i < s_.nodes(); ++i) {
    const double d2 = (s_.x.col(i) - ws_.xStart.col(i)).squaredNorm();
    if (d2 > far2) { far2 = d2; arg = i; }
  }
  if (far2 <= slideLimit_ * slideLimit_) return;
  std::ostringstream os;
  os << "node " << arg << " slides: no static equilibrium (it moved " << std::sqrt(far2) * 1e3
     << " mm within one relaxation, more than " << kSlideLengths << " Lref = " << slideLimit_ * 1e3
     << " mm, after " << res_.substeps << " sub-steps; the loads exceed what friction, the plate and "
     << "the supports can hold)";
  throw RelaxError(os.str());
}

DynamicRelaxation::FirePowers DynamicRelaxation::firePowers() const {
  // the power F.v and the mass-weighted |v|^2 (u = sqrt(m) v) and |F|^2 (g = F / sqrt(m)) FIRE mixes with
  const RodState& s = s_;
  const RelaxWorkspace& ws = ws_;
  FirePowers pw;
  for (int i = free_; i < s.nodes(); ++i) {
    pw.P += ws.force.col(i).dot(s.v.col(i));
    pw.vm2 += ws.mass[i] * s.v.col(i).squaredNorm();
    pw.fm2 += ws.invMass[i] * ws.force.col(i).squaredNorm();
  }
  for (int i = free_; i < s.elements(); ++i) {
    pw.P += ws.torque.col(i).dot(s.w.col(i));
    pw.vm2 += ws.inertia.col(i).dot(s.w.col(i).cwiseAbs2());
    pw.fm2 += ws.invInertia.col(i).dot(ws.torque.col(i).cwiseAbs2());
  }
  return pw;
}

void DynamicRelaxation::fireDamping(double P) {
  // FIRE (Bitzek et al. 2006): while the power stays positive, grow the step and lessen the mixing;
  // when it turns negative, stop (zero velocities), halve the step and restart the mixing
  if (P > 0.0) {
    if (++npos_ > kFireNmin) {
      dt_ = std::min(dt_ * kFireInc, dtMax_);
      alpha_ *= kFireAlphaDec;
    }
  } else {
    npos_ = 0;
    dt_ *= kFireDec;
    alpha_ = kFireAlpha0;
    s_.v.setZero();
    s_.w.setZero();
  }
}

void DynamicRelaxation::fireKick(FirePowers pw) {
  // kick v' = v + dt F/m, then mix v'' = (1 - alpha) v' + alpha |v'| F^ in mass-weighted coordinates;
  // |v'|^2 = |v|^2 + 2 dt F.v + dt^2 |F|^2 exactly, so both fold into
  // v'' = (1 - alpha) v + ((1 - alpha) dt + c) F/m with c = alpha |v'| / |g|
  RodState& s = s_;
  const RelaxWorkspace& ws = ws_;
  if (npos_ == 0) pw.vm2 = pw.P = 0.0;  // FIRE just stopped the motion
  const double dt = dt_;
  const double vm2Kicked = std::max(0.0, pw.vm2 + 2.0 * dt * pw.P + dt * dt * pw.fm2);
  const double c = pw.fm2 > 0.0 ? alpha_ * std::sqrt(vm2Kicked / pw.fm2) : 0.0;
  const double keep = 1.0 - alpha_, gain = keep * dt + c;
  for (int i = free_; i < s.nodes(); ++i) s.v.col(i) = keep * s.v.col(i) + (gain * ws.invMass[i]) * ws.force.col(i);
  for (int i = free_; i < s.elements(); ++i)
    s.w.col(i) = keep * s.w.col(i) + gain * ws.torque.col(i).cwiseProduct(ws.invInertia.col(i));
}

void DynamicRelaxation::viscousKick() {
  RodState& s = s_;
  const RelaxWorkspace& ws = ws_;
  const double dt = dt_;
  for (int i = free_; i < s.nodes(); ++i)
    s.v.col(i) = viscousFactor_ * (s.v.col(i) + (dt * ws.invMass[i]) * ws.force.col(i));
  for (int i = free_; i < s.elements(); ++i)
    s.w.col(i) = viscousFactor_ * (s.w.col(i) + dt * ws.torque.col(i).cwiseProduct(ws.invInertia.col(i)));
}

std::string DynamicRelaxation::describeFailure() const {
  std::ostringstream os;
  os << "relaxation did not reach equilibrium in " << res_.substeps << " sub-steps: residual force "
     << res_.residualForce << " N at node " << argF_ << " (tolerance " << std::sqrt(ftol2_)
     << "), residual couple " << res_.residualTorque << " N m on element " << argM_ << " (tolerance "
     << std::sqrt(mtol2_) << "), max node speed " << res_.maxSpeed << " m/s";
  return os.str();
}

RelaxResult relax(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                  RelaxWorkspace& ws, int firstFreeNode) {
  DynamicRelaxation r(p, env, opt, s, ws, firstFreeNode);
  while (r.result().substeps < opt.maxSubsteps)
    if (r.step()) return r.result();
  throw RelaxError(r.describeFailure());
}

}  // namespace rootsim
