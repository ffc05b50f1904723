#include "rootsim/contact.hpp"
#include "rootsim/contact_newton.hpp"
#include "rootsim/forces.hpp"
#include "rootsim/rotation.hpp"
#include "rootsim/stability.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/Dense>

#include <algorithm>

#include <cmath>
#include <vector>


namespace rootsim {

namespace {

// dof layout: block b = 2i is node i (3 translations), b = 2i + 1 is element i (3 rotations);
// a clamped base removes node 0's block from the unknowns (its rows and columns are skipped)
struct Layout {
  int n;              // elements
  bool clamped;
  int blocks() const { return 2 * n + 1; }
  bool isNode(int b) const { return b % 2 == 0; }
  int index(int b) const { return b / 2; }
  bool free(int b) const { return !(clamped && b == 0); }
};

// applies u_k += h to dof (block b, component c): translation in metres, rotation (material frame,
// about the element's own axes, as the relaxation integrates angular velocity) in radians
void nudge(RodState& s, const Layout& L, int b, int c, double h) {
  if (L.isNode(b)) {
    s.x(c, L.index(b)) += h;
  } else {
    Vec3 phi = Vec3::Zero();
    phi[c] = h;
    Mat3& Q = s.Q[static_cast<size_t>(L.index(b))];
    Q = (rotationFromVector(-phi) * Q).eval();
  }
}

// generalized force of block b, component c
double genForce(const RelaxWorkspace& ws, const Layout& L, int b, int c) {
  return L.isNode(b) ? ws.force(c, L.index(b)) : ws.torque(c, L.index(b));
}

}  // namespace

StabilityReport checkStability(const RodParams& p, const Environment& env, const RodState& s0,
                               RelaxWorkspace& ws) {
  const int n = s0.elements();
  Layout L{n, env.base == BaseCondition::Clamped};
  const double lbar = s0.restLength() / n;  // rotation dof scaled to a length: u_rot = lbar * theta
  const int N = 3 * L.blocks();
  // interaction radius: a dof of block b changes forces of blocks b-4 .. b+4 (strains of the two
  // neighbouring elements, their Voronoi dilatations and curvatures)
  constexpr int kRadius = 4, kStride = 2 * kRadius + 1;
  const double hx = 1e-7 * lbar;  // finite-difference step [m] (and hx / lbar rad for rotations)

  RodState s = s0;
  computeForces(p, env, s, false, ws);
  Eigen::Matrix3Xd f0 = ws.force, t0 = ws.torque;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(N) * 3 * kStride);
  // self-contact couples nodes far apart along the rod (off the band): a node in a self-contact pair
  // is nudged alone and its whole column is read; the coloured passes skip it, so no other column of
  // its colour picks up its far coupling
  markSelfContactNodes(p, env, s0, ws.contact);
  const std::vector<std::uint8_t> offBand = ws.contact.contactNode;
  auto alone = [&](int b) { return L.isNode(b) && offBand[static_cast<size_t>(L.index(b))]; };
  auto entry = [&](int rb, int rc, int col) {
    const double f1 = genForce(ws, L, rb, rc);
    const double f00 = L.isNode(rb) ? f0(rc, L.index(rb)) : t0(rc, L.index(rb));
    // K = -dF/du in scaled units: torques / lbar, rotations * lbar
    double k = -(f1 - f00) / hx;
    if (!L.isNode(rb)) k /= lbar;
    if (k != 0.0) trip.emplace_back(3 * rb + rc, col, k);
  };
  for (int color = 0; color < kStride; ++color) {
    for (int c = 0; c < 3; ++c) {
      s = s0;
      for (int b = color; b < L.blocks(); b += kStride)
        if (L.free(b) && !alone(b)) nudge(s, L, b, c, L.isNode(b) ? hx : hx / lbar);
      computeForces(p, env, s, false, ws);
      for (int b = color; b < L.blocks(); b += kStride) {
        if (!L.free(b) || alone(b)) continue;
        for (int rb = std::max(0, b - kRadius); rb <= std::min(L.blocks() - 1, b + kRadius); ++rb)
          if (L.free(rb))
            for (int rc = 0; rc < 3; ++rc) entry(rb, rc, 3 * b + c);
      }
    }
  }
  for (int b = 0; b < L.blocks(); ++b) {
    if (!L.free(b) || !alone(b)) continue;
    for (int c = 0; c < 3; ++c) {
      s = s0;
      nudge(s, L, b, c, hx);
      computeForces(p, env, s, false, ws);
      for (int rb = 0; rb < L.blocks(); ++rb)
        if (L.free(rb))
          for (int rc = 0; rc < 3; ++rc) entry(rb, rc, 3 * b + c);
    }
  }
  // clamped dofs: identity rows/columns so the matrix stays square and their pivots positive
  if (L.clamped)
    for (int c = 0; c < 3; ++c) trip.emplace_back(c, c, 1.0);
  Eigen::SparseMatrix<double> K(N, N);
  K.setFromTriplets(trip.begin(), trip.end());
  Eigen::SparseMatrix<double> Ks = 0.5 * (K + Eigen::SparseMatrix<double>(K.transpose()));
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Ks);
  StabilityReport r;
  if (ldlt.info() != Eigen::Success) {
    r.negative = 1;  // a singular factorisation: treat as not provably stable
  } else {
    const Eigen::VectorXd D = ldlt.vectorD();
    const double scale = D.cwiseAbs().maxCoeff();
    for (int i = 0; i < N; ++i) r.negative += D[i] < -1e-10 * scale;
  }
  if (r.negative == 0) return r;
  // the unstable direction: inverse iteration with the factorisation, v <- K^-1 v, which converges to
  // the eigenvector of the eigenvalue nearest zero; near the loss of stability that is the negative one
  Eigen::VectorXd v = Eigen::VectorXd::Ones(N);
  for (int i = 0; i < N; ++i) v[i] = std::sin(1.0 + 12.9898 * i);  // deterministic start
  if (L.clamped) v.head(3).setZero();
  for (int it = 0; it < 30 && ldlt.info() == Eigen::Success; ++it) {
    v = ldlt.solve(v);
    if (L.clamped) v.head(3).setZero();
    v.normalize();
  }
  r.lowest = v.dot(Ks * v);
  // back to physical dofs: rotations = u_rot / lbar; normalise the largest translation to 1
  double big = 0;
  for (int b = 0; b < L.blocks(); ++b) {
    if (!L.isNode(b)) v.segment<3>(3 * b) /= lbar;
    else big = std::max(big, v.segment<3>(3 * b).norm());
  }
  r.mode = big > 0 ? Eigen::VectorXd(v / big) : v;
  return r;
}

StiffnessModes softestModes(const RodParams& p, const Environment& env, const RodState& s0, int k) {
  RodState s = s0;
  RelaxWorkspace ws;
  NewtonWorkspace nw;
  SolverOptions opt;
  assembleStiffness(p, env, opt, s, ws, nw, 0);
  const int N = nw.lu.size(), band = nw.lu.kl();
  BandLDLT f;
  f.reset(N, band);
  for (int j = 0; j < N; ++j)
    for (int i = j; i <= std::min(N - 1, j + band); ++i) f.addLower(i, j, 0.5 * (nw.lu.at(i, j) + nw.lu.at(j, i)));
  if (!f.factorize()) throw RelaxError("modes: the stiffness of the final state is singular");
  // dense copy of the symmetric matrix for the Rayleigh quotients (N ~ 6 n, fine for one state)
  auto Kx = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(N);
    for (int j = 0; j < N; ++j)
      for (int i = std::max(0, j - band); i <= std::min(N - 1, j + band); ++i)
        y[i] += 0.5 * (nw.lu.at(i, j) + nw.lu.at(j, i)) * x[j];
    return y;
  };
  k = std::clamp(k, 1, N);
  const int m = std::min(N, 2 * k + 4);  // a larger subspace converges faster to the k wanted
  Eigen::MatrixXd V(N, m);
  for (int c = 0; c < m; ++c)
    for (int i = 0; i < N; ++i) V(i, c) = std::sin(1.0 + 12.9898 * i + 78.233 * c);  // deterministic
  for (int it = 0; it < 60; ++it) {
    for (int c = 0; c < m; ++c) {
      Eigen::VectorXd col = V.col(c);
      f.solve(col.data());
      V.col(c) = col;
    }
    V = Eigen::HouseholderQR<Eigen::MatrixXd>(V).householderQ() * Eigen::MatrixXd::Identity(N, m);
  }
  Eigen::MatrixXd KV(N, m);
  for (int c = 0; c < m; ++c) KV.col(c) = Kx(V.col(c));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(V.transpose() * KV);
  // Ritz values nearest zero, ascending
  std::vector<int> order(static_cast<size_t>(m));
  for (int i = 0; i < m; ++i) order[static_cast<size_t>(i)] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(es.eigenvalues()[a]) < std::abs(es.eigenvalues()[b]); });
  order.resize(static_cast<size_t>(k));
  std::sort(order.begin(), order.end(), [&](int a, int b) { return es.eigenvalues()[a] < es.eigenvalues()[b]; });
  const int n = s.elements();
  const double lbar = s.restLength() / n;
  const int b0 = env.base == BaseCondition::Clamped ? 1 : 0;
  StiffnessModes out;
  out.eigenvalues.resize(k);
  for (int q = 0; q < k; ++q) {
    const int c = order[static_cast<size_t>(q)];
    out.eigenvalues[q] = es.eigenvalues()[c];
    const Eigen::VectorXd v = V * es.eigenvectors().col(c);
    Eigen::VectorXd mode = Eigen::VectorXd::Zero(6 * n + 3);
    double big = 0;
    for (int b = b0; b <= 2 * n; ++b) {
      Vec3 u = v.segment<3>(3 * (b - b0));
      if (b % 2 == 1) u /= lbar;
      else big = std::max(big, u.norm());
      mode.segment<3>(3 * b) = u;
    }
    if (big > 0) mode /= big;
    out.modes.push_back(mode);
  }
  return out;
}

void perturbAlong(RodState& s, const Eigen::VectorXd& mode, double amplitude) {
  const int n = s.elements();
  for (int i = 0; i <= n; ++i) s.x.col(i) += amplitude * mode.segment<3>(6 * i);
  for (int i = 0; i < n; ++i) {
    const Vec3 phi = amplitude * mode.segment<3>(6 * i + 3);
    s.Q[static_cast<size_t>(i)] = (rotationFromVector(-phi) * s.Q[static_cast<size_t>(i)]).eval();
  }
}

}  // namespace rootsim
