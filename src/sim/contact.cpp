// The contact force pieces (docs/model.md, Contact and friction): self-contact, obstacles, Coulomb friction
// and its commit. contact.hpp states the conventions; each piece is called from addExternalForces
// (environment.cpp). The Newton solver's contact helpers: contact_newton.cpp; the observables:
// contact_observe.cpp; the shared geometry: contact_geometry.cpp.
#include "rootsim/contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include <limits>

#include "contact_geometry.hpp"

namespace rootsim {

using namespace contact_detail;

void ContactWorkspace::resize(int n) {
  obstacleN.resize(n + 1);
  obstacleNormal.resize(3, n + 1);
  mid.resize(3, n);
  halfLength.resize(n);
  order.assign(static_cast<size_t>(n), 0);
  key.resize(n);
  // room for 16 candidates per element: a tight coil lists a handful (the turns on either side); more
  // would need several turns stacked on one element, and the list then grows once (an allocation)
  pairs.reserve(16 * static_cast<size_t>(n) + 64);
  xBuilt.resize(3, n + 1);
  contactNode.assign(static_cast<size_t>(n + 1), 0);
  elementFlag.assign(static_cast<size_t>(n), 0);
  invalidate();
}

void addObstacleContact(const RodParams& p, const Environment& env, const RodState& s, bool damping,
                        ContactWorkspace& cw, Eigen::Matrix3Xd& force) {
  if (cw.obstacleN.size() != s.nodes()) cw.resize(s.elements());
  cw.obstacleN.setZero();
  cw.obstacleNormal.setZero();
  const double k = env.plane.k, c = env.plane.c;
  forEachObstacleContact(p, env, s, 0.0, [&](int i, double sa, const Vec3& m, double gap) {
    const double fe = -k * gap;  // elastic part: the normal force friction scales with
    double fn = fe;
    if (damping) fn -= c * ((1.0 - sa) * s.v.col(i) + sa * s.v.col(i + 1)).dot(m);
    force.col(i) += (1.0 - sa) * fn * m;
    force.col(i + 1) += sa * fn * m;
    cw.obstacleN[i] += (1.0 - sa) * fe;
    cw.obstacleN[i + 1] += sa * fe;
    cw.obstacleNormal.col(i) += (1.0 - sa) * fe * m;
    cw.obstacleNormal.col(i + 1) += sa * fe * m;
  });
}

void addSelfContact(const RodParams& p, const Environment& env, const RodState& s, bool damping,
                    ContactWorkspace& cw, Eigen::Matrix3Xd& force) {
  if (static_cast<int>(cw.order.size()) != s.elements()) cw.resize(s.elements());
  updatePairs(p, s, cw);
  const double k = env.selfContact.k, c = env.plane.c;
  const Vec3 up = env.plane.normal();
  PairContact g;
  for (const auto& [i, j] : cw.pairs) {
    if (!pairContact(p.radius, k, up, s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), g)) continue;
    double fn = g.fn;
    if (damping) {
      const Vec3 vi = (1.0 - g.sa) * s.v.col(i) + g.sa * s.v.col(i + 1);
      const Vec3 vj = (1.0 - g.sb) * s.v.col(j) + g.sb * s.v.col(j + 1);
      fn -= c * (vi - vj).dot(g.nrm);
    }
    const Vec3 F = fn * g.nrm;
    force.col(i) += (1.0 - g.sa) * F;
    force.col(i + 1) += g.sa * F;
    force.col(j) -= (1.0 - g.sb) * F;
    force.col(j + 1) -= g.sb * F;
  }
}

bool rootPairForce(double ra, double rb, double k, const Vec3& up, const Vec3& a0, const Vec3& a1, const Vec3& b0,
                   const Vec3& b1, RootPairForce& out) {
  // the self-contact law with the contact distance ra + rb (pairContact's 2R)
  PairContact g;
  if (!pairContact(0.5 * (ra + rb), k, up, a0, a1, b0, b1, g)) return false;
  out.F = g.fn * g.nrm;
  out.sa = g.sa;
  out.sb = g.sb;
  return true;
}

bool neighbourPairForce(const RodParams& p, const Environment& env, const Vec3& up, const NeighbourCapsules& nb, int c,
                        const Vec3& x0, const Vec3& x1, const Vec3& b0, const Vec3& b1, Vec3& F, double& w1) {
  const double k = env.selfContact.k;
  RootPairForce pf;
  if (nb.first[static_cast<size_t>(c)]) {
    if (!rootPairForce(p.radius, nb.radius[c], k, up, x0, x1, b0, b1, pf)) return false;
    F = pf.F;
    w1 = pf.sa;
  } else {
    if (!rootPairForce(nb.radius[c], p.radius, k, up, b0, b1, x0, x1, pf)) return false;
    F = -pf.F;
    w1 = pf.sb;
  }
  return true;
}

void addNeighbourContact(const RodParams& p, const Environment& env, const RodState& s, bool damping,
                         ContactWorkspace& cw, Eigen::Matrix3Xd& force) {
  const NeighbourCapsules& nb = cw.neighbours;
  const double c = env.plane.c;
  const Vec3 up = env.plane.normal();
  for (const auto& [i, j] : nb.pairs) {
    Vec3 F;
    double w1 = 0;
    if (!neighbourPairForce(p, env, up, nb, j, s.x.col(i), s.x.col(i + 1), nb.a.col(j), nb.b.col(j), F, w1)) continue;
    const double w0 = 1.0 - w1;
    if (damping) {
      const Vec3 nrm = F.normalized();
      F -= c * (w0 * s.v.col(i) + w1 * s.v.col(i + 1)).dot(nrm) * nrm;
    }
    force.col(i) += w0 * F;
    force.col(i + 1) += w1 * F;
  }
}

void addFriction(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw,
                 Eigen::Matrix3Xd& force) {
  if (env.plane.enabled) addPlateFriction(p, env, s, force);
  if (!env.obstacles.empty()) addObstacleFriction(env, s, cw, force);
}

FrictionCommit commitFriction(const RodParams& p, const Environment& env, RodState& s, ContactWorkspace& cw) {
  FrictionCommit r;
  const int nn = s.nodes();
  if (!env.friction.enabled) return r;
  const double kt = env.plane.k, touch = kTouchRadii * p.radius;
  // one stick point on a surface: made where the node touches, moved by the return mapping when the
  // trial force leaves the static cone (work = the kinetic force times the slip), dropped off contact
  auto commit = [&](int i, bool touching, double N, const Vec3& nrm, Eigen::Matrix3Xd& stick,
                    std::vector<std::uint8_t>& has) {
    const auto u = static_cast<size_t>(i);
    if (!touching || s.anchored[u]) { has[u] = 0; return; }
    if (!has[u]) { stick.col(i) = s.x.col(i); has[u] = 1; return; }
    Vec3 disp = s.x.col(i) - stick.col(i);
    disp -= disp.dot(nrm) * nrm;
    bool slips = false;
    const Vec3 f = coulomb(disp, nodeAxis(s, i, nrm), kt, N, env.friction, slips);
    if (!slips) return;
    // the new stick point makes the spring force equal the returned force: -kt (x - stick) = f
    const Vec3 moved = s.x.col(i) + f / kt;
    Vec3 slip = moved - stick.col(i);
    slip -= slip.dot(nrm) * nrm;
    r.work += std::abs(f.dot(slip));
    ++r.slips;
    stick.col(i) = moved;
  };
  if (env.plane.enabled) {
    const Vec3 nh = env.plane.normal();
    for (int i = 0; i < nn; ++i) {
      double minGap = 0;
      const double N = plateNodeNormal(p, env.plane, s, i, minGap);
      commit(i, minGap < touch, N, nh, s.plateStick, s.hasPlateStick);
    }
  } else {
    std::fill(s.hasPlateStick.begin(), s.hasPlateStick.end(), 0);
  }
  if (!env.obstacles.empty()) {
    Eigen::Matrix3Xd scratch = Eigen::Matrix3Xd::Zero(3, nn);
    addObstacleContact(p, env, s, false, cw, scratch);
    std::vector<double> minGap(static_cast<size_t>(nn), kInf);
    forEachObstacleContact(p, env, s, touch, [&](int i, double, const Vec3&, double gap) {
      for (int a : {i, i + 1}) minGap[static_cast<size_t>(a)] = std::min(minGap[static_cast<size_t>(a)], gap);
    });
    for (int i = 0; i < nn; ++i) {
      const double N = cw.obstacleN[i];
      // the contact normal: the elastic normals' sum, or (touching without force yet) the plate's
      // normal crossed with nothing useful; a stick point without force has no tangent plane to slip in
      const Vec3 m = N > 0.0 ? Vec3(cw.obstacleNormal.col(i).normalized()) : Vec3::Zero();
      commit(i, minGap[static_cast<size_t>(i)] < touch, N, m, s.obstacleStick, s.hasObstacleStick);
    }
  } else {
    std::fill(s.hasObstacleStick.begin(), s.hasObstacleStick.end(), 0);
  }
  return r;
}

namespace contact_detail {

void addPlateFriction(const RodParams& p, const Environment& env, const RodState& s, Eigen::Matrix3Xd& force) {
  const Vec3 nh = env.plane.normal();
  const double kt = env.plane.k;
  for (int i = 0; i < s.nodes(); ++i) {
    const auto u = static_cast<size_t>(i);
    if (!s.hasPlateStick[u] || s.anchored[u]) continue;
    double minGap = 0;
    const double N = plateNodeNormal(p, env.plane, s, i, minGap);
    if (N <= 0.0) continue;  // lifted off: no friction (the stick point is dropped at the next commit)
    Vec3 disp = s.x.col(i) - s.plateStick.col(i);
    disp -= disp.dot(nh) * nh;
    bool slips = false;
    force.col(i) += coulomb(disp, nodeAxis(s, i, nh), kt, N, env.friction, slips);
  }
}

void addObstacleFriction(const Environment& env, const RodState& s, const ContactWorkspace& cw,
                         Eigen::Matrix3Xd& force) {
  const double kt = env.plane.k;
  for (int i = 0; i < s.nodes(); ++i) {
    const auto u = static_cast<size_t>(i);
    if (!s.hasObstacleStick[u] || s.anchored[u] || cw.obstacleN[i] <= 0.0) continue;
    const Vec3 m = cw.obstacleNormal.col(i).normalized();
    Vec3 disp = s.x.col(i) - s.obstacleStick.col(i);
    disp -= disp.dot(m) * m;
    bool slips = false;
    force.col(i) += coulomb(disp, nodeAxis(s, i, m), kt, cw.obstacleN[i], env.friction, slips);
  }
}

}  // namespace contact_detail

}  // namespace rootsim
