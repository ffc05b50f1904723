#pragma once
// The force evaluation every solver, the stability check and the tests share (forces.cpp): the
// sub-step's strains, internal forces, external pieces and the clamp, in that order.
#include "rootsim/environment.hpp"
#include "rootsim/relax.hpp"

namespace rootsim {

// evaluates all forces of state s into ws.force / ws.torque (used by both solvers, the stability check
// and tests); first > 0: exact only on the nodes and elements after `first` (rod.hpp), for the Newton
// solver's window; pieces: ForcePieces::NoPairContact leaves self-contact and the contact with other roots out (environment.hpp)
void computeForces(const RodParams& p, const Environment& env, const RodState& s, bool planeDamping,
                   RelaxWorkspace& ws, int first = 0, ForcePieces pieces = ForcePieces::All);
// the same over a part of the rod (environment.hpp: ForceSpan)
void computeForces(const RodParams& p, const Environment& env, const RodState& s, bool planeDamping,
                   RelaxWorkspace& ws, ForceSpan span, ForcePieces pieces = ForcePieces::All);

}  // namespace rootsim
