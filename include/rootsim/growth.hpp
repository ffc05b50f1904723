#pragma once
// Growth of the root (docs/model.md, Growth): the growth zone, rest-length growth, remeshing by splitting,
// the intrinsic-curvature law (paper Eqs. 17-19), the intrinsic twist profile (Eqs. 20-21), and the
// adhesion of material that leaves the zone (section 6).
#include "rootsim/model.hpp"

namespace rootsim {

// material coordinate where the growth zone starts: max(L - Lgz, 0) [m]
double growthZoneStart(const Model& m, const RodState& s);

// pins every node that has left the growth zone to where it is now (after the previous relaxation)
void anchorMatureNodes(const Model& m, RodState& s);

// grows rest lengths in the zone by eps0 * dt (pro rata for the element straddling the zone start) and
// stretches the current shape with them, so the tip advances by v_tip dt; returns the length added [m]
double growRestLengths(const Model& m, RodState& s, double dt);

// the gravitropic set-point angle of an organ of age `age` [s] (since it emerged; a seedling's: since the
// run began) [rad]: setPoint at age 0, drifting to setPointFinal, linearly (reached at
// setPointDriftTime, then held) or exponentially (time constant setPointDriftTime); exactly setPoint
// without setPointFinal or when it equals setPoint, and exactly setPointFinal once reached (linear) or when the exponential
// underflows
double setPointAt(const TropismParams& tp, double age);

// kappa0 update of one growth step (Eq. 17): for Voronoi nodes in the zone,
// d kappa0 / dt = (eps0 / R) (d3 x Delta) in d1, d2 components, Delta = beta Rs g - gamma R kappa N
// + circumnutation, g turned to the set-point direction at the organ's age at the step's start (s.time
// minus m.initial.startTime); strains must be those of the current (relaxed) state
void updateIntrinsicCurvature(const Model& m, RodState& s, const RodStrains& k, double dt);

// kappa0_3 = tau clamp((L - S) / Lgz, 0, 1) at every Voronoi node (Eqs. 20-21)
void applyTwistProfile(const Model& m, RodState& s);

// splits every element longer than splitFactor * h in two, keeping centreline, directors, kappa0 and
// anchors; returns the number of splits
int splitLongElements(const Model& m, RodState& s);

}  // namespace rootsim
