#pragma once
// What a run watches across its growth steps (run_watch.cpp): the moments summary.json and result.csv
// report (the first sideways snap, a free organ's turning time) and the extremes of the steps (sub-steps,
// self-contacts, the closest self-approach). One record per step goes in; a checkpoint carries it.
#include <limits>

#include "rootsim/fields.hpp"
#include "rootsim/simulation.hpp"

namespace rootsim {

struct RunWatch {
  // the first time the tip leaves the downhill direction by more than 30 degrees (the first sideways
  // snap) [h]; and, for a free organ (theta_tip measured from gravity, starting at -alpha), the first
  // time the tip reaches the vertical: the measured turning time of Eq. 7 [h], interpolated linearly in
  // theta between the two growth steps around the crossing (a growth step is 0.05 h; the turning time
  // can be < 1 h). NaN until seen.
  double snapFirst = std::numeric_limits<double>::quiet_NaN();
  double snapVertical = std::numeric_limits<double>::quiet_NaN();
  double prevTheta = std::numeric_limits<double>::quiet_NaN();  // the last record's tip angle [rad]
  double prevTime = std::numeric_limits<double>::quiet_NaN();   // and time [h]
  long maxSubsteps = 0;                  // the most explicit sub-steps of one step
  int maxSelfContacts = 0;               // the most element pairs in self-contact at once
  double minSelfDistance = std::numeric_limits<double>::quiet_NaN();  // closest self-approach / R (NaN:
                                         // never within 3R)

  // the initial state (step 0): remembered as the step before the first, its counts taken as they are
  void start(const StepRecord& r);
  // a growth step's record
  void see(const StepRecord& r);
  // in the checkpoint's order (fields.hpp)
  static constexpr auto fields() {
    using W = RunWatch;
    return std::tuple{field("snapFirst", &W::snapFirst), field("snapVertical", &W::snapVertical),
                      field("snapPrevTheta", &W::prevTheta), field("snapPrevTime", &W::prevTime),
                      field("maxSubsteps", &W::maxSubsteps), field("maxSelfContacts", &W::maxSelfContacts),
                      field("minSelfDistance", &W::minSelfDistance)};
  }

 private:
  void seeAngle(const StepRecord& r);
};

}  // namespace rootsim
