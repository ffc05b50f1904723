#pragma once
// Mechanical relaxation to equilibrium (MODEL.md section 7): the options and result of every solver, the
// explicit solver (DynamicRelaxation, relax_dynamic.cpp) and the force evaluation it shares with the
// stability check (stability.cpp). One header for the concept "relaxation"; one source per solver.
#include "rootsim/environment.hpp"
#include <stdexcept>
#include <string>

namespace rootsim {

// how fictitious masses are chosen
enum class MassModel {
  Physical,  // the paper's: density 1000 kg/m^3, dt from the stiffest spring
  Scaled     // dynamic relaxation: per-dof mass proportional to its stiffness, dt = 1 (Underwood 1983)
};
// how kinetic energy is removed
enum class Damping {
  Viscous,   // v *= exp(-nu dt), as PyElastica's analytical linear damper
  Fire       // FIRE (Bitzek et al. 2006, with Guenole et al. 2020 tweaks), mass-weighted
};

struct SolverOptions {
  MassModel mass = MassModel::Scaled;
  Damping damping = Damping::Fire;
  double viscousRate = 2e4;       // nu for Damping::Viscous [1/s]
  double cfl = 0.9;               // fraction of the stability limit used for dt (physical masses)
  double forceTol = 1e-4;         // residual force / (B1/Lref^2), residual torque / (B1/Lref)
  double speedTol = 1e-5;         // max node displacement per sub-step / R, and rotation per sub-step [rad]
  long maxSubsteps = 2000000;     // cap per relaxation; hitting it is an error
  double lengthScale = 0.0;       // Lref [m]; 0 means the rod's rest length (set by completeModel)
  bool stabilityCheck = true;     // growth runs: check each equilibrium's stability, follow unstable modes
};

struct RelaxResult {
  long substeps = 0;
  double residualForce = 0;       // max over free nodes [N]
  double residualTorque = 0;      // max over free elements [N m]
  double maxSpeed = 0;            // max node speed at exit [m/s]
  double dt = 0;                  // last sub-step [s] (pseudo-time when mass is scaled)
};

// a relaxation that diverged or did not converge; what() names the sub-step, the node or element and
// the quantity
class RelaxError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// scratch memory for relax(); sized once per element count so the sub-step never allocates
struct RelaxWorkspace {
  RodStrains strains;
  Eigen::Matrix3Xd force;      // (3 x n+1) lab [N]
  Eigen::Matrix3Xd torque;     // (3 x n) material [N m]
  Eigen::VectorXd mass;        // node masses (n+1) [kg]
  Eigen::Matrix3Xd inertia;    // element inertia per material axis (3 x n) [kg m^2]
  Eigen::VectorXd invMass;     // 1 / mass (n+1)
  Eigen::Matrix3Xd invInertia; // 1 / inertia (3 x n)
  void resize(int n);
};

// the relaxation loop, one sub-step at a time (relax() runs it to the end); holds references to its
// arguments, which must outlive it
class DynamicRelaxation {
 public:
  DynamicRelaxation(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                    RelaxWorkspace& ws);
  // one sub-step; true when the state is in equilibrium (velocities are then zeroed); throws
  // RelaxError when a force or couple is not finite. Allocates nothing.
  bool step();
  const RelaxResult& result() const { return res_; }
  std::string describeFailure() const;

 private:
  // the pieces of one sub-step, in the order step() runs them (relax_dynamic.cpp's header lists it)
  struct FirePowers { double P = 0, vm2 = 0, fm2 = 0; };
  static void drift(RodState& s, double h);
  bool inEquilibrium();
  FirePowers firePowers() const;
  void fireDamping(double P);
  void fireKick(FirePowers pw);
  void viscousKick();

  const RodParams& p_;
  const Environment& env_;
  const SolverOptions& opt_;
  RodState& s_;
  RelaxWorkspace& ws_;
  double ftol2_ = 0, mtol2_ = 0, xtol_ = 0, rtol_ = 0;
  double dtMax_ = 0, dt_ = 0, pendingDrift_ = 0, alpha_ = 0, viscousFactor_ = 1;
  int npos_ = 0, argF_ = 0, argM_ = 0;
  RelaxResult res_;
};

// relaxes the rod to equilibrium under env; throws RelaxError on divergence or on hitting the cap
RelaxResult relax(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                  RelaxWorkspace& ws);

// evaluates all forces of state s into ws.force / ws.torque (used by relax and by tests)
void computeForces(const RodParams& p, const Environment& env, const RodState& s, bool planeDamping,
                   RelaxWorkspace& ws);

}  // namespace rootsim
