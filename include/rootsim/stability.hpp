#pragma once
// Stability of a relaxed equilibrium (docs/model.md, Relaxation, "Stability check"): the inertia of the
// stiffness matrix K = -dF/du, found by finite differences on the banded structure of the discrete rod and an
// LDL^T factorisation; and the unstable direction, to follow it when the equilibrium is a saddle.
#include <Eigen/Core>
#include <vector>

#include "rootsim/relax_newton.hpp"

namespace rootsim {

struct StabilityReport {
  int negative = 0;          // negative pivots of K: the number of unstable directions
  double lowest = 0;         // Rayleigh quotient of the mode found, in scaled units [N/m]
  Eigen::VectorXd mode;      // dofs: per node 3 translations [m], per element 3 rotations [rad] (scaled
                             // so that the largest translation is 1); empty when stable
};

// K is evaluated at s (which must be an equilibrium of env); rotations are scaled by the mean element
// length so that translations and rotations have comparable units
StabilityReport checkStability(const RodParams& p, const Environment& env, const RodState& s,
                               RelaxWorkspace& ws);

// the k stiffness modes of state s nearest zero stiffness (the k softest while s is stable), from the
// symmetric part of the band Jacobian over the whole rod (the Newton solver's, relax.hpp) by subspace
// inverse iteration with Rayleigh-Ritz; eigenvalues ascending, in the scaled units of
// StabilityReport::lowest [N/m]; each mode as StabilityReport::mode (largest translation 1)
struct StiffnessModes {
  Eigen::VectorXd eigenvalues;            // (k)
  std::vector<Eigen::VectorXd> modes;     // (k) x (6 n + 3)
};
StiffnessModes softestModes(const RodParams& p, const Environment& env, const RodState& s, int k);

// moves the state along a mode by amplitude [m] (largest node displacement)
void perturbAlong(RodState& s, const Eigen::VectorXd& mode, double amplitude);

}  // namespace rootsim
