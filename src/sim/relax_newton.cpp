// Quasi-static Newton solver (docs/model.md, Newton solver).
//
// Unknowns: node positions and one incremental rotation per element (material components; directors
// updated by the exponential map, Q <- exp(-[dtheta]x) Q, the same convention as the explicit solver's
// drift). Residual: the explicit solver's forces and couples, from computeForces() (one code path for
// the physics, so the two solvers cannot drift apart). Jacobian K = -dF/du in closed form
// (stiffness.hpp: the derivative of that same force code, checked against differences of it in
// tests/test_stiffness.cpp) wherever it covers the forces in play; with obstacles or friction, by coloured
// finite differences: a dof of block b (node or element) changes the forces of blocks b-3 .. b+3 only (a node
// moves its two elements: their shear and the dilatation of the three Voronoi couples around them, which
// act on the elements i-2 .. i+1; an element's rotation changes its shear and its two curvatures), so
// seven colours x three components x two (central differences) = 42 force evaluations give the whole
// band; rotations are scaled by the mean element length (u = lbar theta, couples / lbar) so that the
// blocks have comparable units. The band (half-bandwidth 11) is factorised by BandLU with partial
// pivoting: K is not symmetric away from equilibrium. Newton steps are damped by Deuflhard's natural monotonicity test (below).
//
// Active window: only the blocks from `firstFreeNode` to the tip are unknowns; the rest is frozen
// exactly (adhered mature material, held by stiff springs, barely moves). The equilibrium criterion is
// the explicit solver's, over the free dofs.
//
// Stability (docs/model.md, Newton solver): at the converged state the symmetric part of K is factorised as
// LDL^T; its negative pivots are the unstable directions (Sylvester), and Lanczos with the
// same factors gives the eigenvalue nearest zero and its mode.
#include "rootsim/relax_newton.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <new>
#include <span>
#include <sstream>
#include <type_traits>
#include <cstdio>
#include <cstdlib>

#include "rootsim/assert.hpp"
#include "rootsim/contact.hpp"
#include "rootsim/contact_newton.hpp"
#include "rootsim/forces.hpp"
#include "rootsim/high_water.hpp"
#include "rootsim/relax_dynamic.hpp"
#include "rootsim/rotation.hpp"
#include "rootsim/stiffness.hpp"
#include "rootsim/tolerance.hpp"

namespace rootsim {

namespace {

constexpr int kForceReach = 3;            // blocks whose forces a block's dofs change, each side
constexpr int kColours = 2 * kForceReach + 1;
constexpr int kBand = 3 * kForceReach + 2;  // dof half-bandwidth
constexpr int kTwistRadius = 2;           // blocks whose forces the twist of an element changes, each side
constexpr int kTwistColours = kTwistRadius + 1;  // in elements (a pass nudges every third element)
constexpr int kMaxHalvings = 30;
// Newton crawls towards a snap: the Newton direction of a stiffness near a fold points far off and the
// line search keeps a few per cent of it. After this many iterations in a row damped to at most kCrawl,
// the explicit relaxation takes over: it snaps in a few hundred sub-steps, where a crawl would run into
// the iteration cap and relax explicitly anyway (docs/numerics.md, "Fallback").
constexpr int kMaxCrawl = 3;
constexpr double kChordTheta = 0.1;
// Chains of chord steps on sparse factors (self-contact), each contracting by this much or better: a
// sparse LU costs many solves, so reusing it pays; a looser bound lets a coil take another path. On band
// factors, which cost about three solves, chains gain nothing and add explicit sub-steps at snaps.
constexpr double kSparseChordTheta = 0.5;
// The frozen part's twists form a tridiagonal chain whose nodes never move: its stiffness changes only
// with those twists, which a growth step changes by little. Its columns are differenced anew for the
// last kMatureFresh frozen elements (they couple to the window) and for the elements that froze since
// the last time; the others are kept, and the whole chain is differenced anew every kMatureRefresh
// relaxations, after a relaxation that needed the explicit solver, and when a relaxation takes more
// than kMatureTrust iterations. A kept column only slows Newton's convergence by what the stiffness
// changed; the equilibrium and its criterion are the same.
constexpr int kMatureFresh = 3;
constexpr int kMatureRefresh = 128;
constexpr int kMatureTrust = 8;
constexpr double kCrawl = 1.0 / 32.0;
// Lanczos for the eigenvalue nearest zero: at most this many solves, and done when the Ritz pair's
// residual is below kLanczosTol of its value (the value's error is then of the order of its square)
constexpr int kMaxLanczos = 16;
constexpr double kLanczosTol = 1e-5;

// dof layout: block b = 2i is node i, b = 2i + 1 is element i; the unknowns are the twists (rotation
// about d3) of the m elements before the window, then all of blocks [b0, 2n]. The frozen mature root
// keeps its twist free: adhesion holds its nodes, nothing holds the rotation of its elements about their
// axes, and that twist carries the clamp's torque (freezing it changed fig4a's skew by 1.3 degrees).
struct Window {
  int n = 0, b0 = 0;
  int m = 0;  // elements before the window (block 2e + 1 < b0): their twists are unknowns 0 .. m-1
  int blocks() const { return 2 * n + 1 - b0; }
  int dofs() const { return m + 3 * blocks(); }
  int dof(int b, int c) const { return m + 3 * (b - b0) + c; }  // unknown of block b >= b0, component c
  // unknown of block b, component c, or -1 when frozen
  int unknown(int b, int c) const {
    if (b >= b0) return dof(b, c);
    return (!isNode(b) && c == 2) ? b / 2 : -1;
  }
  // the first element whose strains the window's forces need (the one before the first free node, and
  // those whose twist rows a window block's nudge reaches)
  int firstElement() const { return std::max(0, b0 / 2 - 1 - (m > 0 ? kForceReach / 2 + 1 : 0)); }
  // the first element whose outside (node) forces the window's rows need: the element before the first
  // free node (its plate contact acts on that node); the frozen nodes before it are never read
  int outsideFrom() const { return std::max(0, b0 / 2 - 1); }
  // the span of a force evaluation for the residual: the twists of the frozen elements are unknowns,
  // so their couples are needed (strains from element 0), but not the forces on the frozen nodes
  ForceSpan residualSpan() const {
    const int f = m > 0 ? 0 : firstElement();
    return ForceSpan{f, -1, std::max(f, outsideFrom())};
  }
  static bool isNode(int b) { return b % 2 == 0; }
};

Window windowOf(const Environment& env, const RodState& s, int firstFreeNode) {
  Window w;
  w.n = s.elements();
  w.b0 = std::clamp(2 * firstFreeNode, 0, 2 * w.n - 1);
  if (env.base == BaseCondition::Clamped && w.b0 == 0) w.b0 = 1;  // node 0 is held
  w.m = w.b0 / 2;  // b0 is even whenever it is past the clamp (then b0 = 2 * firstFreeNode)
  return w;
}

// generalized force of block b, component c, in scaled units (couples / lbar)
double scaledForce(const RelaxWorkspace& ws, int b, int c, double lbar) {
  return Window::isNode(b) ? ws.force(c, b / 2) : ws.torque(c, b / 2) / lbar;
}

// what moveBlock does to an element for a twist alone (u = (0, 0, lbar theta)): d1 and d2 turn by
// theta about d3, without the general exponential map (the frozen part's twists move at every trial
// step; a series below |theta| = 1e-2, exact to round-off there)
void twistInPlace(double theta, Mat3& Q) {
  const double t2 = theta * theta;
  double c, sn;
  if (t2 < 1e-4) {
    c = 1.0 - t2 * (0.5 - t2 * (1.0 / 24.0 - t2 / 720.0));
    sn = theta * (1.0 - t2 * (1.0 / 6.0 - t2 * (1.0 / 120.0 - t2 / 5040.0)));
  } else {
    c = std::cos(theta);
    sn = std::sin(theta);
  }
  const Eigen::RowVector3d d1 = Q.row(0), d2 = Q.row(1);
  Q.row(0) = c * d1 + sn * d2;
  Q.row(1) = c * d2 - sn * d1;
}

void moveBlock(RodState& s, int b, const Vec3& u, double lbar) {
  if (Window::isNode(b)) s.x.col(b / 2) += u;
  else rotateInPlace(-(u / lbar), s.Q[static_cast<size_t>(b / 2)]);
}

// the closed-form stiffness's blocks into the band, scaled (rotations times lbar, couples over it) and
// only where row and column are unknowns of the window
class BandSink final : public StiffnessSink {
 public:
  BandSink(const Window& w, BandLU& lu, double lbar) : w_(w), lu_(lu), il_(1.0 / lbar) {}
  void add(int rb, int cb, const Mat3& k) override {
    const double scale = (Window::isNode(rb) ? 1.0 : il_) * (Window::isNode(cb) ? 1.0 : il_);
    if (rb >= w_.b0 && cb >= w_.b0) {  // inside the window: the whole block (most of them)
      lu_.addBlock(w_.dof(rb, 0), w_.dof(cb, 0), scale, k);
      return;
    }
    for (int cc = 0; cc < 3; ++cc) {
      const int col = w_.unknown(cb, cc);
      if (col < 0) continue;
      for (int rc = 0; rc < 3; ++rc) {
        const int row = w_.unknown(rb, rc);
        if (row >= 0 && k(rc, cc) != 0.0) lu_.add(row, col, scale * k(rc, cc));
      }
    }
  }
  void addTwist(int re, int ce, double k) override {
    const int row = w_.unknown(2 * re + 1, 2), col = w_.unknown(2 * ce + 1, 2);
    if (row >= 0 && col >= 0 && k != 0.0) lu_.add(row, col, k * il_ * il_);
  }

 private:
  const Window& w_;
  BandLU& lu_;
  double il_;
};

}  // namespace

namespace {
struct NewtonSolver {
  const RodParams& p;
  const Environment& env;
  const SolverOptions& opt;
  RodState& s;
  RelaxWorkspace& ws;
  NewtonWorkspace& nw;
  Window w;
  double lbar = 0, ftol = 0, mtol = 0;

  // forces of the current state; returns |F_scaled|^2 over the free dofs and fills nw.r
  double residual() {
    computeForces(p, env, s, false, ws, w.residualSpan());
    double sum = 0;
    for (int e = 0; e < w.m; ++e) {
      const double f = ws.torque(2, e) / lbar;
      nw.r[static_cast<size_t>(e)] = f;
      sum += f * f;
    }
    for (int b = w.b0; b <= 2 * w.n; ++b)
      for (int c = 0; c < 3; ++c) {
        const double f = scaledForce(ws, b, c, lbar);
        nw.r[static_cast<size_t>(w.dof(b, c))] = f;
        sum += f * f;
      }
    return sum;
  }

  bool converged(RelaxResult& res, int& argF, int& argM) const {
    double maxF2 = 0, maxM2 = 0;
    for (int e = 0; e < w.m; ++e) {
      const double m2 = ws.torque(2, e) * ws.torque(2, e);
      if (!std::isfinite(m2)) fail("couple on element", e, ws.torque.col(e), res.iterations);
      if (m2 > maxM2) { maxM2 = m2; argM = e; }
    }
    for (int b = w.b0; b <= 2 * w.n; ++b) {
      const int i = b / 2;
      if (Window::isNode(b)) {
        const double f2 = ws.force.col(i).squaredNorm();
        if (!std::isfinite(f2)) fail("force on node", i, ws.force.col(i), res.iterations);
        if (f2 > maxF2) { maxF2 = f2; argF = i; }
      } else {
        const double m2 = ws.torque.col(i).squaredNorm();
        if (!std::isfinite(m2)) fail("couple on element", i, ws.torque.col(i), res.iterations);
        if (m2 > maxM2) { maxM2 = m2; argM = i; }
      }
    }
    res.residualForce = std::sqrt(maxF2);
    res.residualTorque = std::sqrt(maxM2);
    return maxF2 < ftol * ftol && maxM2 < mtol * mtol;
  }

  [[noreturn]] static void fail(const char* what, int index, const Vec3& val, long it) {
    std::ostringstream os;
    os << "Newton solver diverged at iteration " << it << ": " << what << " " << index << " is not finite ("
       << val.transpose() << ")";
    throw RelaxError(os.str());
  }

  // the band by coloured central differences of computeForces (all pieces but self-contact), the
  // frozen twists' columns partly kept from earlier Jacobians (keepMature, kMatureRefresh)
  void differenced(double h, bool keepMature) {
    // self-contact couples nodes far apart along the rod: a coloured pass would read a far partner's
    // response into the rows of its own colour's blocks. So the passes leave self-contact out, and its
    // stiffness is added pair by pair below (each pair's force depends on its four nodes only).
    // (the contact with other roots on a plate likewise: jacobian() adds it pair by pair, where a
    // coupled plate also reads its columns of the other root's nodes)
    const ForcePieces pieces =
        env.selfContact.enabled || !ws.contact.neighbours.empty() ? ForcePieces::NoPairContact : ForcePieces::All;
    // one pass of central differences over blocks start, start + stride, ... up to `last`, forces
    // evaluated exactly from element `first` on
    auto pass = [&](int start, int stride, int last, int c, ForceSpan span, int radius) {
      Vec3 u = Vec3::Zero();
      u[c] = h;
      auto blocks = [&](auto&& f) {
        for (int b = start; b <= last; b += stride) f(b);
      };
      // central differences: forward differences leave an O(h) error in the stiff stretch/shear
      // entries that swamps the soft bending modes of a long rod (Newton then crawls)
      blocks([&](int b) {
        if (Window::isNode(b)) nw.save[static_cast<size_t>(b)] = s.x.col(b / 2);
        else nw.saveQ[static_cast<size_t>(b / 2)] = s.Q[static_cast<size_t>(b / 2)];
        moveBlock(s, b, u, lbar);
      });
      computeForces(p, env, s, false, ws, span, pieces);
      blocks([&](int b) {
        for (int rb = std::max(0, b - radius); rb <= std::min(2 * w.n, b + radius); ++rb)
          for (int rc = 0; rc < 3; ++rc) {
            const int row = w.unknown(rb, rc);
            if (row >= 0) nw.r0[static_cast<size_t>(row)] = scaledForce(ws, rb, rc, lbar);
          }
      });
      blocks([&](int b) {
        if (Window::isNode(b)) s.x.col(b / 2) = nw.save[static_cast<size_t>(b)];
        else s.Q[static_cast<size_t>(b / 2)] = nw.saveQ[static_cast<size_t>(b / 2)];
        moveBlock(s, b, -u, lbar);
      });
      computeForces(p, env, s, false, ws, span, pieces);
      blocks([&](int b) {
        const int col = w.unknown(b, c);
        for (int rb = std::max(0, b - radius); rb <= std::min(2 * w.n, b + radius); ++rb)
          for (int rc = 0; rc < 3; ++rc) {
            const int row = w.unknown(rb, rc);
            if (row < 0) continue;
            const double k = -(nw.r0[static_cast<size_t>(row)] - scaledForce(ws, rb, rc, lbar)) / (2.0 * h);
            if (k != 0.0) nw.lu.add(row, col, k);
          }
        if (Window::isNode(b)) s.x.col(b / 2) = nw.save[static_cast<size_t>(b)];
        else s.Q[static_cast<size_t>(b / 2)] = nw.saveQ[static_cast<size_t>(b / 2)];
      });
    };
    for (int colour = 0; colour < kColours; ++colour) {
      const int start = w.b0 + ((colour - w.b0 % kColours) + kColours) % kColours;
      if (start > 2 * w.n) continue;
      for (int c = 0; c < 3; ++c)
        pass(start, kColours, 2 * w.n, c, ForceSpan{w.firstElement(), -1, w.firstElement()}, kForceReach);
    }
    // the mature twists: element blocks 2e + 1 < b0, about d3 only. Turning
    // element e about its own axis changes its shear and the curvatures at its two ends only (its
    // tangent stays: the nodes do not move), so it acts on blocks 2e - 1 .. 2e + 3 (kTwistRadius) and
    // every third element can be nudged in one pass: 3 passes, not 9. The columns of the elements
    // before `keep` come from nw.matureK (kMatureRefresh); their rows are frozen twists only (element e
    // acts on e - 1 .. e + 1 < m - 1). The passes start at `keep` and evaluate from element keep - 2 (the
    // couple on keep - 1 needs the Voronoi domain before it) to b0 / 2 + 3 (their rows reach block
    // b0 + 1, the first free element, whose couple needs the strains of the element after it), with no
    // outside forces on the frozen nodes (never read): they cost what the newly frozen part does.
    const int keep = keepMature ? std::max(0, std::min(nw.matureValid, w.m - kMatureFresh)) : 0;
    const double l2 = lbar * lbar;  // K [N m / rad] = scaled K * lbar^2
    for (int e = 0; e < keep; ++e)
      for (int r = std::max(0, e - 1); r <= e + 1; ++r)
        nw.lu.add(r, e, nw.matureK[3 * static_cast<size_t>(e) + static_cast<size_t>(r - e + 1)] / l2);
    const ForceSpan frozen{std::max(0, keep - 2), std::min(w.n, w.b0 / 2 + 3), w.outsideFrom()};
    for (int colour = 0; colour < kTwistColours && keep + colour < w.m; ++colour)
      pass(2 * (keep + colour) + 1, 2 * kTwistColours, w.b0 - 1, 2, frozen, kTwistRadius);
    const int valid = std::max(keep, w.m - kMatureFresh);
    for (int e = keep; e < valid; ++e)
      for (int r = std::max(0, e - 1); r <= e + 1; ++r)
        nw.matureK[3 * static_cast<size_t>(e) + static_cast<size_t>(r - e + 1)] = nw.lu.at(r, e) * l2;
    if (keep == 0) nw.matureAge = 0;
    nw.matureValid = valid;
  }

  // K = -dF/du over the free dofs into nw.lu (and, when sym, its symmetric part into nw.ldlt); the
  // forces of the current state must be in nw.r. With self-contact, the couplings of nodes far apart
  // along the rod go to nw.offBand and the whole matrix to nw.sparse (nw.sparseActive). keepMature:
  // the frozen twists' columns kept from earlier Jacobians may serve (kMatureRefresh). alone false: a
  // block of a plate's coupled system (relaxNewtonCoupled), which assembles and factorises nw.lu and
  // nw.offBand itself (nw.sparse and nw.ldlt are left as they are).
  void jacobian(bool sym, bool keepMature, bool alone = true) {
    const int N = w.dofs();
    nw.lu.reset(N, kBand, kBand);
    const double h = 1e-6 * lbar;  // [m], and h / lbar [rad]
    if (opt.closedFormStiffness && stiffnessInClosedForm(env)) {
      // in closed form (stiffness.hpp), from the strains residual() left in ws: the differenced band
      // below is the dearer (docs/numerics.md, "Jacobian")
      BandSink sink(w, nw.lu, lbar);
      addStiffness(p, env, s, ws.strains, w.b0 / 2, sink);
      nw.matureValid = 0;  // the differenced chain is not kept meanwhile
    } else {
      differenced(h, keepMature);
    }
    // self-contact: each pair's 12 x 12 stiffness (node translations only: scaled units are SI there),
    // inside the band where the nodes are close enough, off it otherwise
    nw.offBand.clear();
    if (env.selfContact.enabled) {
      selfContactStiffness(p, env, s, h, ws.contact);
      for (const PairStiffness& ps : ws.contact.stiffness) {
        const int nodes[4] = {ps.i, ps.i + 1, ps.j, ps.j + 1};
        for (int a = 0; a < 4; ++a)
          for (int bn = 0; bn < 4; ++bn) {
            const int rb = 2 * nodes[a], cb = 2 * nodes[bn];
            if (rb < w.b0 || cb < w.b0) continue;  // frozen (nodes before the window)
            for (int rc = 0; rc < 3; ++rc)
              for (int cc = 0; cc < 3; ++cc) {
                const double k = ps.K(3 * a + rc, 3 * bn + cc);
                const int row = w.dof(rb, rc), col = w.dof(cb, cc);
                if (nw.lu.inBand(row, col)) nw.lu.add(row, col, k);
                else nw.offBand.push_back({row, col, k});  // zeros too: a pattern that changes less
              }
          }
      }
    }
    // the contact with other roots on a plate: each pair's stiffness in this root's own nodes (always in
    // the band: the two nodes of one element)
    if (!ws.contact.neighbours.empty()) {
      neighbourContactStiffness(p, env, s, h, ws.contact);
      for (const NeighbourStiffness& ns : ws.contact.neighbourStiffness)
        for (int a = 0; a < 2; ++a)
          for (int bn = 0; bn < 2; ++bn) {
            const int rb = 2 * (ns.i + a), cb = 2 * (ns.i + bn);
            if (rb < w.b0 || cb < w.b0) continue;
            nw.lu.addBlock(w.dof(rb, 0), w.dof(cb, 0), 1.0, Mat3(ns.K.block<3, 3>(3 * a, 3 * bn)));
          }
    }
    if (alone) assembleAlone(sym);
  }

  // the last jacobian()'s band and off-band entries (nw.lu unfactorised, nw.offBand) as this root's own
  // matrix: the sparse one while offBand is not empty, and with sym the band of its symmetric part
  void assembleAlone(bool sym) {
    const int N = w.dofs();
    nw.sparseActive = !nw.offBand.empty();
    if (nw.sparseActive) {
      nw.sparse.assemble(nw.lu, nw.offBand);  // keeps its own copy: the symmetric part is taken from it
    } else if (sym) {
      nw.ldlt.reset(N, kBand);
      // the frozen twists couple to their neighbours only (a tridiagonal chain up to the window)
      for (int j = 0; j < N; ++j)
        for (int i = j; i <= std::min(N - 1, j < w.m - kForceReach ? j + 1 : j + kBand); ++i)
          nw.ldlt.addLower(i, j, 0.5 * (nw.lu.at(i, j) + nw.lu.at(j, i)));
    }
  }

  // the factorisations and solves of the last jacobian(): band, or sparse with self-contact
  bool factorize() { return nw.sparseActive ? nw.sparse.factorizeLU() : nw.lu.factorize(); }
  void solve(double* b) const {
    if (nw.sparseActive) nw.sparse.solveLU(b);
    else nw.lu.solve(b);
  }
  bool factorizeSymmetric() { return nw.sparseActive ? nw.sparse.factorizeSymmetric() : nw.ldlt.factorize(); }
  int negativePivots(double relTol) const {
    return nw.sparseActive ? nw.sparse.negativePivots(relTol) : nw.ldlt.negativePivots(relTol);
  }
  void solveSymmetric(double* b) const {
    if (nw.sparseActive) nw.sparse.solveSymmetric(b);
    else nw.ldlt.solve(b);
  }

  // the eigenvalue of the symmetric stiffness nearest zero, from the LDL^T factors of the last
  // factorizeSymmetric(), and its vector into nw.mode (unit length; it starts from what nw.mode holds):
  // Lanczos on the inverse, whose extreme Ritz value converges where inverse iteration crawls through
  // a coil's cluster of soft modes (docs/numerics.md, "Stability"). Full reorthogonalisation: the basis
  // is short.
  double nearestEigenvalue() {
    const int N = w.dofs();
    using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLanczos, 1>;
    using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxLanczos, kMaxLanczos>;
    auto q = [&](int j) { return Eigen::Map<Eigen::VectorXd>(nw.lanczos.data() + static_cast<size_t>(j) * N, N); };
    Eigen::Map<Eigen::VectorXd> mode(nw.mode.data(), N);
    q(0) = mode / mode.norm();
    SmallVector alpha(kMaxLanczos), beta(kMaxLanczos);
    Eigen::SelfAdjointEigenSolver<SmallMatrix> tri;
    double theta = 0.0;
    int k = 0, top = 0;
    for (int j = 0; j < kMaxLanczos; ++j) {
      auto wj = q(j + 1);
      wj = q(j);
      solveSymmetric(wj.data());
      alpha[j] = q(j).dot(wj);
      wj -= alpha[j] * q(j);
      if (j > 0) wj -= beta[j - 1] * q(j - 1);
      for (int i = 0; i <= j; ++i) wj -= q(i).dot(wj) * q(i);
      beta[j] = wj.norm();
      k = j + 1;
      const SmallVector d = alpha.head(k), e = beta.head(std::max(k - 1, 0));
      tri.computeFromTridiagonal(d, e, Eigen::ComputeEigenvectors);
      // the Ritz value of largest magnitude: 1 / (the eigenvalue of K nearest zero)
      const auto& ritz = tri.eigenvalues();
      top = std::abs(ritz[0]) >= std::abs(ritz[k - 1]) ? 0 : k - 1;
      theta = ritz[top];
      const double residual = beta[j] * std::abs(tri.eigenvectors()(k - 1, top));
      if (residual <= kLanczosTol * std::abs(theta) || beta[j] <= 1e-300) break;
      wj /= beta[j];
    }
    // the Ritz vector
    mode.setZero();
    for (int i = 0; i < k; ++i) mode += tri.eigenvectors()(i, top) * q(i);
    mode.normalize();
    return theta != 0.0 ? 1.0 / theta : 0.0;
  }

  void saveState() {
    for (int e = 0; e < w.m; ++e) nw.saveQ[static_cast<size_t>(e)] = s.Q[static_cast<size_t>(e)];
    for (int b = w.b0; b <= 2 * w.n; ++b) {
      if (Window::isNode(b)) nw.save[static_cast<size_t>(b)] = s.x.col(b / 2);
      else nw.saveQ[static_cast<size_t>(b / 2)] = s.Q[static_cast<size_t>(b / 2)];
    }
  }
  void restoreState() {
    for (int e = 0; e < w.m; ++e) s.Q[static_cast<size_t>(e)] = nw.saveQ[static_cast<size_t>(e)];
    for (int b = w.b0; b <= 2 * w.n; ++b) {
      if (Window::isNode(b)) s.x.col(b / 2) = nw.save[static_cast<size_t>(b)];
      else s.Q[static_cast<size_t>(b / 2)] = nw.saveQ[static_cast<size_t>(b / 2)];
    }
  }
  // state = saved + a * delta (delta in scaled units)
  void applyStep(double a) {
    for (int e = 0; e < w.m; ++e) twistInPlace(a * nw.delta[static_cast<size_t>(e)] / lbar, s.Q[static_cast<size_t>(e)]);
    for (int b = w.b0; b <= 2 * w.n; ++b) {
      const Vec3 u = a * Eigen::Map<const Vec3>(nw.delta.data() + w.dof(b, 0));
      moveBlock(s, b, u, lbar);
    }
  }
};

}  // namespace

void NewtonWorkspace::reserve(int elements) {
  const size_t nb = static_cast<size_t>(2 * elements + 1);
  if (r.size() < 3 * nb) {
    r.resize(3 * nb);
    r0.resize(3 * nb);
    delta.resize(3 * nb);
    mode.resize(3 * nb);
    lanczos.resize(static_cast<size_t>(kMaxLanczos + 1) * 3 * nb);
  }
  if (save.size() < nb) save.resize(nb);
  if (saveQ.size() < static_cast<size_t>(elements)) saveQ.resize(static_cast<size_t>(elements));
  if (matureK.size() < 3 * static_cast<size_t>(elements)) matureK.resize(3 * static_cast<size_t>(elements));
}

RelaxResult relaxNewton(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                        RelaxWorkspace& ws, NewtonWorkspace& nw, int firstFreeNode) {
  const int n = s.elements();
  if (n < 2) throw RelaxError("relaxation needs at least 2 elements");
  ROOTSIM_ASSERT(firstFreeNode >= 0 && firstFreeNode <= n, "a window inside the rod");
  nw.reserve(n);
  s.v.setZero();
  s.w.setZero();
  NewtonSolver ns{p, env, opt, s, ws, nw, windowOf(env, s, firstFreeNode)};
  ns.lbar = s.restLength() / n;
  // the sparse pattern and pivots carry over while the unknowns stay as many (a checkpoint holds them:
  // same bytes on resume): a coiling root's relaxations then refactorise instead of analysing anew
  nw.sparse.beginRelaxation(ns.w.dofs());
  // the explicit solver's tolerances (relax.hpp: equilibriumTolerance), over the window's nodes
  const EquilibriumTolerance tol = equilibriumTolerance(p, env, opt, s, firstFreeNode);
  ns.ftol = tol.force;
  ns.mtol = tol.couple;
  const int N = ns.w.dofs();
  // nw.lu holds this root's block of the plate's coupled Jacobian of this growth step, for these unknowns
  // (relaxNewtonCoupled: coupledBlockDofs); read once, by this relaxation only
  const bool coupledBlock = opt.stabilityCheck && nw.coupledBlockDofs == N && nw.coupledBlockFirst == ns.w.b0;
  nw.coupledBlockDofs = -1;
  RelaxResult res;
  nw.firstFreeNode = firstFreeNode;
  ++nw.matureAge;
  int argF = 0, argM = 0;
  // the previous relaxation's factors serve this one's first iteration when they are for the same
  // unknowns: banded, or sparse (KLU's factors stay while the pattern does; the contacts that changed
  // since only make the chord step a little less accurate, and a poor one is rejected below). Measured
  // on a coiling root (alpha = 45, beta = 1, full resolution): 23 % of the sparse factorisations were
  // a relaxation's first.
  bool reuse = nw.factorsValid && nw.factorsDofs == N && nw.factorsFirstBlock == ns.w.b0 &&
               (!nw.sparseActive || nw.sparse.hasFactors());
  bool fresh = false;  // a Jacobian of this relaxation has been computed
  int crawl = 0;       // iterations in a row damped to at most kCrawl
  bool chordNext = false;  // the next iteration reuses the factors of this one
  long chords = 0;         // iterations that did so
  ns.residual();
  for (;;) {
    if (ns.converged(res, argF, argM)) break;
    if (res.iterations - chords >= opt.newtonMaxIterations) {  // chord steps are not counted: they follow
                                                               // a fresh step each and cost no Jacobian
      // a snap: the equilibrium sought is far away (the straight branch lost); Newton wanders there, the
      // explicit relaxation gets there. The caller continues explicitly from here.
      std::ostringstream os;
      os << "Newton solver did not reach equilibrium in " << res.iterations << " iterations: residual force "
         << res.residualForce << " N at node " << argF << " (tolerance " << ns.ftol << "), residual couple "
         << res.residualTorque << " N m on element " << argM << " (tolerance " << ns.mtol << ")";
      res.message = os.str();
      res.stalled = true;
      nw.matureAge = kMatureRefresh;  // the explicit solver takes over: difference the chain anew after it
      return res;
    }
    ++res.iterations;
    // The first iteration of a growth step takes the factors of the previous step's last Jacobian when
    // the unknowns are the same (a chord step: growth changed the stiffness little), every later one a
    // fresh Jacobian. A typical step converges in two iterations, so this halves its Jacobians. Stability
    // is judged only from a Jacobian of this step: the symmetric part of the last fresh one (the last
    // iterate's, standing in for the converged state's, as Newton's last step is below the equilibrium
    // tolerance), or one of the converged state. (Reusing one factorisation over all iterations,
    // simplified Newton, misjudges stability after large steps: the Euler test, docs/numerics.md.)
    const bool chordStep = chordNext;
    const bool stale = (res.iterations == 1 && reuse) || chordStep;
    if (!stale) {
      ns.jacobian(opt.stabilityCheck, nw.matureAge < kMatureRefresh && res.iterations <= kMatureTrust);
      fresh = true;
      nw.factorsValid = false;
      if (!ns.factorize()) {
        // exactly singular (a fold passed on the way to a snap): the caller relaxes explicitly
        std::ostringstream os;
        os << "Newton solver: singular stiffness at iteration " << res.iterations << " (" << N << " unknowns)";
        res.message = os.str();
        res.stalled = true;
        nw.matureAge = kMatureRefresh;
        return res;
      }
      nw.factorsValid = true;
      nw.factorsDofs = N;
      nw.factorsFirstBlock = ns.w.b0;
    }
    if (chordStep) {
      ++chords;
      // the simplified Newton correction of the last trial is this chord step (same factors, same state)
      std::copy(nw.r0.begin(), nw.r0.begin() + N, nw.delta.begin());
    } else {
      std::copy(nw.r.begin(), nw.r.begin() + N, nw.delta.begin());
      ns.solve(nw.delta.data());
    }
    chordNext = false;
    // Damped Newton with Deuflhard's natural monotonicity test: a step a*delta is accepted when the
    // simplified Newton correction there, |K^-1 F(u + a delta)|, is smaller than |delta| by (1 - a/4).
    // This measures the residual in the solver's own metric; a plain |F|^2 test rejects good steps,
    // because a bending step of a stiff-in-stretch rod leaves second-order stretch forces that dwarf
    // the bending loads (a cantilever's exact full step raises |F| by orders of magnitude).
    double norm0 = 0;
    for (int i = 0; i < N; ++i) norm0 += nw.delta[static_cast<size_t>(i)] * nw.delta[static_cast<size_t>(i)];
    norm0 = std::sqrt(norm0);
    ns.saveState();
    double a = 1.0, norm1 = 0;
    int halvings = 0;
    for (;;) {
      ns.applyStep(a);
      ns.residual();
      std::copy(nw.r.begin(), nw.r.begin() + N, nw.r0.begin());
      ns.solve(nw.r0.data());
      norm1 = 0;
      for (int i = 0; i < N; ++i) norm1 += nw.r0[static_cast<size_t>(i)] * nw.r0[static_cast<size_t>(i)];
      norm1 = std::sqrt(norm1);
      if (std::getenv("ROOTSIM_NEWTON_TRACE"))
        std::fprintf(stderr, "it %ld a %g |delta| %g |simplified| %g\n", res.iterations, a, norm0, norm1);
      if (std::isfinite(norm1) && norm1 <= (1.0 - 0.25 * a) * norm0) break;
      ns.restoreState();
      if (stale && halvings >= 2) break;  // the chord direction is poor: take a fresh Jacobian instead
      if (++halvings > kMaxHalvings) {
        // no acceptable step along the Newton direction (K indefinite far from equilibrium): the
        // caller continues with the explicit relaxation from here
        ns.residual();
        res.stalled = true;
        res.message = "Newton solver: no acceptable step along the Newton direction at iteration " +
                      std::to_string(res.iterations);
        nw.matureAge = kMatureRefresh;
        return res;
      }
      a *= 0.5;
    }
    if (stale && halvings >= 2) {
      ns.residual();  // of the restored state
      --res.iterations;
      if (chordStep) --chords;  // the failed step is not counted at all
      reuse = false;
      continue;
    }
    // a full step that contracted well (Deuflhard's theta = |simplified correction| / |step| small) on
    // this relaxation's own factors: Newton is in its quadratic range and the same factors serve the
    // next step (simplified Newton). Measured on coiling roots: a relaxation took a first step at theta
    // ~0.5 (contacts switching on), a second at ~0.04, a third only to confirm; the third now reuses the
    // second's factorisation (one Jacobian and one sparse LU fewer per growth step).
    // With self-contact, a factorisation (sparse) costs many solves: there a stale step that contracted
    // by kSparseChordTheta or better is followed by another on the same factors.
    chordNext = (!stale && a == 1.0 && norm1 <= kChordTheta * norm0) ||
                (stale && nw.sparseActive && a == 1.0 && norm1 <= kSparseChordTheta * norm0 &&
                 chords < opt.newtonMaxIterations);
    crawl = a <= kCrawl ? crawl + 1 : 0;
    if (crawl >= kMaxCrawl && !ns.converged(res, argF, argM)) {
      std::ostringstream os;
      os << "Newton solver crawls: " << crawl << " iterations in a row damped to " << a
         << " or less of the Newton step (iteration " << res.iterations << ")";
      res.message = os.str();
      res.stalled = true;
      res.crawled = true;
      nw.matureAge = kMatureRefresh;
      return res;
    }
  }
  res.converged = true;
  // stability from the factorisation of the converged state's stiffness
  if (opt.stabilityCheck) {
    if (!fresh && coupledBlock) {
      // in equilibrium already after the plate's coupled solve: this root's block of its last Jacobian is
      // the last fresh Jacobian of this step (its factors were the coupled system's: none kept here)
      ns.assembleAlone(true);
    } else if (!fresh) {
      // in equilibrium already, or after a chord step only: no Jacobian of this step yet (its factors
      // serve the next step's chord step)
      ns.jacobian(true, nw.matureAge < kMatureRefresh && res.iterations <= kMatureTrust);
      nw.factorsValid = false;
      if (ns.factorize()) {
        nw.factorsValid = true;
        nw.factorsDofs = N;
        nw.factorsFirstBlock = ns.w.b0;
      }
    }
    const bool factorised = ns.factorizeSymmetric();
    nw.negative = factorised ? ns.negativePivots(1e-10) : 1;
    // eigenvalue nearest zero (the lowest while stable) and its mode, warm started from the last growth
    // step's mode when the unknowns are the same, otherwise from a deterministic vector
    double* v = nw.mode.data();
    const bool warm = nw.modeSize == N;
    if (!warm)
      for (int i = 0; i < N; ++i) v[i] = std::sin(1.0 + 12.9898 * i);
    nw.modeSize = N;
    const double lambda = factorised ? ns.nearestEigenvalue() : 0.0;
    nw.lowestEigenvalue = lambda;
  }
  return res;
}

namespace {

// the coupled system of a plate's roots in contact (relaxNewtonCoupled): one NewtonSolver per root for its
// window, residual and band; the unknowns side by side in the roots' order
struct Coupled {
  const std::vector<CoupledRoot>& roots;
  const std::function<void()>& refresh;
  CoupledWorkspace& cw;
  // one solver per root, built in cw.solvers (kept from system to system: no allocation once it is large
  // enough); ns.size() of them
  std::span<NewtonSolver> ns;
  int N = 0;

  Coupled(const std::vector<CoupledRoot>& rs, const std::function<void()>& rf, CoupledWorkspace& w)
      : roots(rs), refresh(rf), cw(w) {
    static_assert(std::is_trivially_destructible_v<NewtonSolver> && alignof(NewtonSolver) <= alignof(std::max_align_t));
    const size_t words = (roots.size() * sizeof(NewtonSolver) + sizeof(std::max_align_t) - 1) / sizeof(std::max_align_t);
    if (cw.solvers.size() < words) cw.solvers.resize(words);
    auto* room = reinterpret_cast<NewtonSolver*>(cw.solvers.data());
    size_t built = 0;
    cw.first.clear();
    int last = 0;
    for (const CoupledRoot& cr : roots) {
      const int n = cr.s->elements();
      if (n < 2) throw RelaxError("relaxation needs at least 2 elements");
      ROOTSIM_ASSERT(cr.firstFreeNode >= 0 && cr.firstFreeNode <= n, "a window inside the rod");
      cr.nw->reserve(n);
      cr.s->v.setZero();
      cr.s->w.setZero();
      NewtonSolver& s = *new (room + built++) NewtonSolver{*cr.rod, *cr.env, *cr.opt, *cr.s, *cr.ws, *cr.nw,
                                                           windowOf(*cr.env, *cr.s, cr.firstFreeNode)};
      ns = std::span<NewtonSolver>(room, built);
      s.lbar = cr.s->restLength() / n;
      const EquilibriumTolerance tol = equilibriumTolerance(*cr.rod, *cr.env, *cr.opt, *cr.s, cr.firstFreeNode);
      s.ftol = tol.force;
      s.mtol = tol.couple;
      cw.first.push_back(N);
      N += s.w.dofs();
      last = std::max(last, cr.plateIndex);
    }
    cw.clusterOf.assign(static_cast<size_t>(last + 1), -1);
    for (size_t k = 0; k < roots.size(); ++k) cw.clusterOf[static_cast<size_t>(roots[k].plateIndex)] = static_cast<int>(k);
    if (cw.r.size() < static_cast<size_t>(N)) {
      cw.r.resize(static_cast<size_t>(N));
      cw.r0.resize(static_cast<size_t>(N));
      cw.delta.resize(static_cast<size_t>(N));
    }
  }
  int size() const { return static_cast<int>(ns.size()); }

  // every root's forces with the others where they are now, into cw.r
  void residual() {
    refresh();
    for (int k = 0; k < size(); ++k) {
      NewtonSolver& s = ns[static_cast<size_t>(k)];
      s.residual();
      std::copy(s.nw.r.begin(), s.nw.r.begin() + s.w.dofs(), cw.r.begin() + cw.first[static_cast<size_t>(k)]);
    }
  }
  // every root within its own tolerance (the largest residuals of all into res)
  bool converged(RelaxResult& res) {
    bool all = true;
    double f = 0, m = 0;
    for (NewtonSolver& s : ns) {
      RelaxResult rk;
      rk.iterations = res.iterations;
      int argF = 0, argM = 0;
      all = s.converged(rk, argF, argM) && all;
      f = std::max(f, rk.residualForce);
      m = std::max(m, rk.residualTorque);
    }
    res.residualForce = f;
    res.residualTorque = m;
    return all;
  }
  // the roots' bands side by side, their off-band entries and the contacts between them into cw
  void jacobian(bool keepMature) {
    cw.band.reset(N, kBand, kBand);
    cw.offBand.clear();
    for (int k = 0; k < size(); ++k) {
      NewtonSolver& s = ns[static_cast<size_t>(k)];
      NewtonWorkspace& nw = s.nw;
      s.jacobian(false, keepMature && nw.matureAge < kMatureRefresh, false);
      nw.factorsValid = false;  // nw.lu holds this block unfactorised
      const int o = cw.first[static_cast<size_t>(k)];
      cw.band.addDiagonalBlock(o, nw.lu, kBand);
      reserveHighWater(cw.offBand, cw.offBand.size() + nw.offBand.size());
      for (const OffBandEntry& e : nw.offBand) cw.offBand.push_back({o + e.row, o + e.col, e.value});
    }
    // each root's rows of its contacts with the others, in the other root's columns (node translations:
    // SI in the scaled units too)
    for (int k = 0; k < size(); ++k) {
      const NewtonSolver& s = ns[static_cast<size_t>(k)];
      const NeighbourCapsules& nb = s.ws.contact.neighbours;
      // at most the 2 x 2 node blocks of 3 x 3 entries of each contact
      reserveHighWater(cw.offBand, cw.offBand.size() + 36 * s.ws.contact.neighbourStiffness.size());
      for (const NeighbourStiffness& st : s.ws.contact.neighbourStiffness) {
        const auto [o, j] = nb.source[static_cast<size_t>(st.c)];
        const int l = o < static_cast<int>(cw.clusterOf.size()) ? cw.clusterOf[static_cast<size_t>(o)] : -1;
        if (l < 0) continue;  // a root outside the system: its capsule stays where it is
        const NewtonSolver& t = ns[static_cast<size_t>(l)];
        for (int a = 0; a < 2; ++a)
          for (int bn = 0; bn < 2; ++bn)
            for (int rc = 0; rc < 3; ++rc)
              for (int cc = 0; cc < 3; ++cc) {
                const int row = s.w.unknown(2 * (st.i + a), rc), col = t.w.unknown(2 * (j + bn), cc);
                if (row < 0 || col < 0) continue;  // frozen
                cw.offBand.push_back({cw.first[static_cast<size_t>(k)] + row, cw.first[static_cast<size_t>(l)] + col,
                                      st.K(3 * a + rc, 6 + 3 * bn + cc)});
              }
      }
    }
  }
  // the root and its unknown of system unknown u
  int owner(int u) const {
    int k = size() - 1;
    while (k > 0 && cw.first[static_cast<size_t>(k)] > u) --k;
    return k;
  }
  void scatterDelta() {
    for (int k = 0; k < size(); ++k) {
      NewtonSolver& s = ns[static_cast<size_t>(k)];
      std::copy(cw.delta.begin() + cw.first[static_cast<size_t>(k)],
                cw.delta.begin() + cw.first[static_cast<size_t>(k)] + s.w.dofs(), s.nw.delta.begin());
    }
  }
  double norm(const std::vector<double>& v) const {
    double sum = 0;
    for (int i = 0; i < N; ++i) sum += v[static_cast<size_t>(i)] * v[static_cast<size_t>(i)];
    return std::sqrt(sum);
  }
};

}  // namespace

RelaxResult relaxNewtonCoupled(const std::vector<CoupledRoot>& roots, const std::function<void()>& refresh,
                               CoupledWorkspace& cw) {
  Coupled c(roots, refresh, cw);
  for (const CoupledRoot& r : roots) r.nw->coupledBlockDofs = -1;  // none of this relaxation yet
  const SolverOptions& opt = *roots.front().opt;
  cw.start.resize(roots.size());
  for (size_t k = 0; k < roots.size(); ++k) cw.start[k] = *roots[k].s;
  RelaxResult res;
  // no acceptable step: every root back where it started (the plate relaxes them together explicitly);
  // why, a printf format and its arguments, into cw.stallReason (a stall is an ordinary event of a step:
  // it must not allocate)
  auto stall = [&](const char* why, auto... args) {
    for (size_t k = 0; k < roots.size(); ++k) {
      *roots[k].s = cw.start[k];
      roots[k].nw->matureAge = kMatureRefresh;
      roots[k].nw->coupledBlockDofs = -1;  // of states the roots have left
    }
    refresh();
    res.stalled = true;
    const int n = std::snprintf(cw.stallReason.data(), cw.stallReason.size(), "coupled Newton solver of the roots in contact: ");
    std::snprintf(cw.stallReason.data() + n, cw.stallReason.size() - static_cast<size_t>(n), why, args...);
    return res;
  };
  cw.stallReason[0] = '\0';
  cw.sparse.beginRelaxation(c.N);
  int crawl = 0;
  bool chordNext = false;  // the next iteration reuses this one's factors (as relaxNewton's chord steps)
  long chords = 0;         // iterations that did so (not counted against the limit: they cost no Jacobian)
  c.residual();
  for (;;) {
    if (c.converged(res)) break;
    if (res.iterations - chords >= opt.newtonMaxIterations) {
      return stall("no joint equilibrium in %ld iterations (residual force %g N, couple %g N m)", res.iterations,
                   res.residualForce, res.residualTorque);
    }
    ++res.iterations;
    const bool chord = chordNext;
    chordNext = false;
    if (chord) {
      // the simplified Newton correction of the accepted trial is this step (same factors, same state)
      ++chords;
      std::copy(cw.r0.begin(), cw.r0.begin() + c.N, cw.delta.begin());
    } else {
      c.jacobian(res.iterations <= kMatureTrust);
      for (NewtonSolver& s : c.ns) {
        s.nw.coupledBlockDofs = s.w.dofs();
        s.nw.coupledBlockFirst = s.w.b0;
      }
      cw.sparse.assemble(cw.band, cw.offBand);
      if (!cw.sparse.factorizeLU()) return stall("singular stiffness at iteration %ld", res.iterations);
      std::copy(cw.r.begin(), cw.r.begin() + c.N, cw.delta.begin());
      cw.sparse.solveLU(cw.delta.data());
    }
    c.scatterDelta();
    const double norm0 = c.norm(cw.delta);
    for (NewtonSolver& s : c.ns) s.saveState();
    // damped as relaxNewton's steps (Deuflhard's natural monotonicity test), over all the roots' unknowns
    double a = 1.0, norm1 = 0;
    int halvings = 0;
    for (;;) {
      for (NewtonSolver& s : c.ns) s.applyStep(a);
      c.residual();
      std::copy(cw.r.begin(), cw.r.begin() + c.N, cw.r0.begin());
      cw.sparse.solveLU(cw.r0.data());
      norm1 = c.norm(cw.r0);
      if (std::isfinite(norm1) && norm1 <= (1.0 - 0.25 * a) * norm0) break;
      for (NewtonSolver& s : c.ns) s.restoreState();
      if (chord && halvings >= 2) break;  // the chord direction is poor: a fresh Jacobian instead
      if (++halvings > kMaxHalvings)
        return stall("no acceptable step along the Newton direction at iteration %ld", res.iterations);
      a *= 0.5;
    }
    if (chord && halvings >= 2) {
      c.residual();  // of the restored state
      --res.iterations;
      --chords;
      continue;
    }
    // a full step that contracted well: Newton is in its quadratic range and these factors serve the next
    // step (relaxNewton's rule, kChordTheta)
    chordNext = !chord && a == 1.0 && norm1 <= kChordTheta * norm0;
    crawl = a <= kCrawl ? crawl + 1 : 0;
    if (crawl >= kMaxCrawl && !c.converged(res))
      return stall("crawls (%d iterations in a row damped to %f)", crawl, a);
  }
  res.converged = true;
  return res;
}

Eigen::MatrixXd coupledStiffness(const std::vector<CoupledRoot>& roots, const std::function<void()>& refresh,
                                 CoupledWorkspace& cw) {
  Coupled c(roots, refresh, cw);
  c.residual();
  c.jacobian(false);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(c.N, c.N);
  for (int j = 0; j < c.N; ++j)
    for (int i = std::max(0, j - kBand); i <= std::min(c.N - 1, j + kBand); ++i) K(i, j) = cw.band.at(i, j);
  for (const OffBandEntry& e : cw.offBand) K(e.row, e.col) += e.value;
  return K;
}

Eigen::VectorXd coupledResidual(const std::vector<CoupledRoot>& roots, const std::function<void()>& refresh,
                                CoupledWorkspace& cw, int k, double h) {
  Coupled c(roots, refresh, cw);
  NewtonSolver* moved = nullptr;
  if (k >= 0) {
    ROOTSIM_ASSERT(k < c.N, "an unknown of the system");
    const int m = c.owner(k);
    moved = &c.ns[static_cast<size_t>(m)];
    std::fill(moved->nw.delta.begin(), moved->nw.delta.begin() + moved->w.dofs(), 0.0);
    moved->nw.delta[static_cast<size_t>(k - cw.first[static_cast<size_t>(m)])] = h;
    moved->saveState();
    moved->applyStep(1.0);
  }
  c.residual();
  Eigen::VectorXd r = Eigen::Map<const Eigen::VectorXd>(cw.r.data(), c.N);
  if (moved) {
    moved->restoreState();
    refresh();
  }
  return r;
}

void assembleStiffness(const RodParams& p, const Environment& env, const SolverOptions& opt, RodState& s,
                       RelaxWorkspace& ws, NewtonWorkspace& nw, int firstFreeNode) {
  nw.reserve(s.elements());
  NewtonSolver ns{p, env, opt, s, ws, nw, windowOf(env, s, firstFreeNode)};
  ns.lbar = s.restLength() / s.elements();
  ns.residual();
  ns.jacobian(false, false);
}

Eigen::VectorXd NewtonWorkspace::unstableMode(const RodState& s, const Environment& env) const {
  // the Lanczos Ritz vector, embedded in the full dof vector (per node 3 translations [m], per
  // element 3 rotations [rad]) and scaled so that its largest translation is 1, as checkStability's
  const int n = s.elements();
  const Window w = windowOf(env, s, firstFreeNode);
  const double lbar = s.restLength() / n;
  Eigen::VectorXd m = Eigen::VectorXd::Zero(6 * n + 3);
  double big = 0;
  for (int e = 0; e < w.m; ++e) m[3 * (2 * e + 1) + 2] = mode[static_cast<size_t>(e)] / lbar;
  for (int b = w.b0; b <= 2 * n; ++b) {
    Vec3 u = Eigen::Map<const Vec3>(mode.data() + w.dof(b, 0));
    if (!Window::isNode(b)) u /= lbar;
    else big = std::max(big, u.norm());
    m.segment<3>(3 * b) = u;
  }
  if (big > 0) m /= big;
  return m;
}

}  // namespace rootsim
