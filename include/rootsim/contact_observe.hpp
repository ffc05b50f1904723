#pragma once
// What is observed of a state's contacts (contact_observe.cpp): the counts each time-series row holds, the
// force per node a snapshot shows.
#include "rootsim/contact.hpp"

namespace rootsim {

// contact counts of a state; allocates nothing once cw is sized (use a workspace of its own, not the
// solver's, so that observing never changes when the solver's list is rebuilt)
struct ContactCounts {
  int selfContacts = 0;          // element pairs in self-contact (gap < 0)
  int obstacleContacts = 0;      // elements touching an obstacle
  double minSelfDistance = 0.0;  // smallest centreline distance of elements at least 3R apart along the
                                 // rod / R, over pairs within 2R + skin (NaN when there are none)
};
ContactCounts countContacts(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw);

// the counts and the contact force on each node (for snapshots; allocates)
struct ContactObservables : ContactCounts {
  Eigen::Matrix3Xd perNode;      // |force| on each node from the plate (with friction), from self-
                                 // contact and from obstacles (with friction) [N]  (3 x n+1)
};
ContactObservables observeContacts(const RodParams& p, const Environment& env, const RodState& s);

}  // namespace rootsim
