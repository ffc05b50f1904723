// The equilibrium tolerance of both solvers (tolerance.hpp). The rule and why it is
// the rule: docs/model.md, Relaxation (the equilibrium tolerance), and docs/contact.md.
#include "rootsim/tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rootsim/units.hpp"

namespace rootsim {

double appliedLoadScale(const RodParams& p, const Environment& env, const RodState& s, double Lref,
                        int firstFreeNode) {
  const int n = s.elements();
  const int first = std::clamp(firstFreeNode, 0, n);
  double a = env.tipForce.norm();
  a = std::max(a, env.tipTorque.norm() / Lref);
  const double g = env.gravity.norm();
  if (g > 0.0) {
    // the weight lumped to a node: half of each element beside it (addWeight)
    const double rhoAg = p.density * units::pi * p.radius * p.radius * g;
    for (int i = first; i <= n; ++i) {
      const double l = (i > 0 ? s.l0[i - 1] : 0.0) + (i < n ? s.l0[i] : 0.0);
      a = std::max(a, 0.5 * rhoAg * l);
    }
  }
  return a;
}

EquilibriumTolerance equilibriumTolerance(const RodParams& p, const Environment& env, const SolverOptions& opt,
                                          const RodState& s, int firstFreeNode) {
  const double B1 = p.bendStiffness().x();
  const double Lref = opt.lengthScale > 0.0 ? opt.lengthScale : s.restLength();
  const double elastic = B1 / (Lref * Lref);
  const double applied = appliedLoadScale(p, env, s, Lref, firstFreeNode);
  EquilibriumTolerance t;
  if (!(applied > 0.0) || applied >= elastic) {
    // the rod's own scale: what growth and tropism load it with, and at least the applied loads
    t.force = opt.forceTol * elastic;
    t.couple = opt.forceTol * B1 / Lref;
    return t;
  }
  // applied loads below the elastic scale: the residual must be small against them, or a rod that they
  // move (a free rod sliding under its weight) passes as in equilibrium before it has moved
  // (but not below what the force evaluation resolves, unless forceTol * B1/Lref^2 asks for that anyway):
  // its round-off is the stretch stiffness EA/l times the last bit of a node position
  const int n = s.elements();
  double kmax = 0.0;
  for (int i = 0; i < n; ++i) kmax = std::max(kmax, 1.0 / s.l0[i]);
  kmax *= p.shearStiffness().maxCoeff();
  const double roundOff = std::numeric_limits<double>::epsilon() * kmax * s.x.colwise().norm().maxCoeff();
  const double floor = std::min(opt.forceTol * elastic, kResolvableResidual * roundOff);
  t.force = std::max(opt.forceTol * applied, floor);
  t.couple = std::max(opt.forceTol * applied * Lref, std::min(opt.forceTol * B1 / Lref, floor * Lref));
  return t;
}

}  // namespace rootsim
