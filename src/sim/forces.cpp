// The force evaluation of a rod state (forces.hpp): the sub-step pieces 2-5 of relax_dynamic.cpp's list.
#include "rootsim/forces.hpp"

#include "rootsim/assert.hpp"

namespace rootsim {

void computeForces(const RodParams& p, const Environment& env, const RodState& s, bool planeDamping,
                   RelaxWorkspace& ws, int first, ForcePieces pieces) {
  computeForces(p, env, s, planeDamping, ws, ForceSpan{first, -1, first}, pieces);
}

void computeForces(const RodParams& p, const Environment& env, const RodState& s, bool planeDamping,
                   RelaxWorkspace& ws, ForceSpan span, ForcePieces pieces) {
  ROOTSIM_ASSERT(s.elements() >= 1 && s.x.cols() == s.nodes() && static_cast<int>(s.Q.size()) == s.elements(),
                 "a rod state whose fields agree on the element count");
  if (ws.force.cols() != s.nodes()) ws.resize(s.elements());
  computeStrains(p, s, ws.strains, span.first, span.end);                              // 2.
  computeInternalForces(s, ws.strains, ws.force, ws.torque, span.first, span.end);     // 3.
  addExternalForces(p, env, s, ws.strains, planeDamping, ws.contact, ws.force, ws.torque, span, pieces);  // 4.
  holdClampedBase(env, ws.force);                                                      // 5.
}

}  // namespace rootsim
