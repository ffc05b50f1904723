#pragma once
// The quasi-static Newton solver (docs/model.md, Newton solver; relax_newton.cpp) and the memory it keeps
// across growth steps.
#include <array>
#include <functional>
#include <cstddef>
#include <vector>

#include "rootsim/band.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/fields.hpp"
#include "rootsim/relax.hpp"
#include "rootsim/sparse_stiffness.hpp"

namespace rootsim {

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
  // lu holds, unfactorised, this root's block of the last Jacobian of a plate's coupled solve, of
  // coupledBlockDofs unknowns from block coupledBlockFirst (-1: it does not): the next relaxation's
  // stability check reads it when the root is in equilibrium already (scratch: set and read within a
  // growth step)
  int coupledBlockDofs = -1, coupledBlockFirst = 0;
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

// Roots on a plate that touch are one Newton system (docs/plate.md, Solving; relax_newton.cpp): the
// unknowns of every root's window side by side, each root's banded Jacobian a diagonal block, the
// contacts between them the off-diagonal blocks (neighbourContactStiffness), factorised together by KLU.
// One root of the system: its model's parts, state, workspaces and window (what relaxNewton takes), and
// its index on the plate (the NeighbourCapsules::source of the others name it so).
struct CoupledRoot {
  const RodParams* rod = nullptr;
  const Environment* env = nullptr;
  const SolverOptions* opt = nullptr;
  RodState* s = nullptr;
  RelaxWorkspace* ws = nullptr;
  NewtonWorkspace* nw = nullptr;
  int firstFreeNode = 0;
  int plateIndex = 0;
};

// the coupled system's memory (a plate's, reused from step to step; it allocates while a cluster grows,
// as SparseStiffness does)
struct CoupledWorkspace {
  BandLU band;                        // the roots' bands side by side
  std::vector<OffBandEntry> offBand;  // their self-contacts' off-band entries and the couplings between roots
  SparseStiffness sparse;
  std::vector<double> r, r0, delta;
  std::vector<int> first;             // each root's first unknown
  std::vector<int> clusterOf;         // plate index -> position in the system (-1: not in it)
  std::vector<RodState> start;        // the states before a relaxation (a stalled one returns to them)
  std::vector<std::max_align_t> solvers;  // room for the roots' Newton solvers (relax_newton.cpp: Coupled)
  std::array<char, 256> stallReason{};    // why the last relaxation stalled (empty when it did not)
  // what the next coupled relaxation depends on (fields.hpp): the sparse pattern and pivots, reused by a
  // system of the same size; the rest is scratch
  static constexpr auto fields() {
    using W = CoupledWorkspace;
    return std::tuple{field("sparse", &W::sparse)};
  }
};

// Newton's method on the roots' joint equilibrium: converged when every root is within its own
// equilibrium tolerance (equilibriumTolerance, as relaxNewton). refresh() puts every root's neighbour
// capsules where the other roots now are (before each force evaluation). No stability check here (the
// plate confirms each root's equilibrium alone: relaxAgain). Returns stalled, with every root back where
// it started, when no acceptable step is found, the iterations run out, the stiffness is singular or
// Newton crawls (the plate then relaxes the roots together explicitly), and why in cw.stallReason (not in
// the result's message: formatted in place, a stall allocates nothing); throws RelaxError on divergence.
RelaxResult relaxNewtonCoupled(const std::vector<CoupledRoot>& roots, const std::function<void()>& refresh,
                               CoupledWorkspace& cw);

// the coupled system at the roots' current states, for tests: its Jacobian K = -dF/du (dense; scaled
// units as relaxNewton's) and its scaled residual F after displacing unknown k by h (k < 0: none; the
// state is restored)
Eigen::MatrixXd coupledStiffness(const std::vector<CoupledRoot>& roots, const std::function<void()>& refresh,
                                 CoupledWorkspace& cw);
Eigen::VectorXd coupledResidual(const std::vector<CoupledRoot>& roots, const std::function<void()>& refresh,
                                CoupledWorkspace& cw, int k, double h);

}  // namespace rootsim
