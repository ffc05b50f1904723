#pragma once
// The run loop (STYLE.md "Data flow"): for each growth step grow -> relax -> observe. No I/O here.
#include <array>
#include <limits>
#include <vector>

#include "rootsim/analysis.hpp"
#include "rootsim/model.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// one row of the time series
struct StepRecord {
  int step = 0;
  double timeH = 0;           // growth time [h]
  double length = 0;          // rest length [m]
  int elements = 0;
  double thetaTip = 0;        // planar tip angle, unwrapped over time [rad]
  ZoneObservables zone;
  long substeps = 0;          // explicit relaxation sub-steps of this step
  long iterations = 0;        // Newton iterations of this step
  double lowestEigenvalue = 0;  // Newton with stability check: eigenvalue of the scaled stiffness nearest
                                // zero at the equilibrium found (the lowest while stable) [N/m]; else NaN
  double residualForce = 0;   // at exit [N]
  int splits = 0;             // elements split in this step
  int unstable = 0;           // unstable equilibria found (and left along their unstable mode) in this step
  Vec3 tip = Vec3::Zero();    // tip position, lab [m]
  // contact (MODEL.md section 11; all zero when the features are off)
  int selfContacts = 0;       // element pairs in self-contact
  double minSelfDistance = std::numeric_limits<double>::quiet_NaN();  // closest approach of non-
                              // neighbouring elements / R (NaN: none within 3R, or self-contact off)
  int obstacleContacts = 0;   // elements touching an obstacle
  long slipEvents = 0;        // node slips committed so far (friction), cumulative
  double frictionWork = 0;    // work done against friction so far [J], cumulative
};

// what a growth step carries to the next besides the rod state: counters, the unwrapped tip angle, the
// last record, and the solvers' memory that changes their results (the Newton stability check's
// softest-mode start vector, the self-contact Verlet list). A checkpoint (src/io/checkpoint.cpp)
// saves it with the state; Simulation(model, state, carry) continues bit for bit where carry() left.
struct SimulationCarry {
  int step = 0;
  long totalSubsteps = 0, totalIterations = 0;
  double thetaUnwrapped = 0;            // [rad]
  long slipEvents = 0;
  double frictionWork = 0;              // [J]
  StepRecord last;
  // NewtonWorkspace: the warm start of the eigenvalue search and what it knows about the last solve
  std::vector<double> newtonMode;       // (at least newtonModeSize)
  int newtonModeSize = 0, newtonFirstFreeNode = 0, newtonNegative = 0;
  double newtonLowestEigenvalue = 0;    // [N/m]
  // the last Jacobian's band LU factors, which the next relaxation's first (chord) iteration uses
  bool newtonFactorsValid = false, newtonSparseActive = false;
  int newtonFactorsDofs = 0, newtonFactorsFirstBlock = 0;
  int newtonBandN = 0, newtonBandKl = 0, newtonBandKu = 0;
  std::vector<double> newtonBand;       // BandLU::storage()
  std::vector<int> newtonPivots;        // BandLU::pivots()
  SparseMemory newtonSparse;            // the sparse Jacobian's pattern and pivots (self-contact)
  std::vector<double> newtonMatureK;    // the frozen twists' kept stiffness (NewtonWorkspace::matureK)
  int newtonMatureValid = 0, newtonMatureAge = 0;
  // the solver's self-contact Verlet list (ContactWorkspace)
  std::vector<std::array<int, 2>> pairs;
  Eigen::Matrix3Xd pairsBuiltX;         // (3 x builtElements+1) [m]
  int pairsBuiltElements = -1;
  double pairsBuiltRestLength = -1.0;   // [m]
  long pairsBuilds = 0;
};

class Simulation {
 public:
  // builds the initial rod (MODEL.md section 3) and relaxes it once (no growth yet)
  explicit Simulation(const Model& m);
  // continues from a state of an earlier simulation of a compatible model (its growth step `step`), as it
  // is: no relaxation (a restart, or the same root handed to another solver)
  Simulation(const Model& m, const RodState& s, int step);
  // continues a simulation exactly where carry() of an earlier one with the same model and state left
  // it (a checkpoint): the next growthStep() gives the same bits as it would have there
  Simulation(const Model& m, const RodState& s, const SimulationCarry& carry);

  // one growth step: anchor mature nodes, grow rest lengths, update kappa0 (Eq. 17) and the twist
  // profile, split long elements, relax, commit the friction stick points; throws RelaxError naming
  // the growth step
  const StepRecord& growthStep();

  // changes the tropism parameters (beta, gamma, sensing, twist, circumnutation) between growth steps:
  // the next growthStep uses them (an experiment that changes gravity's effect half-way). The caller
  // validates them (the scene schema's ranges); the rest of the model stays constant.
  void setTropism(const TropismParams& t) { m_.tropism = t; }

  const Model& model() const { return m_; }
  const RodState& state() const { return s_; }
  const RodStrains& strains() const { return ws_.strains; }
  const StepRecord& last() const { return rec_; }
  int step() const { return step_; }
  long totalSubsteps() const { return totalSubsteps_; }
  long totalIterations() const { return totalIterations_; }
  Snapshot snapshot() const;
  SimulationCarry carry() const;

 private:
  void observe(const RelaxResult& res, int splits, int unstable);
  void commitStep();
  // relaxes; with solver.stabilityCheck, leaves saddle points along their unstable mode
  RelaxResult relaxStable(int step, int& unstable);
  RelaxResult relaxNewtonStable(int step, int& unstable);
  RelaxResult newtonOrExplain(int step);
  int windowStart();
  Model m_;
  RodState s_;
  RodState start_;              // newtonOrExplain's copy of the state before Newton (scratch)
  RelaxWorkspace ws_;
  NewtonWorkspace nw_;
  int step_ = 0;
  long totalSubsteps_ = 0;
  long totalIterations_ = 0;
  double thetaUnwrapped_ = 0;
  ContactWorkspace observed_;   // contact counts' own scratch (the solver's list stays untouched)
  long slipEvents_ = 0;
  double frictionWork_ = 0;
  StepRecord rec_;
};

}  // namespace rootsim
