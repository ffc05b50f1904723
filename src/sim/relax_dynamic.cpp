// Explicit damped relaxation (MODEL.md section 7, first bullet).
//
// One sub-step, in this fixed order (position Verlet, as ref. 37 / PyElastica):
//   1. half drift: x += h v, Q <- exp(-h [w]x) Q  (h = dt/2; merged with the previous sub-step's
//      closing half drift, the leapfrog form of position Verlet)
//   2. strains -> internal forces -> contact, adhesion, loads  (at the mid-step configuration)
//   3. residuals and finiteness; stop if in equilibrium
//   4. damping decision (FIRE power test) and kick: v += dt F/m, w += dt tau/J
//   5. half drift (deferred)
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

#include "rootsim/relax.hpp"
#include "rootsim/rotation.hpp"

namespace rootsim {

namespace {

constexpr double kMassSafety = 2.0;  // scaled masses m = kMassSafety * k / 4: omega dt <= sqrt(2) < 2

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

void drift(const Environment& env, RodState& s, double h) {
  const int n = s.elements();
  const int first = env.base == BaseCondition::Clamped ? 1 : 0;
  for (int i = first; i <= n; ++i) s.x.col(i) += h * s.v.col(i);
  for (int i = 0; i < n; ++i) {
    rotateInPlace(-h * Vec3(s.w.col(i)), s.Q[static_cast<size_t>(i)]);
  }
}

[[noreturn]] void failNonFinite(long step, const char* what, int index, const Vec3& val) {
  std::ostringstream os;
  os << "relaxation diverged at sub-step " << step << ": " << what << " " << index
     << " is not finite (" << val.transpose() << ")";
  throw RelaxError(os.str());
}

}  // namespace

void RelaxWorkspace::resize(int n) {
  strains.resize(n);
  force.resize(3, n + 1);
  torque.resize(3, n);
  mass.resize(n + 1);
  inertia.resize(3, n);
  invMass.resize(n + 1);
  invInertia.resize(3, n);
}

void computeForces(const RodParams& p, const Environment& env, const RodState& s, bool planeDamping,
                   RelaxWorkspace& ws) {
  if (ws.force.cols() != s.nodes()) ws.resize(s.elements());
  computeStrains(p, s, ws.strains);
  computeInternalForces(s, ws.strains, ws.force, ws.torque);
  addExternalForces(p, env, s, ws.strains, planeDamping, ws.force, ws.torque);
  if (env.base == BaseCondition::Clamped) {
    ws.force.col(0).setZero();
  }
}

DynamicRelaxation::DynamicRelaxation(const RodParams& p, const Environment& env,
                                     const SolverOptions& opt, RodState& s, RelaxWorkspace& ws)
    : p_(p), env_(env), opt_(opt), s_(s), ws_(ws) {
  const int n = s.elements();
  if (n < 2) throw RelaxError("relaxation needs at least 2 elements");
  if (ws.force.cols() != n + 1) ws.resize(n);
  reorthonormalise(s);
  s.v.setZero();
  s.w.setZero();
  // tolerances from the rod's own scale: B1 / Lref^2 for forces, B1 / Lref for couples
  const double B1 = p.bendStiffness().x();
  const double Lref = opt.lengthScale > 0.0 ? opt.lengthScale : s.restLength();
  ftol2_ = std::pow(opt.forceTol * B1 / (Lref * Lref), 2);
  mtol2_ = std::pow(opt.forceTol * B1 / Lref, 2);
  xtol_ = opt.speedTol * p.radius;  // displacement per sub-step [m]
  rtol_ = opt.speedTol;             // rotation per sub-step [rad]
  dtMax_ = setMasses(p, env, opt, s, ws);
  ws.invMass = ws.mass.cwiseInverse();
  ws.invInertia = ws.inertia.cwiseInverse();
  dt_ = dtMax_;
  alpha_ = kFireAlpha0;
  viscousFactor_ = std::exp(-opt.viscousRate * dtMax_);
}

bool DynamicRelaxation::step() {
  RodState& s = s_;
  RelaxWorkspace& ws = ws_;
  const int n = s.elements();
  const bool fire = opt_.damping == Damping::Fire;
  const long step = ++res_.substeps;
  // 1. drift: the closing half drift of the previous sub-step and the opening half drift of this one,
  //    merged (leapfrog form of position Verlet; halves the director rotations)
  if (pendingDrift_ > 0.0) drift(env_, s, pendingDrift_ + 0.5 * dt_);
  pendingDrift_ = 0.0;
  // 2. forces at the mid-step configuration
  computeForces(p_, env_, s, opt_.mass == MassModel::Physical, ws);
  // 3. residuals, power, finiteness; also the mass-weighted |v|^2 and |F|^2 that FIRE mixes with
  double maxF2 = 0, maxM2 = 0, maxV2 = 0, maxW2 = 0, P = 0, vm2 = 0, fm2 = 0;
  for (int i = 0; i <= n; ++i) {
    const double f2 = ws.force.col(i).squaredNorm();
    if (!std::isfinite(f2)) failNonFinite(step, "force on node", i, ws.force.col(i));
    if (f2 > maxF2) { maxF2 = f2; argF_ = i; }
    const double v2 = s.v.col(i).squaredNorm();
    maxV2 = std::max(maxV2, v2);
    P += ws.force.col(i).dot(s.v.col(i));
    vm2 += ws.mass[i] * v2;
    fm2 += ws.invMass[i] * f2;
  }
  for (int i = 0; i < n; ++i) {
    const double m2 = ws.torque.col(i).squaredNorm();
    if (!std::isfinite(m2)) failNonFinite(step, "couple on element", i, ws.torque.col(i));
    if (m2 > maxM2) { maxM2 = m2; argM_ = i; }
    maxW2 = std::max(maxW2, s.w.col(i).squaredNorm());
    P += ws.torque.col(i).dot(s.w.col(i));
    vm2 += ws.inertia.col(i).dot(s.w.col(i).cwiseAbs2());
    fm2 += ws.invInertia.col(i).dot(ws.torque.col(i).cwiseAbs2());
  }
  res_.residualForce = std::sqrt(maxF2);
  res_.residualTorque = std::sqrt(maxM2);
  res_.maxSpeed = std::sqrt(maxV2);
  res_.dt = dt_;
  if (maxF2 < ftol2_ && maxM2 < mtol2_ && maxV2 * dtMax_ * dtMax_ < xtol_ * xtol_ &&
      maxW2 * dtMax_ * dtMax_ < rtol_ * rtol_) {
    s.v.setZero();
    s.w.setZero();
    return true;
  }
  // 4. damping decision and kick, in one pass
  if (fire) {
    if (P > 0.0) {
      if (++npos_ > kFireNmin) {
        dt_ = std::min(dt_ * kFireInc, dtMax_);
        alpha_ *= kFireAlphaDec;
      }
    } else {
      npos_ = 0;
      dt_ *= kFireDec;
      alpha_ = kFireAlpha0;
      s.v.setZero();
      s.w.setZero();
      vm2 = 0.0;
      P = 0.0;
    }
  }
  const double dt = dt_;
  if (fire) {
    // kick v' = v + dt F/m, then mix v'' = (1 - alpha) v' + alpha |v'| F^ in mass-weighted coordinates
    // (u = sqrt(m) v, g = F / sqrt(m)); |v'|^2 = |v|^2 + 2 dt F.v + dt^2 |F|^2 exactly, so both fold
    // into v'' = (1 - alpha) v + ((1 - alpha) dt + c) F/m with c = alpha |v'| / |g|
    const double vm2Kicked = std::max(0.0, vm2 + 2.0 * dt * P + dt * dt * fm2);
    const double c = fm2 > 0.0 ? alpha_ * std::sqrt(vm2Kicked / fm2) : 0.0;
    const double keep = 1.0 - alpha_, gain = keep * dt + c;
    for (int i = 0; i <= n; ++i) s.v.col(i) = keep * s.v.col(i) + (gain * ws.invMass[i]) * ws.force.col(i);
    for (int i = 0; i < n; ++i)
      s.w.col(i) = keep * s.w.col(i) + gain * ws.torque.col(i).cwiseProduct(ws.invInertia.col(i));
  } else {
    for (int i = 0; i <= n; ++i)
      s.v.col(i) = viscousFactor_ * (s.v.col(i) + (dt * ws.invMass[i]) * ws.force.col(i));
    for (int i = 0; i < n; ++i)
      s.w.col(i) = viscousFactor_ * (s.w.col(i) + dt * ws.torque.col(i).cwiseProduct(ws.invInertia.col(i)));
  }
  if (env_.base == BaseCondition::Clamped) s.v.col(0).setZero();
  // 5. half drift, deferred to the next sub-step (a converged state is the one forces were checked at)
  pendingDrift_ = 0.5 * dt;
  return false;
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
                  RelaxWorkspace& ws) {
  DynamicRelaxation r(p, env, opt, s, ws);
  while (r.result().substeps < opt.maxSubsteps)
    if (r.step()) return r.result();
  throw RelaxError(r.describeFailure());
}

}  // namespace rootsim
