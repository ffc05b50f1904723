// What a run watches across its growth steps (run_watch.hpp).
#include "rootsim/run_watch.hpp"

#include <algorithm>
#include <cmath>

#include "rootsim/units.hpp"

namespace rootsim {

void RunWatch::seeAngle(const StepRecord& r) {
  if (std::isnan(snapFirst) && std::abs(r.thetaTip) > 30.0 * units::deg && r.step > 0) snapFirst = r.timeH;
  if (std::isnan(snapVertical) && r.thetaTip >= 0.0 && r.step > 0)
    snapVertical = std::isfinite(prevTheta) && prevTheta < 0.0
                       ? prevTime + (r.timeH - prevTime) * (-prevTheta) / (r.thetaTip - prevTheta)
                       : r.timeH;
  prevTheta = r.thetaTip;
  prevTime = r.timeH;
}

void RunWatch::start(const StepRecord& r) {
  seeAngle(r);
  maxSubsteps = r.substeps;
  maxSelfContacts = r.selfContacts;
  minSelfDistance = r.minSelfDistance;
}

void RunWatch::see(const StepRecord& r) {
  maxSubsteps = std::max(maxSubsteps, r.substeps);
  maxSelfContacts = std::max(maxSelfContacts, r.selfContacts);
  if (std::isnan(minSelfDistance) || r.minSelfDistance < minSelfDistance) minSelfDistance = r.minSelfDistance;
  seeAngle(r);
}

}  // namespace rootsim
