#pragma once
// The equilibrium criterion both solvers share (docs/numerics.md; tolerance.cpp).
#include "rootsim/environment.hpp"
#include "rootsim/relax.hpp"

namespace rootsim {

// The equilibrium tolerance of both solvers (tolerance.cpp): the largest residual force on a free node
// and couple on a free element that count as equilibrium, with E = B1/Lref^2:
//   force = forceTol * E                                         without applied loads, or A >= E,
//   force = max(forceTol * A, min(forceTol * E, kResolvableResidual * r))   when the applied loads A < E,
//   couple = forceTol * B1/Lref, or max(forceTol * A Lref, min(forceTol B1/Lref, kResolvableResidual r Lref)),
// r the round-off of a node force (machine epsilon * largest EA/l * largest |x|),
// A the largest applied load per node (appliedLoadScale: the weight lumped to a free node, the tip
// force, the tip couple / Lref). B1/Lref^2 is the scale of the forces that growth and tropism make
// (intrinsic curvature over the growth zone Lref); a residual below 1e-4 of it resolves them, but a load
// far below it is not seen at all: a free 2 mm rod's weight pulls each node down a plate at 80 degrees
// with 3e-9 N against a tolerance of 9.8e-8 N, so the rod "converged" unmoved. Contact (plate, self,
// obstacles), friction and adhesion are reactions: in equilibrium they are bounded by the elastic and
// applied loads, so they set no scale of their own; taken as a floor of the tolerance, a penalty's
// overshoot away from equilibrium would loosen it (circular), taken as a bound, a grazing contact would
// make it vanish.
struct EquilibriumTolerance {
  double force = 0;   // [N]
  double couple = 0;  // [N m]
};
EquilibriumTolerance equilibriumTolerance(const RodParams& p, const Environment& env, const SolverOptions& opt,
                                          const RodState& s, int firstFreeNode = 0);
// A [N]: the largest of the tip force, the tip couple / Lref and the weight on nodes firstFreeNode.. n
double appliedLoadScale(const RodParams& p, const Environment& env, const RodState& s, double Lref,
                        int firstFreeNode = 0);
// small loads ask for a residual down to this many times the round-off of a node force, not below (a
// 10 mm cantilever of 0.4 mm elements stalled at 1.3 times that round-off)
inline constexpr double kResolvableResidual = 100.0;

}  // namespace rootsim
