#pragma once
// Mechanical relaxation to equilibrium (docs/model.md, Relaxation): what every solver takes (the options),
// gives back (the result, the error) and works in (the scratch of the force evaluation). The solvers have
// their own headers: relax_dynamic.hpp (explicit), relax_newton.hpp (Newton); the forces they share:
// forces.hpp; their equilibrium criterion: tolerance.hpp.
#include <stdexcept>
#include <string>

#include "rootsim/contact.hpp"
#include "rootsim/rod.hpp"

namespace rootsim {

// which solver brings a growth step to equilibrium
enum class SolverKind {
  Dynamic,   // the paper's: explicit damped pseudo-dynamics (relax_dynamic.cpp)
  Newton     // quasi-static Newton on the equilibrium equations, banded Jacobian (relax_newton.cpp)
};

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
  // Newton is the default: it agrees with the paper's explicit relaxation on the paper's scenes at a
  // fraction of its CPU (docs/performance.md, "The two solvers on the paper's scenes")
  SolverKind kind = SolverKind::Newton;
  // Newton: the unknowns are the nodes within this rest length behind the growth zone's start, everything
  // tipward, the oldest part a self-contact touches onward, and the twist of every element before (the
  // adhered mature root keeps its positions, not its twist, which carries the clamp's torque) [m]; 0: the
  // whole rod. Checked against the whole rod (docs/numerics.md, "Active window"): a narrower window
  // freezes adhered nodes too near the growth zone and changes the high-gain roots' amplitude; only
  // where adhesion holds the mature root
  double window = 6e-3;
  int newtonMaxIterations = 30;   // Newton iterations before a relaxation continues explicitly
  // Newton's Jacobian in closed form (stiffness.hpp) wherever it covers the forces in play; false:
  // coloured central differences of the forces everywhere (tests compare the two)
  bool closedFormStiffness = true;
  MassModel mass = MassModel::Scaled;
  Damping damping = Damping::Fire;
  double viscousRate = 2e4;       // nu for Damping::Viscous [1/s]
  double cfl = 0.9;               // fraction of the stability limit used for dt (physical masses)
  double forceTol = 1e-4;         // residual force and couple relative to the load scale of
                                  // equilibriumTolerance (below): B1/Lref^2 and B1/Lref, or the applied
                                  // loads where they are smaller
  double speedTol = 1e-5;         // max node displacement per sub-step / R, and rotation per sub-step [rad]
  long maxSubsteps = 2000000;     // cap per relaxation; hitting it is an error
  double lengthScale = 0.0;       // Lref [m]; 0 means the rod's rest length (set by completeModel)
  bool stabilityCheck = true;     // growth runs: check each equilibrium's stability, follow unstable modes
};

struct RelaxResult {
  long substeps = 0;              // explicit sub-steps
  long iterations = 0;            // Newton iterations
  bool converged = false;         // Newton: reached the equilibrium criterion
  bool stalled = false;           // Newton: no acceptable step, or the iteration cap (the caller relaxes
                                  // explicitly); message says which
  bool crawled = false;           // Newton: stalled because its steps were damped to a crawl (the caller
                                  // relaxes explicitly from where Newton started)
  std::string message;
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
  Eigen::Matrix3Xd xStart;     // node positions when the relaxation started (3 x n+1) [m]
  ContactWorkspace contact;    // scratch of the contact pieces (self-contact list, obstacle forces)
  void resize(int n);
};

}  // namespace rootsim
