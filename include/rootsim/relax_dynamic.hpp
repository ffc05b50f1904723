#pragma once
// The explicit damped relaxation (docs/model.md, Relaxation; relax_dynamic.cpp): the paper's solver, and
// the Newton solver's fallback.
#include <string>

#include "rootsim/environment.hpp"
#include "rootsim/relax.hpp"

namespace rootsim {

// the relaxation loop, one sub-step at a time (relax() runs it to the end); holds references to its
// arguments, which must outlive it
class DynamicRelaxation {
 public:
  // firstFreeNode > 0: only the nodes and elements from there on move (the rest, twists included,
  // stays exactly), and the equilibrium criterion covers those only: the Newton solver's fallback
  // relaxes its window so (the explicit solver proper relaxes the whole rod)
  DynamicRelaxation(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                    RelaxWorkspace& ws, int firstFreeNode = 0);
  // one sub-step; true when the state is in equilibrium (velocities are then zeroed); throws
  // RelaxError when a force or couple is not finite, or when a node slides without bound (no static
  // equilibrium: it moved more than kSlideLengths * Lref within the relaxation). Allocates nothing.
  bool step();
  const RelaxResult& result() const { return res_; }
  std::string describeFailure() const;

 private:
  // the pieces of one sub-step, in the order step() runs them (relax_dynamic.cpp's header lists it)
  struct FirePowers { double P = 0, vm2 = 0, fm2 = 0; };
  void drift(double h);
  bool inEquilibrium();
  void checkSliding() const;
  FirePowers firePowers() const;
  void fireDamping(double P);
  void fireKick(FirePowers pw);
  void viscousKick();

  const RodParams& p_;
  const Environment& env_;
  const SolverOptions& opt_;
  RodState& s_;
  RelaxWorkspace& ws_;
  double ftol2_ = 0, mtol2_ = 0, xtol_ = 0, rtol_ = 0;
  double dtMax_ = 0, dt_ = 0, pendingDrift_ = 0, alpha_ = 0, viscousFactor_ = 1, slideLimit_ = 0;
  int npos_ = 0, argF_ = 0, argM_ = 0;
  int free_ = 0;     // the first node and element that move
  ForceSpan span_;   // what computeForces evaluates: from the element before free_ (its force and
                     // plate contact act on node free_, its Voronoi couple on element free_)
  RelaxResult res_;
};

// a node that moves more than this many Lref within one relaxation is sliding away: no static
// equilibrium (docs/model.md, Contact and friction). A clamped rod's node moves at most twice its arc length;
// a growing root's snap moves its tip by less than the growth zone (Lref).
inline constexpr double kSlideLengths = 3.0;

// relaxes the rod to equilibrium under env; throws RelaxError on divergence or on hitting the cap
RelaxResult relax(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                  RelaxWorkspace& ws, int firstFreeNode = 0);

}  // namespace rootsim
