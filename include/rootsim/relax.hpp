#pragma once
// Mechanical relaxation to equilibrium (docs/model.md, Relaxation): the options and result of every solver,
// the explicit solver (DynamicRelaxation, relax_dynamic.cpp) and the force evaluation it shares with the
// stability check (stability.cpp). One header for the concept "relaxation"; one source per solver.
#include "rootsim/contact.hpp"
#include <stdexcept>
#include <string>
#include <vector>

#include "rootsim/band.hpp"
#include "rootsim/environment.hpp"

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
  // Newton is the default: it agrees with the paper's explicit relaxation on the paper's scenes (README,
  // scripts/compare-solvers.sh) at 6-15 times less CPU
  SolverKind kind = SolverKind::Newton;
  // Newton: the unknowns are the nodes within this rest length behind the growth zone's start, everything
  // tipward, the oldest part a self-contact touches onward, and the twist of every element before (the
  // adhered mature root keeps its positions, not its twist, which carries the clamp's torque) [m]; 0: the
  // whole rod. Measured against the whole rod (README): fig2b's lambda, A and theta_tip, fig4a's skew
  // and tip angle agree to 1e-5 relative, and so do the high-gain Fig. 3 roots (beta 0.5 and 1) that a
  // 3 mm window got wrong (A 55 % too large at alpha 20, beta 0.5: the frozen adhered nodes stand too
  // near the growth zone), at 0.75x the cost on fig2b; only where adhesion holds the mature root
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

// the relaxation loop, one sub-step at a time (relax() runs it to the end); holds references to its
// arguments, which must outlive it
class DynamicRelaxation {
 public:
  // firstFreeNode > 0: only the nodes and elements from there on move (the rest, twists included,
  // stays exactly), and the equilibrium criterion covers those only: the Newton solver's fallback
  // relaxes its window so (the explicit solver proper relaxes the whole rod)
  DynamicRelaxation(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                    RelaxWorkspace& ws, int firstFreeNode = 0);
  // one sub-step; true when the state is in equilibrium (velocities are then zeroed); throws
  // RelaxError when a force or couple is not finite, or when a node slides without bound (no static
  // equilibrium: it moved more than kSlideLengths * Lref within the relaxation). Allocates nothing.
  bool step();
  const RelaxResult& result() const { return res_; }
  std::string describeFailure() const;

 private:
  // the pieces of one sub-step, in the order step() runs them (relax_dynamic.cpp's header lists it)
  struct FirePowers { double P = 0, vm2 = 0, fm2 = 0; };
  void drift(double h);
  bool inEquilibrium();
  void checkSliding() const;
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
  double dtMax_ = 0, dt_ = 0, pendingDrift_ = 0, alpha_ = 0, viscousFactor_ = 1, slideLimit_ = 0;
  int npos_ = 0, argF_ = 0, argM_ = 0;
  int free_ = 0;     // the first node and element that move
  ForceSpan span_;   // what computeForces evaluates: from the element before free_ (its force and
                     // plate contact act on node free_, its Voronoi couple on element free_)
  RelaxResult res_;
};

// memory of the Newton solver, kept across growth steps so that solving allocates nothing once it has
// seen the largest rod; also what it found about the stability of the last equilibrium
struct NewtonWorkspace {
  BandLU lu;                      // the Jacobian over the free dofs and its LU factors
  BandLDLT ldlt;                  // its symmetric part at the converged state, LDL^T factors
  // self-contact's couplings of nodes far apart along the rod (off the band), and with them the whole
  // Jacobian as a sparse matrix (used instead of lu / ldlt while offBand is not empty)
  std::vector<OffBandEntry> offBand;
  SparseStiffness sparse;
  bool sparseActive = false;
  std::vector<double> r, r0, delta, mode;  // scaled residual, base residual, Newton step, softest mode
  std::vector<double> lanczos;    // the Lanczos basis of the eigenvalue nearest zero (relax_newton.cpp)
  std::vector<Vec3> save;         // node positions (by block index) saved across a trial step
  std::vector<Mat3> saveQ;        // directors saved across a trial step
  int firstFreeNode = 0;          // the window of the last solve
  bool factorsValid = false;      // lu holds the LU factors of the last relaxation's last Jacobian, for
  int factorsDofs = 0;            //   this many unknowns from this first block: the next relaxation's
  int factorsFirstBlock = 0;      //   first (chord) iteration uses them (relax_newton.cpp)
  // the frozen twists' stiffness, a tridiagonal chain (relax_newton.cpp): per element e < matureValid,
  // K(e-1, e), K(e, e), K(e+1, e) [N m / rad], differenced at an earlier state; the relaxations since
  // the whole chain was last differenced
  std::vector<double> matureK;
  int matureValid = 0, matureAge = 0;
  int modeSize = 0;               // unknowns of the last mode (a warm start for the next one)
  int negative = 0;               // negative pivots of the symmetric stiffness: unstable directions
  double lowestEigenvalue = 0;    // eigenvalue of the scaled stiffness nearest zero (the lowest while
                                  // stable) [N/m]
  void reserve(int elements);
  // what the next relaxation depends on, in the checkpoint's order (fields.hpp): the rest is scratch
  static constexpr auto fields() {
    using W = NewtonWorkspace;
    return std::tuple{field("mode", &W::mode), field("modeSize", &W::modeSize),
                      field("firstFreeNode", &W::firstFreeNode), field("negative", &W::negative),
                      field("lowestEigenvalue", &W::lowestEigenvalue), field("factorsValid", &W::factorsValid),
                      field("sparseActive", &W::sparseActive), field("factorsDofs", &W::factorsDofs),
                      field("factorsFirstBlock", &W::factorsFirstBlock), field("lu", &W::lu),
                      field("sparse", &W::sparse), field("matureK", &W::matureK),
                      field("matureValid", &W::matureValid), field("matureAge", &W::matureAge)};
  }
  // the eigenvector of lowestEigenvalue as a full dof vector (per node 3 translations [m], per element 3
  // rotations [rad]), largest translation 1
  Eigen::VectorXd unstableMode(const RodState& s, const Environment& env) const;
};

// Newton's method on the discrete equilibrium (docs/model.md, Newton solver) for the nodes firstFreeNode..n
// and the elements from there on; the rest stays exactly where it is. With opt.stabilityCheck, also the
// inertia of the converged state's stiffness (nw.negative, nw.lowestEigenvalue). Returns stalled when
// no acceptable step is found or opt.newtonMaxIterations is reached (the state is then where Newton
// left it); throws RelaxError on divergence or a singular stiffness.
RelaxResult relaxNewton(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                        RelaxWorkspace& ws, NewtonWorkspace& nw, int firstFreeNode);

// the stiffness K = -dF/du over the free dofs of state s, unfactorised, into nw.lu (scaled units:
// translations [m] and rotations times the mean element length; forces [N] and couples over it); dof
// 3b + c - 3 b0 for block b (node i: b = 2i, element i: b = 2i + 1), b0 the first free block
void assembleStiffness(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                       RelaxWorkspace& ws, NewtonWorkspace& nw, int firstFreeNode);

// The equilibrium tolerance of both solvers (tolerance.cpp): the largest residual force on a free node
// and couple on a free element that count as equilibrium, with E = B1/Lref^2:
//   force = forceTol * E                                         without applied loads, or A >= E,
//   force = max(forceTol * A, min(forceTol * E, kResolvableResidual * r))   when the applied loads A < E,
//   couple = forceTol * B1/Lref, or max(forceTol * A Lref, min(forceTol B1/Lref, kResolvableResidual r Lref)),
// r the round-off of a node force (machine epsilon * largest EA/l * largest |x|),
// A the largest applied load per node (appliedLoadScale: the weight lumped to a free node, the tip
// force, the tip couple / Lref). B1/Lref^2 is the scale of the forces that growth and tropism make
// (intrinsic curvature over the growth zone Lref); a residual below 1e-4 of it resolves them, but a load
// far below it is not seen at all: a free 2 mm rod's weight pulls each node down a plate at 80 degrees
// with 3e-9 N against a tolerance of 9.8e-8 N, so the rod "converged" unmoved. Contact (plate, self,
// obstacles), friction and adhesion are reactions: in equilibrium they are bounded by the elastic and
// applied loads, so they set no scale of their own; taken as a floor of the tolerance, a penalty's
// overshoot away from equilibrium would loosen it (circular), taken as a bound, a grazing contact would
// make it vanish.
struct EquilibriumTolerance {
  double force = 0;   // [N]
  double couple = 0;  // [N m]
};
EquilibriumTolerance equilibriumTolerance(const RodParams& p, const Environment& env, const SolverOptions& opt,
                                          const RodState& s, int firstFreeNode = 0);
// A [N]: the largest of the tip force, the tip couple / Lref and the weight on nodes firstFreeNode.. n
double appliedLoadScale(const RodParams& p, const Environment& env, const RodState& s, double Lref,
                        int firstFreeNode = 0);
// small loads ask for a residual down to this many times the round-off of a node force, not below (a
// 10 mm cantilever of 0.4 mm elements stalled at 1.3 times that round-off)
inline constexpr double kResolvableResidual = 100.0;

// a node that moves more than this many Lref within one relaxation is sliding away: no static
// equilibrium (docs/model.md, Contact and friction). A clamped rod's node moves at most twice its arc length;
// a growing root's snap moves its tip by less than the growth zone (Lref).
inline constexpr double kSlideLengths = 3.0;

// relaxes the rod to equilibrium under env; throws RelaxError on divergence or on hitting the cap
RelaxResult relax(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                  RelaxWorkspace& ws, int firstFreeNode = 0);

// evaluates all forces of state s into ws.force / ws.torque (used by both solvers, the stability check
// and tests); first > 0: exact only on the nodes and elements after `first` (rod.hpp), for the Newton
// solver's window; pieces: ForcePieces::NoSelfContact leaves self-contact out (environment.hpp)
void computeForces(const RodParams& p, const Environment& env, const RodState& s, bool planeDamping,
                   RelaxWorkspace& ws, int first = 0, ForcePieces pieces = ForcePieces::All);
// the same over a part of the rod (environment.hpp: ForceSpan)
void computeForces(const RodParams& p, const Environment& env, const RodState& s, bool planeDamping,
                   RelaxWorkspace& ws, ForceSpan span, ForcePieces pieces = ForcePieces::All);

}  // namespace rootsim
