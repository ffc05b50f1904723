#pragma once
// A plate of roots (docs/plate.md): seedlings sown on one tilted plate, each a root of its own (a
// Simulation in its own frame, its base at the frame's origin), and the contact between them. No I/O here.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rootsim/simulation.hpp"

namespace rootsim {

// lateral roots (docs/plate.md, Lateral roots): where they emerge along a parent, and their own root
struct LateralParams {
  bool enabled = false;
  double first = 5e-3;             // the first site, from the parent's base along its rest arc length [m]
  double spacing = 2e-3;           // between sites [m]
  double apicalUnbranched = 5e-3;  // a site emerges once the parent's tip is this far beyond it [m]
  double delay = 0.0;              // and this long after that [s]
  double delaySpread = 0.0;        // each site's delay is delay plus a normal draw of this sd, drawn again
                                   // while negative (siteDelay) [s]
  bool alternate = true;           // sides alternate (+lateral side first); false: drawn from seed
  std::uint64_t seed = 1;          // the sides' draws
  double insertion = 60.0 * units::deg;  // angle from the parent's tangent (or downhill) [rad]
  bool fromParent = true;          // insertion measured from the parent's tangent at the site; false:
                                   // from downhill in the plate (docs/plate.md, Laterals on a tilted plate)
  double radius = 0.06e-3;         // the lateral's R [m] (0.6 of the primary's)
  double rate = 0.1 / units::hour; // its relative growth rate in the zone [1/s] (half the primary's)
  double zoneLength = 0.6e-3;      // its growth zone [m]
  double initialLength = 0.3e-3;   // its length at emergence [m]
  double beta = 0.1, gamma = 0.1, rTau = 0.0;
  double setPoint = 60.0 * units::deg;  // its gravitropic set-point angle at emergence [rad]
  std::optional<double> setPointFinal;   // the angle it drifts to with its age (TropismParams; none, or
                                         // equal to setPoint: no drift) [rad]
  SetPointDrift setPointDrift = SetPointDrift::Exponential;
  double setPointDriftTime = 24.0 * units::hour;  // [s]
  int maxOrder = 1;                // laterals of laterals up to this order (1: laterals of the primary only)
};

// one seedling: where it is sown, which way it points, and its root's model (the plate's keys, the
// seedling's own overrides and the values drawn for it: docs/plate.md, Scenes)
struct Seedling {
  std::string name;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // the base's foot on the plate (lateral, downhill)
                                                       // from the plate's origin, its uphill-left corner [m]
  Model model;                                         // model.initial.angle: its initial direction
  std::string genotype;                                // a label the plate summary groups by ("" none)
  std::optional<LateralParams> laterals;               // its lateral roots' own parameters (a scene's: the
                                                       // plate's [laterals], its set and draws); none: the
                                                       // plate's. A lateral carries its parent's
  std::vector<std::string> overrides;                  // its keys that differ from the plate's, as
                                                       // "section.key=value" (set or drawn), for the summary
  // a lateral root's: its parent (index in the plate), order (0: a seedling), the parent's rest arc
  // length at the junction [m], when it emerged [h]
  int parent = -1;
  int order = 0;
  double siteS = 0.0;
  double emergedH = 0.0;
};

struct PlateParams {
  double width = 0.12;   // lateral extent of the plate from its origin [m] (a 120 mm square plate)
  double length = 0.12;  // downhill extent [m]
  // most rounds (a coupled Newton solve of the roots in contact and a sweep confirming it) within one
  // growth step before the step fails (docs/plate.md, Solving)
  int maxSweeps = 100;
  std::uint64_t populationSeed = 1;  // the seed of the scene's [population] draws (the drawn values stand
                                     // in each seedling's model and laterals)
  LateralParams laterals;           // the plate-wide [laterals]; each seedling carries its own
};

// the delay of root `root`'s lateral site `site` (both indices from 0) [s]: lp.delay, plus, when
// lp.delaySpread > 0, a normal draw of that sd, drawn again while the delay would be negative. Each site
// draws from its own splitmix64 stream, seeded by lp.seed, the root and the site: no state, so a site
// draws the same delay at every step, after a resume, and in every run of the same scene
double siteDelay(const LateralParams& lp, int root, int site);

// the lateral parameters a root grows its laterals by: its own, else the plate's
const LateralParams& lateralsOf(const Seedling& sd, const PlateParams& plate);

// a plate as a scene describes it: the plate and its seedlings (an empty list: a scene of one root alone)
struct PlateSpec {
  PlateParams params;
  std::vector<Seedling> seedlings;
  Model base;              // the plate-wide keys' model (obstacles in plate coordinates)
  std::string headToml;    // the resolved text of the plate-wide keys and obstacles (a root's scene starts so)
};

// a root alone as a plate of one seedling: the model as it is, at the plate's origin, no name (its errors
// keep their own text) and no laterals. Its growth steps are the root's own (Simulation), bit for bit: a scene
// of one root runs so (runSceneToDir)
PlateSpec plateOfOne(const Model& m);

// one row of the plate's time series
struct PlateStepRecord {
  int step = 0;
  double timeH = 0;       // growth time [h]
  int touchingPairs = 0;  // element pairs of two different roots in contact (closer than Ra + Rb)
  double minGap = std::numeric_limits<double>::quiet_NaN();  // closest approach of two roots' centrelines /
                                                             // (Ra + Rb) (NaN: no two roots within reach)
  int sweeps = 0;         // relaxation sweeps this step took (1: no root re-relaxed for another)
  static constexpr auto fields() {
    using R = PlateStepRecord;
    return std::tuple{field("step", &R::step), field("timeH", &R::timeH), field("touchingPairs", &R::touchingPairs),
                      field("minGap", &R::minGap), field("sweeps", &R::sweeps)};
  }
};

// the contact forces between two roots at their current states, per node, in plate coordinates' lab
// frame (lab axes, the plate's origin): what a test of action and reaction reads
struct RootPairForces {
  Eigen::Matrix3Xd onA, onB;  // 3 x nodes of each root [N]
  int contacts = 0;           // element pairs in contact
};

// a lateral root as it emerged (emergeLaterals): its parent (plate index), its site's index along the parent,
// where it starts (the parent's node at the site, plate coordinates [m], and that node's rest arc length
// [m]), its initial direction [rad] and the time [s]. The rest of its seedling follows from these, the
// parent and [laterals] (PlateSimulation builds it so when it emerges and when a plate is restored).
struct LateralBirth {
  int parent = 0;
  int site = 0;
  double lateral = 0, downhill = 0;
  double siteS = 0;
  double angle = 0;
  double time = 0;
  static constexpr auto fields() {
    using B = LateralBirth;
    return std::tuple{field("parent", &B::parent), field("site", &B::site), field("lateral", &B::lateral),
                      field("downhill", &B::downhill), field("siteS", &B::siteS), field("angle", &B::angle),
                      field("time", &B::time)};
  }
};

// the name of a parent's lateral at site index `site` (its folder roots/NAME): "s1.3" for s1's third site
std::string lateralName(const std::string& parent, int site);

// one root of a plate as a growth step leaves it: its state and its simulation's carry (simulation.hpp)
struct RootCarry {
  RodState state;
  SimulationCarry carry;
  static constexpr auto fields() {
    using C = RootCarry;
    return std::tuple{field("state", &C::state), field("carry", &C::carry)};
  }
};

// what a plate carries from one growth step to the next (a checkpoint saves it; PlateSimulation(plate,
// seedlings, carry) continues bit for bit where carry() left): the last record, every root's state and
// carry (seedlings, then laterals in the order they emerged), the laterals emerged, each root's next
// lateral site, the sides' draws, and the coupled Newton system's memory. The lists of nearby elements
// are rebuilt from the states (they are before every relaxation).
struct PlateCarry {
  PlateStepRecord last;
  std::vector<RootCarry> roots;
  std::vector<LateralBirth> laterals;
  std::vector<int> nextSite;
  std::uint64_t sideStream = 1;
  Memory<CoupledWorkspace> coupled;
  static constexpr auto fields() {
    using C = PlateCarry;
    return std::tuple{field("last", &C::last), field("roots", &C::roots), field("laterals", &C::laterals),
                      field("nextSite", &C::nextSite), field("sideStream", &C::sideStream),
                      field("coupled", &C::coupled)};
  }
};

// a lateral root's model as it emerges from a parent of model `parent`: the parent's keys with the lateral's
// own root, growth and tropism ([laterals]); its angle, start time, seed and obstacles are the site's
// (PlateSimulation sets them). One function, so that the scene check at the start sees what emerges.
Model lateralModel(const Model& parent, const LateralParams& lp);

class PlateSimulation {
 public:
  // where the coupled Newton stalls, the first kJointHandBacks stalls of a step relax the roots in
  // contact together explicitly for kJointBudget sub-steps (four times more at each further one) and
  // hand them back to the coupled Newton; later stalls relax them explicitly to equilibrium
  static constexpr long kJointBudget = 32;
  static constexpr int kJointHandBacks = 4;

  // builds every seedling's initial root and relaxes it (seeing the roots built before it)
  PlateSimulation(const PlateParams& plate, std::vector<Seedling> seedlings);
  // continues a plate of the same params and seedlings exactly where carry() of it left (a checkpoint):
  // the laterals emerge again from their births, every root from its state and carry. Throws
  // std::invalid_argument when the carry does not fit the seedlings (a caller checks it first)
  PlateSimulation(const PlateParams& plate, std::vector<Seedling> seedlings, const PlateCarry& carry);
  PlateCarry carry() const;

  // one growth step of every root: each grows; roots apart relax alone (the single root's step); roots
  // within reach of another are solved together by one Newton system on their cluster, then each
  // confirms alone (docs/plate.md, Solving); throws RelaxError naming the root
  const PlateStepRecord& growthStep();
  // the roots that emerged in the last growth step (indices; the plate's roots grow by them)
  const std::vector<int>& emerged() const { return emerged_; }

  int size() const { return static_cast<int>(roots_.size()); }
  const Simulation& root(int r) const { return *roots_[static_cast<size_t>(r)]; }
  // changes root r's tropism parameters between growth steps (Simulation::setTropism; its seedling's model
  // says so too): an experiment that changes gravity's effect half-way. The caller validates them
  void setTropism(int r, const TropismParams& t);
  const Seedling& seedling(int r) const { return seedlings_[static_cast<size_t>(r)]; }
  const PlateParams& params() const { return plate_; }
  const PlateStepRecord& last() const { return last_; }
  int step() const { return last_.step; }
  // the lab vector from the plate's origin to root r's frame origin (its base's foot) [m]
  Vec3 offset(int r) const;
  RootPairForces pairForces(int a, int b) const;
  // the roots within reach of another as one Newton system at their current states (docs/plate.md,
  // Solving; tests): its Jacobian K = -dF/du (dense, scaled units) and its residual after displacing
  // unknown k by h (k < 0: none); coupledRoots: the roots of that system, in the order of its unknowns,
  // coupledFirst: each one's first unknown
  Eigen::MatrixXd coupledJacobian();
  Eigen::VectorXd coupledResidual(int k, double h);
  std::vector<int> coupledRoots() const;
  const std::vector<int>& coupledFirst() const { return coupled_.first; }

 private:
  // the capsules of the other roots near root r, into its contact pieces (ContactWorkspace::neighbours)
  void listNeighbours(int r);
  void indexElements();
  // root r's capsules where their roots are now (the lists kept)
  void refreshCapsules(int r);
  // every root within reach of another relaxes again (Newton); returns the largest node displacement
  double sweep();
  // the lists of every root and the roots within reach of another (cluster_)
  void listCluster();
  // the roots of cluster_ (as listCluster left them) relax together as one Newton system
  // (relaxNewtonCoupled)
  RelaxResult relaxCoupled();
  // a growth step of two roots or more: every root grows and relaxes, the roots within reach of another
  // together (docs/plate.md, Solving); returns the sweeps it took
  int settleStep();
  // the roots within reach of another relax together, explicitly, one sub-step each in turn, until all
  // are in equilibrium or, budget > 0, for at most budget sub-steps
  void relaxJointly(long budget);
  PlateStepRecord observe(int sweeps) const;
  // the lateral roots whose sites the last growth step opened (docs/plate.md, Lateral roots)
  void emergeLaterals();
  // the seedling of a lateral born so (its model from its parent's and [laterals]); adds its root, new or
  // (from a carry) as it was
  Seedling lateralSeedling(const LateralBirth& b) const;
  void addLateral(const LateralBirth& b, const RootCarry* from);
  // pairs of root r's element i and root o's element j that contact skips: within 3 (Ra + Rb) of arc
  // length of a lateral's junction with its parent, on both
  bool nearJunction(int r, int i, int o, int j) const;

  PlateParams plate_;
  std::vector<Seedling> seedlings_;
  std::vector<std::unique_ptr<Simulation>> roots_;
  std::vector<Vec3> offset_;
  PlateFrame frame_;
  PlateStepRecord last_;
  // the broad phase (growth-step scratch, reused): every element of every root in a uniform grid of the
  // plate, sorted by cell
  struct Element {
    long long cell;
    int root, index;
  };
  std::vector<Element> grid_;
  std::vector<int> firstElement_;  // global index of each root's element 0
  Eigen::Matrix3Xd before_;        // a sweep's scratch: a root's nodes before it relaxed again
  std::vector<Eigen::Matrix3Xd> listed_;  // every root's nodes when the step's lists were built
  std::vector<int> capsuleOf_;      // global element -> capsule index in the list being built (-1: none)
  std::vector<int> capsules_;       // listNeighbours: the global elements listed, in the order first listed
  std::vector<int> jointRoots_;     // relaxJointly: the roots relaxing together
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> boxes_;  // each root's box in the plate, widened
  std::vector<char> near_;         // the root's box overlaps another's: it is in the grid
  std::vector<int> nextSite_;      // per root: the index of its next lateral site
  std::vector<int> emerged_;
  std::vector<LateralBirth> births_;  // the laterals emerged, in order (root seedlings + i)
  std::uint64_t sideStream_ = 1;   // the sides' draws (LateralParams::alternate false)
  std::vector<CoupledRoot> cluster_;  // the roots within reach of another (scratch)
  CoupledWorkspace coupled_;       // their coupled Newton system's memory
  double cellSize_ = 0;
};

}  // namespace rootsim
