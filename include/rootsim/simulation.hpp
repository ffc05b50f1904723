#pragma once
// The run loop (docs/architecture.md, Data flow): for each growth step grow -> relax -> observe. No I/O here.
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "rootsim/analysis.hpp"
#include "rootsim/fields.hpp"
#include "rootsim/model.hpp"
#include "rootsim/relax_dynamic.hpp"
#include "rootsim/relax_newton.hpp"
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
  // contact (docs/model.md, "Contact and friction"; all zero when the features are off)
  int selfContacts = 0;       // element pairs in self-contact
  double minSelfDistance = std::numeric_limits<double>::quiet_NaN();  // closest approach of non-
                              // neighbouring elements / R (NaN: none within 3R, or self-contact off)
  int obstacleContacts = 0;   // elements touching an obstacle
  long slipEvents = 0;        // node slips committed so far (friction), cumulative
  double frictionWork = 0;    // work done against friction so far [J], cumulative
  static constexpr auto fields() {
    using R = StepRecord;
    return std::tuple{field("step", &R::step), field("timeH", &R::timeH), field("length", &R::length),
                      field("elements", &R::elements), field("thetaTip", &R::thetaTip), field("zone", &R::zone),
                      field("substeps", &R::substeps), field("iterations", &R::iterations),
                      field("lowestEigenvalue", &R::lowestEigenvalue), field("residualForce", &R::residualForce),
                      field("splits", &R::splits), field("unstable", &R::unstable), field("tip", &R::tip),
                      field("selfContacts", &R::selfContacts), field("minSelfDistance", &R::minSelfDistance),
                      field("obstacleContacts", &R::obstacleContacts), field("slipEvents", &R::slipEvents),
                      field("frictionWork", &R::frictionWork)};
  }
};

// what a growth step carries to the next besides the rod state and the solvers' memory: counters, the
// unwrapped tip angle, the last record
struct SimulationProgress {
  int step = 0;
  long totalSubsteps = 0, totalIterations = 0;
  double thetaUnwrapped = 0;            // [rad]
  long slipEvents = 0;
  double frictionWork = 0;              // [J]
  StepRecord last;
  static constexpr auto fields() {
    using P = SimulationProgress;
    return std::tuple{field("step", &P::step), field("totalSubsteps", &P::totalSubsteps),
                      field("totalIterations", &P::totalIterations), field("thetaUnwrapped", &P::thetaUnwrapped),
                      field("slipEvents", &P::slipEvents), field("frictionWork", &P::frictionWork),
                      field("last", &P::last)};
  }
};

// what a growth step carries to the next besides the rod state: the progress and the solvers' memory
// that changes their results (NewtonWorkspace::fields: the stability check's softest-mode start vector,
// the last Jacobian's factors, the frozen twists' stiffness; ContactWorkspace::fields: the self-contact
// Verlet list). A checkpoint (src/io/checkpoint.cpp) saves it with the state; Simulation(model, state,
// carry) continues bit for bit where carry() left. Every part is a field list (fields.hpp): a new
// persistent member of a workspace is one line in its list, and carry(), the restoring constructor and
// the checkpoint follow.
struct SimulationCarry {
  SimulationProgress progress;
  // the banded factors (lu) only while they are valid and in use (else an empty BandLU)
  Memory<NewtonWorkspace> newton;
  // the list only while it describes the rod as it was built (else a fresh workspace's: builds aside)
  Memory<ContactWorkspace> contact;
  static constexpr auto fields() {
    using C = SimulationCarry;
    return std::tuple{field("progress", &C::progress), field("newton", &C::newton), field("contact", &C::contact)};
  }
};

class Simulation {
 public:
  // builds the initial rod (docs/model.md, "Frames and signs": the initial rod) and relaxes it once (no growth yet)
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
  // growthStep in two halves (a plate's roots in contact relax together in between: plate.cpp):
  // beginStep grows (everything before the relaxation), finishStep relaxes, commits and observes
  void beginStep();
  const StepRecord& finishStep();

  // relaxes the current state again, without growing (a plate: another root it touches has moved since):
  // the same growth step's equilibrium with the contact forces as they are now. The step's record adds the
  // solver's work; friction's stick points stay where the step's first equilibrium committed them
  const StepRecord& relaxAgain();
  // a plate's roots that touch relax together, explicitly, one sub-step of each in turn (plate.cpp):
  // beginJoint starts this root's explicit relaxation (over its Newton window, as Newton's fallback
  // does), jointStep takes one sub-step and says whether the root is in equilibrium, endJoint adds the
  // sub-steps to the step's record; relaxAgain then confirms the equilibrium
  void beginJoint();
  bool jointStep();
  long jointSubsteps() const;
  void endJoint();
  // this root as one block of a plate's coupled Newton system (relaxNewtonCoupled: its window as its own
  // relaxation's, its state and Newton memory); addCoupled adds that relaxation's iterations to the step
  CoupledRoot coupled(int plateIndex);
  void addCoupled(const RelaxResult& r);
  // the other roots on a plate as this root's contact pieces see them (ContactWorkspace::neighbours)
  NeighbourCapsules& neighbours() { return ws_.contact.neighbours; }
  const NeighbourCapsules& neighbours() const { return ws_.contact.neighbours; }

  // changes the tropism parameters (beta, gamma, sensing, twist, circumnutation) between growth steps:
  // the next growthStep uses them (an experiment that changes gravity's effect half-way). The caller
  // validates them (the scene schema's ranges); the rest of the model stays constant.
  void setTropism(const TropismParams& t) { m_.tropism = t; }

  const Model& model() const { return m_; }
  const RodState& state() const { return s_; }
  const RodStrains& strains() const { return ws_.strains; }
  const StepRecord& last() const { return p_.last; }
  int step() const { return p_.step; }
  long totalSubsteps() const { return p_.totalSubsteps; }
  long totalIterations() const { return p_.totalIterations; }
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
  SimulationProgress p_;
  ContactWorkspace observed_;   // contact counts' own scratch (the solver's list stays untouched)
  std::optional<DynamicRelaxation> joint_;  // a plate's joint relaxation under way (beginJoint; in place: no allocation)
  // a step begun and not finished: its splits, and the plate's coupled iterations and joint sub-steps
  // so far (the record finishStep makes adds them)
  struct Open {
    bool open = false;
    int splits = 0;
    long iterations = 0, substeps = 0;
  };
  Open open_;
};

}  // namespace rootsim
