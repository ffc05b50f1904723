#pragma once
// The stiffness K = -dF/du of the discrete rod in closed form (docs/model.md, Newton solver): the derivative
// of exactly what computeStrains / computeInternalForces (rod.cpp) and the outside pieces of environment.cpp
// evaluate, for the Newton solver's Jacobian. tests/test_stiffness.cpp checks it against central
// differences of computeForces, one dof at a time; the solver's coloured finite differences stay as the
// route for the pieces it does not cover (stiffnessInClosedForm).
//
// Blocks: b = 2i is node i (translation u [m] in lab components; force [N]), b = 2i + 1 is element i
// (rotation theta [rad] of its directors about their own axes, material components, Q <- exp(-[theta]x) Q
// as the solvers move them; couple [N m], material components).
#include "rootsim/environment.hpp"
#include "rootsim/rod.hpp"

namespace rootsim {

// where the blocks go (the Newton solver scales them and keeps those of its unknowns)
class StiffnessSink {
 public:
  virtual ~StiffnessSink() = default;
  // K(rowBlock, colBlock) += k
  virtual void add(int rowBlock, int colBlock, const Mat3& k) = 0;
  // K(twist of element re, twist of element ce) += k: the (2, 2) entry of their element blocks
  virtual void addTwist(int re, int ce, double k) = 0;
};

// true when every force piece env switches on has its stiffness here: all but obstacles and friction
// (their stick points and contact geometry are differenced by the solver); self-contact has its own,
// pair by pair (contact_newton.hpp: selfContactStiffness)
bool stiffnessInClosedForm(const Environment& env);

// the stiffness of the rod's internal forces and couples, the clamp's couple, the tip couple, plate
// contact (without damping) and adhesion, at state s whose strains k are current (computeStrains over
// the whole rod). The nodes before firstFreeNode do
// not move and the elements before it turn only about d3 (the Newton solver's window): blocks that only
// those touch get only their twist entries (addTwist), and no block is added for a frozen node's row.
// Allocates nothing.
void addStiffness(const RodParams& p, const Environment& env, const RodState& s, const RodStrains& k,
                  int firstFreeNode, StiffnessSink& sink);

}  // namespace rootsim
