#pragma once
// shared set-up for mechanics tests: a horizontal cantilever (alpha = 90 deg, plane off) along -y,
// d1 = x, d2 = z, d3 = -y, clamped at the origin side
#include <array>
#include <vector>
#include <Eigen/Dense>

#include "rootsim/forces.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/relax.hpp"
#include "rootsim/relax_dynamic.hpp"
#include "rootsim/relax_newton.hpp"
#include "rootsim/rotation.hpp"

namespace rootsim::test {

struct Cantilever {
  RodParams p;
  Environment env;
  SolverOptions opt;
  RodState s;
  RelaxWorkspace ws;
  double L;

  Cantilever(int n, double length = 1e-2, double forceTol = 1e-8) : L(length) {
    env.plane.enabled = false;
    env.plane.alpha = 1.5707963267948966;
    env.adhesion = false;
    opt.forceTol = forceTol;
    opt.speedTol = 1e-9;
    InitialShape sh;
    sh.length = length;
    sh.elementLength = length / n;
    sh.perturbation = 0.0;
    s = makeInitialRod(p, env.plane, sh);
  }
  double B1() const { return p.bendStiffness().x(); }
  Vec3 tip() const { return s.x.col(s.nodes() - 1) - s.x.col(0); }
  RelaxResult relax() { return rootsim::relax(p, env, opt, s, ws); }
};


// K = -dF/du of state s over the given unknowns (block b: node b / 2 when even, element b / 2 when odd;
// component c), one dof at a time by central differences, dense, in the Newton solver's scaled units
// (rotations times the mean element length, couples over it)
inline Eigen::MatrixXd oneDofStiffness(const RodParams& p, const Environment& env, const RodState& s,
                                      RelaxWorkspace& ws, const std::vector<std::array<int, 2>>& unknowns) {
  const int n = s.elements(), N = static_cast<int>(unknowns.size());
  const double lbar = s.restLength() / n, h = 1e-6 * lbar;
  auto forces = [&](const RodState& st) {
    computeForces(p, env, st, false, ws);
    Eigen::VectorXd f(N);
    for (int k = 0; k < N; ++k) {
      const auto [b, c] = unknowns[static_cast<size_t>(k)];
      f[k] = b % 2 == 0 ? ws.force(c, b / 2) : ws.torque(c, b / 2) / lbar;
    }
    return f;
  };
  Eigen::MatrixXd K(N, N);
  for (int k = 0; k < N; ++k) {
    const auto [cb, cc] = unknowns[static_cast<size_t>(k)];
    RodState plus = s, minus = s;
    Vec3 u = Vec3::Zero();
    u[cc] = h;
    if (cb % 2 == 0) {
      plus.x.col(cb / 2) += u;
      minus.x.col(cb / 2) -= u;
    } else {
      rotateInPlace(-u / lbar, plus.Q[static_cast<size_t>(cb / 2)]);
      rotateInPlace(u / lbar, minus.Q[static_cast<size_t>(cb / 2)]);
    }
    K.col(k) = -(forces(plus) - forces(minus)) / (2 * h);
  }
  return K;
}

// the same over all blocks from b0 on
inline Eigen::MatrixXd oneDofStiffness(const RodParams& p, const Environment& env, const RodState& s,
                                      RelaxWorkspace& ws, int b0) {
  std::vector<std::array<int, 2>> unknowns;
  for (int b = b0; b <= 2 * s.elements(); ++b)
    for (int c = 0; c < 3; ++c) unknowns.push_back({b, c});
  return oneDofStiffness(p, env, s, ws, unknowns);
}

// the Jacobian of assembleStiffness as a dense matrix: its band and its off-band (self-contact) entries
inline Eigen::MatrixXd assembledStiffness(const NewtonWorkspace& nw) {
  const int N = nw.lu.size();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
      if (nw.lu.inBand(i, j)) K(i, j) = nw.lu.at(i, j);
  for (const OffBandEntry& e : nw.offBand) K(e.row, e.col) += e.value;
  return K;
}

}  // namespace rootsim::test
