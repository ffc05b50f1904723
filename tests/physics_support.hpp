#pragma once
// Physics test fixtures shared by the physics tests (rootsim_tests): a horizontal cantilever, the
// one-dof-at-a-time stiffness and the assembled Newton Jacobian, the Euler elastica reference, and the
// counter of heap allocations (count_allocations.cpp); the tolerance helper: tolerance_support.hpp.
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <utility>
#include <vector>
#include <Eigen/Dense>

#include "rootsim/contact.hpp"
#include "rootsim/forces.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/model.hpp"
#include "rootsim/relax.hpp"
#include "rootsim/relax_dynamic.hpp"
#include "rootsim/relax_newton.hpp"
#include "rootsim/rotation.hpp"
#include "tolerance_support.hpp"

namespace rootsim::test {

// --- a horizontal cantilever (alpha = 90 deg, plane off) along -y, d1 = x, d2 = z, d3 = -y, clamped at
// the origin side ---
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

// --- the Euler elastica: a cantilever clamped at s = 0 along +xi, dead load P at the tip along -eta. With
// theta the tangent angle, B theta'' = P cos(theta), theta(0) = 0, theta'(L) = 0, solved by shooting on
// theta'(0) (bisection) with classical RK4 ---
struct ElasticaTip { double xi, eta, theta; };  // tip position / L and tip angle

// load = P L^2 / B; returns the tip of the unit-length rod
inline ElasticaTip elasticaTip(double load, int steps = 4000) {
  auto integrate = [&](double k0) {
    // state (theta, theta', xi, eta) over s in [0, 1]
    double y[4] = {0.0, k0, 0.0, 0.0};
    const double h = 1.0 / steps;
    auto f = [&](const double* a, double* d) {
      d[0] = a[1];
      d[1] = load * std::cos(a[0]);
      d[2] = std::cos(a[0]);
      d[3] = std::sin(a[0]);
    };
    for (int i = 0; i < steps; ++i) {
      double k1[4], k2[4], k3[4], k4[4], t[4];
      f(y, k1);
      for (int j = 0; j < 4; ++j) t[j] = y[j] + 0.5 * h * k1[j];
      f(t, k2);
      for (int j = 0; j < 4; ++j) t[j] = y[j] + 0.5 * h * k2[j];
      f(t, k3);
      for (int j = 0; j < 4; ++j) t[j] = y[j] + h * k3[j];
      f(t, k4);
      for (int j = 0; j < 4; ++j) y[j] += h / 6.0 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    }
    return ElasticaTip{y[2], y[3], y[0]};
  };
  auto endSlope = [&](double k0) {
    // theta'(1) = k0 + load * int cos(theta) = k0 + load * xi(1)
    const ElasticaTip t = integrate(k0);
    return k0 + load * t.xi;
  };
  double lo = -load, hi = 0.0;  // |theta'(0)| <= P L / B
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (endSlope(mid) > 0.0) hi = mid; else lo = mid;
  }
  return integrate(0.5 * (lo + hi));
}

// observed convergence order from errors at resolutions n1 < n2
inline double order(double err1, double err2, double n1, double n2) {
  return std::log(err1 / err2) / std::log(n2 / n1);
}

// --- a coarse growth model: 0.1 mm elements (10 in the zone), 0.1 h steps ---
inline Model coarse(double alphaDeg, double beta, int steps) {
  Model m;
  m.env.plane.alpha = alphaDeg * (std::numbers::pi / 180.0);
  m.tropism.beta = beta;
  m.initial.elementLength = 1e-4;
  m.growth.stepTime = 0.1 * 3600;
  m.growth.steps = steps;
  completeModel(m);
  return m;
}

// --- self-contact geometry by brute force ---
// a hairpin of elements 0.5 R long: up along +y at x = 0 for 12 R, across to x = gap, back down
inline RodState hairpin(const RodParams& p, double gap) {
  const double R = p.radius, l = 0.5 * R;
  std::vector<Vec3> pts;
  for (int i = 0; i <= 24; ++i) pts.push_back(Vec3(0, i * l, 0));
  const int across = static_cast<int>(std::ceil(gap / l));
  for (int i = 1; i <= across; ++i) pts.push_back(Vec3(gap * i / across, 24 * l, 0));
  for (int i = 1; i <= 24; ++i) pts.push_back(Vec3(gap, (24 - i) * l, 0));
  RodState s;
  s.resize(static_cast<int>(pts.size()) - 1);
  s.S[0] = 0.0;
  for (int i = 0; i < s.nodes(); ++i) s.x.col(i) = pts[static_cast<size_t>(i)];
  for (int i = 0; i < s.elements(); ++i) s.S[i + 1] = s.S[i] + (s.x.col(i + 1) - s.x.col(i)).norm();
  return s;
}
// every element pair self-contact considers (not excluded along the rod) whose segments come closer than
// reach, by brute force over all pairs, sorted
inline std::vector<std::array<int, 2>> closePairs(const RodParams& p, const RodState& s, double reach) {
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i < s.elements(); ++i)
    for (int j = i + 2; j < s.elements(); ++j) {
      if (s.S[j] - s.S[i + 1] < kSelfExclusionRadii * p.radius) continue;
      double a = 0, b = 0;
      closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), a, b);
      const Vec3 d = (s.x.col(i) + a * (s.x.col(i + 1) - s.x.col(i))) - (s.x.col(j) + b * (s.x.col(j + 1) - s.x.col(j)));
      if (d.norm() < reach) pairs.push_back({i, j});
    }
  return pairs;
}
// the centreline distance of elements i and j (closest points)
inline double pairDistance(const RodState& s, int i, int j) {
  double a = 0, b = 0;
  closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), a, b);
  return ((s.x.col(i) + a * (s.x.col(i + 1) - s.x.col(i))) - (s.x.col(j) + b * (s.x.col(j + 1) - s.x.col(j)))).norm();
}

// --- heap allocations of this test binary so far: operator new counts them (count_allocations.cpp) ---
extern std::atomic<long> gAllocs;

}  // namespace rootsim::test
