#pragma once
// A plate of roots (docs/plate.md): seedlings sown on one tilted plate, each a root of its own (a
// Simulation in its own frame, its base at the frame's origin), and the contact between them. No I/O here.
#include <memory>
#include <string>
#include <vector>

#include "rootsim/simulation.hpp"

namespace rootsim {

// one seedling: where it is sown, which way it points, and its root's model (the plate's keys, the
// seedling's own overrides and the values drawn for it: docs/plate.md, Scenes)
struct Seedling {
  std::string name;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // the base's foot on the plate (lateral, downhill)
                                                       // from the plate's origin, its uphill-left corner [m]
  Model model;                                         // model.initial.angle: its initial direction
  std::string genotype;                                // a label the plate summary groups by ("" none)
  std::vector<std::string> overrides;                  // its keys that differ from the plate's, as
                                                       // "section.key=value" (set or drawn), for the summary
};

struct PlateParams {
  double width = 0.12;   // lateral extent of the plate from its origin [m] (a 120 mm square plate)
  double length = 0.12;  // downhill extent [m]
  // most sweeps of the roots in contact within one growth step before the step fails (docs/plate.md,
  // Solving)
  int maxSweeps = 100;
};

// a plate as a scene describes it: the plate and its seedlings (an empty list: a scene of one root alone)
struct PlateSpec {
  PlateParams params;
  std::vector<Seedling> seedlings;
};

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

class PlateSimulation {
 public:
  // builds every seedling's initial root and relaxes it (seeing the roots built before it)
  PlateSimulation(const PlateParams& plate, std::vector<Seedling> seedlings);

  // one growth step of every root, in the seedlings' order, each seeing the others as they stand; then
  // sweeps re-relax the roots another root touches until none moves (docs/plate.md, Solving); throws
  // RelaxError naming the root
  const PlateStepRecord& growthStep();

  int size() const { return static_cast<int>(roots_.size()); }
  const Simulation& root(int r) const { return *roots_[static_cast<size_t>(r)]; }
  const Seedling& seedling(int r) const { return seedlings_[static_cast<size_t>(r)]; }
  const PlateParams& params() const { return plate_; }
  const PlateStepRecord& last() const { return last_; }
  int step() const { return last_.step; }
  // the lab vector from the plate's origin to root r's frame origin (its base's foot) [m]
  Vec3 offset(int r) const;
  RootPairForces pairForces(int a, int b) const;

 private:
  // the capsules of the other roots near root r, into its contact pieces (ContactWorkspace::neighbours)
  void listNeighbours(int r);
  void indexElements();
  // root r's capsules where their roots are now (the lists kept)
  void refreshCapsules(int r);
  // every root within reach of another relaxes again (Newton); returns the largest node displacement
  double sweep();
  // the roots within reach of another relax together, explicitly, one sub-step each in turn
  void relaxJointly();
  PlateStepRecord observe(int sweeps) const;

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
  std::vector<int> capsuleOf_;     // global element -> capsule index in the list being built (-1: none)
  double cellSize_ = 0;
};

}  // namespace rootsim
