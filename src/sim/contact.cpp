// Contact beyond the paper (docs/model.md, Contact and friction): self-contact, obstacles, Coulomb friction.
// contact.hpp states the conventions; each piece below is called from addExternalForces (environment.cpp).
#include "rootsim/contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "rootsim/assert.hpp"

namespace rootsim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Verlet skin of the self-contact list, in radii: pairs within 2R + skin are listed, and the list stays
// valid while no node has moved more than skin/2 (the centreline distance of two segments changes by at
// most the largest displacement of their four nodes, twice skin/2 for two segments)
constexpr double kSkinRadii = 1.0;

// a node "touches" for friction (gets a stick point) within this fraction of R of a surface; the rod
// starts exactly at the plate (gap 0 up to round-off)
constexpr double kTouchRadii = 1e-3;

double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

// unit in-plane axis of the rod at node i, perpendicular to the contact normal nh (zero when the rod is
// along the normal there)
Vec3 nodeAxis(const RodState& s, int i, const Vec3& nh) {
  const int n = s.elements();
  Vec3 t = s.x.col(std::min(i + 1, n)) - s.x.col(std::max(i - 1, 0));
  t -= t.dot(nh) * nh;
  const double l = t.norm();
  return l > 0.0 ? Vec3(t / l) : Vec3::Zero();
}

// Coulomb's law with an elliptic, anisotropic cone: the trial force of the stick spring -kt u (u the
// tangential displacement from the stick point) is kept while it lies inside the static ellipse
// (fa / (ratio mu_s N))^2 + (fb / (mu_s N))^2 <= 1 (fa along the rod's axis a, fb across it); otherwise
// the node slips and the force is returned radially onto the ellipse of the sliding coefficient (same
// direction). The radial return is the closest-point return for an isotropic cone; for an anisotropic
// one it keeps the force opposite to the slip instead of normal to the ellipse (a non-associated rule).
//
// The sliding coefficient weakens from mu_s to mu_k over the slip distance ell beyond the static limit,
// mu = mu_k + (mu_s - mu_k) exp(-slip / ell) (a slip-weakening law, Ida 1972; Palmer & Rice 1973).
// Deviation from a plain Coulomb law, which drops to mu_k at once (docs/model.md, Deviations): within one
// relaxation the force is a function of the displacement from the committed stick point, and with an abrupt
// drop a node that overshoots the static limit by a round-off during the pseudo-dynamics lands on the kinetic
// branch and, where mu_k N is less than the load, slides away although a sticking equilibrium exists
// (measured: a free rod on a plate tilted by 60 deg with mu_s = 1.06 cot(alpha) slid). ell = 0 gives the
// abrupt drop.
Vec3 coulomb(const Vec3& u, const Vec3& a, double kt, double N, const Friction& fr, bool& slips) {
  const Vec3 ft = -kt * u;
  const double fa = ft.dot(a);
  const double fb2 = std::max(0.0, ft.squaredNorm() - fa * fa);
  auto measure = [&](double mu) {
    const double ca = fr.axialRatio * mu * N, cb = mu * N;
    double q = 0.0;
    if (fa != 0.0) q += ca > 0.0 ? (fa / ca) * (fa / ca) : kInf;
    if (fb2 > 0.0) q += cb > 0.0 ? fb2 / (cb * cb) : kInf;
    return q;
  };
  const double qs = measure(fr.muStatic);
  if (qs <= 1.0) {
    slips = false;
    return ft;
  }
  slips = true;
  double mu = fr.muKinetic;
  if (fr.slipWeakening > 0.0 && std::isfinite(qs)) {
    const double slip = u.norm() * (1.0 - 1.0 / std::sqrt(qs));  // beyond the static limit [m]
    mu += (fr.muStatic - fr.muKinetic) * std::exp(-slip / fr.slipWeakening);
  }
  const double q = measure(mu);
  return std::isinf(q) ? Vec3::Zero() : Vec3(ft / std::sqrt(q));
}

// elastic normal force of the plate on node i: half the penalty of each neighbouring element [N]
double plateNodeNormal(const RodParams& p, const Plane& plane, const RodState& s, int i, double& minGap) {
  const Vec3 nh = plane.normal();
  double N = 0.0;
  minGap = kInf;
  for (int e = std::max(i - 1, 0); e <= std::min(i, s.elements() - 1); ++e) {
    const double gap = 0.5 * (s.x.col(e) + s.x.col(e + 1)).dot(nh) - p.radius;
    minGap = std::min(minGap, gap);
    if (gap < 0.0) N += 0.5 * plane.k * -gap;
  }
  return N;
}

// an obstacle as a lab segment in the plate (height 0)
void obstacleSegment(const PlateFrame& f, const Obstacle& o, Vec3& b0, Vec3& b1) {
  b0 = o.from.x() * f.lateral + o.from.y() * f.downhill;
  b1 = o.to.x() * f.lateral + o.to.y() * f.downhill;
}

// calls visit(element, node weight sa, unit normal, gap) for every element/obstacle pair with gap < limit
template <class Visit>
void forEachObstacleContact(const RodParams& p, const Environment& env, const RodState& s, double limit,
                            Visit&& visit) {
  const PlateFrame f = env.plane.frame();
  const Vec3 nh = f.normal;
  for (const Obstacle& o : env.obstacles) {
    Vec3 b0, b1;
    obstacleSegment(f, o, b0, b1);
    for (int i = 0; i < s.elements(); ++i) {
      // the element's centreline projected onto the plate: the obstacles are infinitely tall
      const Vec3 a0 = s.x.col(i) - s.x.col(i).dot(nh) * nh;
      const Vec3 a1 = s.x.col(i + 1) - s.x.col(i + 1).dot(nh) * nh;
      double sa = 0, sb = 0;
      contactSegmentPoints(a0, a1, b0, b1, sa, sb);
      const Vec3 d = (a0 + sa * (a1 - a0)) - (b0 + sb * (b1 - b0));
      const double dist = d.norm();
      const double gap = dist - p.radius - o.radius;
      if (gap >= limit) continue;
      // centreline on the obstacle's axis: push sideways, across the element
      Vec3 m = dist > 0.0 ? Vec3(d / dist) : Vec3(nh.cross(a1 - a0).normalized());
      visit(i, sa, m, gap);
    }
  }
}

// ---- self-contact broad phase ----

bool excludedAlongRod(const RodParams& p, const RodState& s, int i, int j) {
  // neighbours along the rod always overlap; elements whose nearest ends are closer than
  // kSelfExclusionRadii * R in rest arc length are treated as neighbours too
  return j <= i + 1 || s.S[j] - s.S[i + 1] < kSelfExclusionRadii * p.radius;
}

// (re)builds the Verlet list when it is stale; allocation-free while the pair count stays below the
// capacity reserved by resize
// a list built at xBuilt serves while no node has moved more than skin/2 since (then every pair now
// closer than 2R is in it) and the rod has not grown (the exclusion along the rod uses rest arc length)
bool listServes(const RodState& s, double skin, const Eigen::Matrix3Xd& xBuilt, int builtElements,
                double builtRestLength) {
  const int n = s.elements();
  if (builtElements != n || builtRestLength != s.S[n]) return false;
  const double lim2 = 0.25 * skin * skin;
  for (int i = 0; i <= n; ++i)
    if ((s.x.col(i) - xBuilt.col(i)).squaredNorm() > lim2) return false;
  return true;
}

void updatePairs(const RodParams& p, const RodState& s, ContactWorkspace& cw) {
  const int n = s.elements();
  const double skin = kSkinRadii * p.radius;
  if (listServes(s, skin, cw.xBuilt, cw.builtElements, cw.builtRestLength)) return;
  ROOTSIM_ASSERT(static_cast<int>(cw.order.size()) == n, "a contact workspace sized for the rod");
  ++cw.builds;
  const double reach = 2.0 * p.radius + skin;
  double lmax = 0.0;
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  for (int i = 0; i < n; ++i) {
    cw.mid.col(i) = 0.5 * (s.x.col(i) + s.x.col(i + 1));
    cw.halfLength[i] = 0.5 * (s.x.col(i + 1) - s.x.col(i)).norm();
    lmax = std::max(lmax, 2.0 * cw.halfLength[i]);
    lo = lo.cwiseMin(cw.mid.col(i));
    hi = hi.cwiseMax(cw.mid.col(i));
  }
  // sort and sweep along the axis of the midpoints' widest spread: two elements within `reach` have
  // midpoints within lmax + reach along it. (It replaced a spatial hash of 27 cells per element, whose
  // fixed cost per element was most of a rebuild on a long waving root: 8 % of a fig2b run.)
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const double slab = lmax + reach;
  for (int i = 0; i < n; ++i) {
    cw.key[i] = std::isfinite(cw.mid(axis, i)) ? cw.mid(axis, i) : 0.0;
    cw.order[static_cast<size_t>(i)] = i;
  }
  std::sort(cw.order.begin(), cw.order.end(), [&](int a, int b) {
    return cw.key[a] < cw.key[b] || (cw.key[a] == cw.key[b] && a < b);
  });
  cw.pairs.clear();
  for (int u = 0; u < n; ++u) {
    const int a = cw.order[static_cast<size_t>(u)];
    for (int v = u + 1; v < n; ++v) {
      const int b = cw.order[static_cast<size_t>(v)];
      if (cw.key[b] - cw.key[a] >= slab) break;
      const int i = std::min(a, b), j = std::max(a, b);
      if (excludedAlongRod(p, s, i, j)) continue;
      // no point of two segments is closer than their midpoints' distance less the half-lengths: a
      // cheap test that spares the exact one most pairs
      const double far = cw.halfLength[i] + cw.halfLength[j] + reach;
      if ((cw.mid.col(i) - cw.mid.col(j)).squaredNorm() >= far * far) continue;
      double sa = 0, sb = 0;
      closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), sa, sb);
      const Vec3 d = (s.x.col(i) + sa * (s.x.col(i + 1) - s.x.col(i))) - (s.x.col(j) + sb * (s.x.col(j + 1) - s.x.col(j)));
      if (d.squaredNorm() < reach * reach) cw.pairs.push_back({i, j});
    }
  }
  // canonical order: the forces sum the pairs in contact in the same order whichever list serves, so
  // they do not depend on when the list was built (nor does a resumed run)
  std::sort(cw.pairs.begin(), cw.pairs.end());
  cw.xBuilt = s.x;
  cw.builtElements = n;
  cw.builtRestLength = s.S[n];
}

// closest points of a listed pair: the two points, their parameters and the distance
struct PairGeometry {
  double sa = 0, sb = 0, dist = 0;
  Vec3 d = Vec3::Zero();  // point on i minus point on j
};
PairGeometry pairGeometry(const RodState& s, int i, int j) {
  PairGeometry g;
  closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), g.sa, g.sb);
  g.d = (s.x.col(i) + g.sa * (s.x.col(i + 1) - s.x.col(i))) - (s.x.col(j) + g.sb * (s.x.col(j + 1) - s.x.col(j)));
  g.dist = g.d.norm();
  return g;
}

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

}  // namespace

void closestSegmentPoints(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double& sa,
                          double& sb) {
  const Vec3 d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (a <= 0.0 && e <= 0.0) { sa = sb = 0.0; return; }
  if (a <= 0.0) { sa = 0.0; sb = clamp01(f / e); return; }
  const double c = d1.dot(r);
  if (e <= 0.0) { sb = 0.0; sa = clamp01(-c / a); return; }
  const double b = d1.dot(d2), denom = a * e - b * b;
  if (denom > 1e-12 * a * e) {
    sa = clamp01((b * f - c * e) / denom);
  } else {
    // parallel: any point of the overlap is closest; take the middle of a's part that faces b
    const double lo = clamp01(-c / a), hi = clamp01((b - c) / a);
    sa = 0.5 * (lo + hi);
  }
  sb = (b * sa + f) / e;
  if (sb < 0.0) { sb = 0.0; sa = clamp01(-c / a); }
  else if (sb > 1.0) { sb = 1.0; sa = clamp01((b - c) / a); }
}

void contactSegmentPoints(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double& sa,
                          double& sb) {
  closestSegmentPoints(a0, a1, b0, b1, sa, sb);
  const Vec3 d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm();
  if (a <= 0.0 || e <= 0.0) return;
  const double b = d1.dot(d2), c = d1.dot(r);
  const double sin2 = std::max(0.0, (a * e - b * b) / (a * e));
  if (sin2 >= kParallelSin2) return;
  // nearly parallel: the closest points jump from one end of the overlap to the other as the segments
  // pass through parallel (the distance does not): blend towards the middle of a's part facing b, so
  // that the point, and the force applied there, are continuous functions of the nodes
  const double t = sin2 / kParallelSin2, w = t * t * (3.0 - 2.0 * t);
  const double lo = clamp01(-c / a), hi = clamp01((b - c) / a);
  sa = w * sa + (1.0 - w) * 0.5 * (lo + hi);
  sb = clamp01((a0 + sa * d1 - b0).dot(d2) / e);
}

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

namespace {
// the elastic contact of one element pair (nodes a0-a1 against b0-b1): closest-point weights, the
// normal (from b towards a) and fn = k (2R - distance); false when the capsules do not overlap
struct PairContact {
  double sa = 0, sb = 0, fn = 0;
  Vec3 nrm = Vec3::Zero();
};
bool pairContact(double R, double k, const Vec3& up, const Vec3& a0, const Vec3& a1, const Vec3& b0,
                 const Vec3& b1, PairContact& pc) {
  contactSegmentPoints(a0, a1, b0, b1, pc.sa, pc.sb);
  const Vec3 d = (a0 + pc.sa * (a1 - a0)) - (b0 + pc.sb * (b1 - b0));
  const double dist = d.norm(), contact = 2.0 * R;
  if (dist >= contact) return false;
  // centrelines crossing exactly: separate along the normal of both tangents, away from the plate
  if (dist > 1e-9 * R) {
    pc.nrm = d / dist;
  } else {
    pc.nrm = (a1 - a0).cross(b1 - b0);
    if (pc.nrm.squaredNorm() == 0.0) pc.nrm = up;
    pc.nrm.normalize();
    if (pc.nrm.dot(up) < 0.0) pc.nrm = -pc.nrm;
  }
  pc.fn = k * (contact - dist);
  return true;
}
}  // namespace

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

void selfContactStiffness(const RodParams& p, const Environment& env, const RodState& s, double h,
                          ContactWorkspace& cw) {
  cw.stiffness.clear();
  if (!env.selfContact.enabled) return;
  if (static_cast<int>(cw.order.size()) != s.elements()) cw.resize(s.elements());
  updatePairs(p, s, cw);
  const double k = env.selfContact.k;
  const Vec3 up = env.plane.normal();
  PairContact g;
  for (const auto& [i, j] : cw.pairs) {
    const std::array<int, 4> nodes{i, i + 1, j, j + 1};
    std::array<Vec3, 4> x;
    for (int a = 0; a < 4; ++a) x[static_cast<size_t>(a)] = s.x.col(nodes[static_cast<size_t>(a)]);
    if (!pairContact(p.radius, k, up, x[0], x[1], x[2], x[3], g)) continue;
    // forces on the four nodes of the pair at positions x (zero when apart)
    auto forces = [&](Eigen::Matrix<double, 12, 1>& f) {
      f.setZero();
      if (!pairContact(p.radius, k, up, x[0], x[1], x[2], x[3], g)) return;
      const Vec3 F = g.fn * g.nrm;
      f.segment<3>(0) = (1.0 - g.sa) * F;
      f.segment<3>(3) = g.sa * F;
      f.segment<3>(6) = -(1.0 - g.sb) * F;
      f.segment<3>(9) = -g.sb * F;
    };
    PairStiffness& ps = cw.stiffness.emplace_back();
    ps.i = i;
    ps.j = j;
    Eigen::Matrix<double, 12, 1> fp, fm;
    for (int col = 0; col < 12; ++col) {
      double& xc = x[static_cast<size_t>(col / 3)][col % 3];
      const double x0 = xc;
      xc = x0 + h;
      forces(fp);
      xc = x0 - h;
      forces(fm);
      xc = x0;
      ps.K.col(col) = -(fp - fm) / (2.0 * h);
    }
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

ContactCounts countContacts(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw) {
  ContactCounts c;
  c.minSelfDistance = std::numeric_limits<double>::quiet_NaN();
  if (static_cast<int>(cw.order.size()) != s.elements()) cw.resize(s.elements());
  if (env.selfContact.enabled) {
    cw.invalidate();  // the pairs within 2R + skin of this very state
    updatePairs(p, s, cw);
    for (const auto& [i, j] : cw.pairs) {
      const PairGeometry g = pairGeometry(s, i, j);
      c.selfContacts += g.dist < 2.0 * p.radius;
      const double d = g.dist / p.radius;
      if (std::isnan(c.minSelfDistance) || d < c.minSelfDistance) c.minSelfDistance = d;
    }
  }
  if (!env.obstacles.empty()) {
    std::fill(cw.elementFlag.begin(), cw.elementFlag.end(), 0);
    forEachObstacleContact(p, env, s, 0.0, [&](int i, double, const Vec3&, double) { cw.elementFlag[static_cast<size_t>(i)] = 1; });
    for (auto t : cw.elementFlag) c.obstacleContacts += t;
  }
  return c;
}

ContactObservables observeContacts(const RodParams& p, const Environment& env, const RodState& s) {
  ContactObservables o;
  const int nn = s.nodes();
  ContactWorkspace cw;
  cw.resize(s.elements());
  static_cast<ContactCounts&>(o) = countContacts(p, env, s, cw);
  o.perNode = Eigen::Matrix3Xd::Zero(3, nn);
  Eigen::Matrix3Xd f(3, nn);
  if (env.plane.enabled) {
    f.setZero();
    addPlaneContact(p, env.plane, s, false, f);
    if (env.friction.enabled) addPlateFriction(p, env, s, f);
    o.perNode.row(0) = f.colwise().norm();
  }
  if (env.selfContact.enabled) {
    f.setZero();
    addSelfContact(p, env, s, false, cw, f);
    o.perNode.row(1) = f.colwise().norm();
  }
  if (!env.obstacles.empty()) {
    f.setZero();
    addObstacleContact(p, env, s, false, cw, f);
    if (env.friction.enabled) addObstacleFriction(env, s, cw, f);
    o.perNode.row(2) = f.colwise().norm();
  }
  return o;
}

int firstNodeNearContact(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw,
                         int from) {
  int first = s.nodes();
  if (!env.selfContact.enabled) return first;
  if (static_cast<int>(cw.order.size()) != s.elements()) cw.resize(s.elements());
  cw.invalidate();  // the pairs within 2R + skin of this very state (not of when the list was built)
  updatePairs(p, s, cw);
  for (const auto& [i, j] : cw.pairs)
    if (j + 1 >= from) first = std::min(first, i);  // i < j: the younger element reaches node `from`
  return first;
}

void markSelfContactNodes(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw) {
  if (static_cast<int>(cw.order.size()) != s.elements()) cw.resize(s.elements());
  std::fill(cw.contactNode.begin(), cw.contactNode.end(), 0);
  if (!env.selfContact.enabled) return;
  updatePairs(p, s, cw);
  for (const auto& [i, j] : cw.pairs) {
    if (pairGeometry(s, i, j).dist >= 2.0 * p.radius) continue;
    for (int a : {i, i + 1, j, j + 1}) cw.contactNode[static_cast<size_t>(a)] = 1;
  }
}

}  // namespace rootsim
