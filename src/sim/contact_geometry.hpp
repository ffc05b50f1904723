#pragma once
// internal to the contact pieces (contact.cpp, contact_newton.cpp, contact_observe.cpp): the geometry
// they share (closest points, the obstacle segments, the self-contact Verlet list) and Coulomb's law.
// The small helpers are inline: the force evaluation calls them per node and per pair.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "rootsim/contact.hpp"

namespace rootsim::contact_detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// Verlet skin of the self-contact list, in radii: pairs within 2R + skin are listed, and the list stays
// valid while no node has moved more than skin/2 (the centreline distance of two segments changes by at
// most the largest displacement of their four nodes, twice skin/2 for two segments)
inline constexpr double kSkinRadii = 1.0;

// a node "touches" for friction (gets a stick point) within this fraction of R of a surface; the rod
// starts exactly at the plate (gap 0 up to round-off)
inline constexpr double kTouchRadii = 1e-3;

inline double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

// unit in-plane axis of the rod at node i, perpendicular to the contact normal nh (zero when the rod is
// along the normal there)
inline Vec3 nodeAxis(const RodState& s, int i, const Vec3& nh) {
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
// (docs/contact.md, Friction). ell = 0 gives the abrupt drop.
inline Vec3 coulomb(const Vec3& u, const Vec3& a, double kt, double N, const Friction& fr, bool& slips) {
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
inline double plateNodeNormal(const RodParams& p, const Plane& plane, const RodState& s, int i, double& minGap) {
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
inline void obstacleSegment(const PlateFrame& f, const Obstacle& o, Vec3& b0, Vec3& b1) {
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

inline bool excludedAlongRod(const RodParams& p, const RodState& s, int i, int j) {
  // neighbours along the rod always overlap; elements whose nearest ends are closer than
  // kSelfExclusionRadii * R in rest arc length are treated as neighbours too
  return j <= i + 1 || s.S[j] - s.S[i + 1] < kSelfExclusionRadii * p.radius;
}

// (re)builds the Verlet list when it is stale; allocation-free while the pair count stays below the
// capacity reserved by resize
// a list built at xBuilt serves while no node has moved more than skin/2 since (then every pair now
// closer than 2R is in it) and the rod has not grown (the exclusion along the rod uses rest arc length)
inline bool listServes(const RodState& s, double skin, const Eigen::Matrix3Xd& xBuilt, int builtElements,
                double builtRestLength) {
  const int n = s.elements();
  if (builtElements != n || builtRestLength != s.S[n]) return false;
  const double lim2 = 0.25 * skin * skin;
  for (int i = 0; i <= n; ++i)
    if ((s.x.col(i) - xBuilt.col(i)).squaredNorm() > lim2) return false;
  return true;
}

void updatePairs(const RodParams& p, const RodState& s, ContactWorkspace& cw);

// closest points of a listed pair: the two points, their parameters and the distance
struct PairGeometry {
  double sa = 0, sb = 0, dist = 0;
  Vec3 d = Vec3::Zero();  // point on i minus point on j
};
inline PairGeometry pairGeometry(const RodState& s, int i, int j) {
  PairGeometry g;
  closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), g.sa, g.sb);
  g.d = (s.x.col(i) + g.sa * (s.x.col(i + 1) - s.x.col(i))) - (s.x.col(j) + g.sb * (s.x.col(j + 1) - s.x.col(j)));
  g.dist = g.d.norm();
  return g;
}


// the elastic contact of one element pair (nodes a0-a1 against b0-b1): closest-point weights, the
// normal (from b towards a) and fn = k (2R - distance); false when the capsules do not overlap
struct PairContact {
  double sa = 0, sb = 0, fn = 0;
  Vec3 nrm = Vec3::Zero();
};
inline bool pairContact(double R, double k, const Vec3& up, const Vec3& a0, const Vec3& a1, const Vec3& b0,
                 const Vec3& b1, PairContact& pc) {
  const double contact = 2.0 * R;
  // boxes of the two segments farther apart than the contact distance along an axis: no point of one is
  // within it of the other (the margin, far above rounding, keeps the answer the full test's)
  const double reach = contact * (1.0 + 1e-9);
  for (int ax = 0; ax < 3; ++ax)
    if (std::min(a0[ax], a1[ax]) - std::max(b0[ax], b1[ax]) > reach || std::min(b0[ax], b1[ax]) - std::max(a0[ax], a1[ax]) > reach)
      return false;
  contactSegmentPoints(a0, a1, b0, b1, pc.sa, pc.sb);
  const Vec3 d = (a0 + pc.sa * (a1 - a0)) - (b0 + pc.sb * (b1 - b0));
  const double dist = d.norm();
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

// the friction pieces on the plate and on the obstacles (contact.cpp), also evaluated alone to observe
// the contact force per node (contact_observe.cpp)
void addPlateFriction(const RodParams& p, const Environment& env, const RodState& s, Eigen::Matrix3Xd& force);
void addObstacleFriction(const Environment& env, const RodState& s, const ContactWorkspace& cw,
                         Eigen::Matrix3Xd& force);

}  // namespace rootsim::contact_detail
