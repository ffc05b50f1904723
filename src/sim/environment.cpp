#include "rootsim/environment.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "rootsim/assert.hpp"
#include "rootsim/contact.hpp"
#include "rootsim/rotation.hpp"

namespace rootsim {

namespace {
// cos and sin that are exact at multiples of 90 degrees, so a horizontal or vertical plate gives
// exactly planar problems (cos(pi/2) = 6e-17 would otherwise seed out-of-plane modes)
std::pair<double, double> cosSin(double a) {
  const double q = a / (0.5 * std::numbers::pi);
  const double r = std::round(q);
  if (std::abs(q - r) < 1e-14) {
    static constexpr double c[4] = {1, 0, -1, 0}, s[4] = {0, 1, 0, -1};
    const int k = static_cast<int>(((static_cast<long>(r) % 4) + 4) % 4);
    return {c[k], s[k]};
  }
  return {std::cos(a), std::sin(a)};
}
}  // namespace

PlateFrame PlateFrame::tilted(double alpha) {
  const auto [ca, sa] = cosSin(alpha);
  PlateFrame f;
  f.normal = Vec3(0.0, -ca, sa);
  f.downhill = Vec3(0.0, -sa, -ca);
  f.lateral = Vec3::UnitX();
  return f;
}

Vec3 PlateFrame::toPlateMm(const Vec3& labM) const {
  return Vec3(lateral.dot(labM), -downhill.dot(labM), normal.dot(labM)) / units::mm;
}

ClampCouple clampCouple(const RodParams& p, const RodState& s, double e0) {
  // A clamp that fixed element 0's own directors would put the clamped cross-section at the element
  // centre, l0/2 from the base node, and make every deflection first-order in l0 (the error against
  // Timoshenko's cantilever halves with the element length). Instead the clamp frame sits at s = 0 and couples
  // to element 0 through a half Voronoi domain, as interior elements couple to each other; the scheme
  // then stays second order. (docs/model.md, Environment says "directors of the first element"; this is the
  // same clamp moved to the base node.)
  ROOTSIM_ASSERT(s.elements() >= 1 && s.l0[0] > 0.0 && e0 > 0.0, "a clamped rod with a first element of positive length");
  const double D0 = 0.5 * s.l0[0];
  ClampCouple c;
  c.kappa = rotationToVector(s.clampFrame * s.Q[0].transpose()) / D0;
  const double ev = e0;
  c.m = p.bendStiffness().cwiseProduct(c.kappa / ev) / (ev * ev);
  // element 0 sees the clamp domain on its left: -m + (D0/2) kappa x m
  c.torque = -c.m + 0.5 * D0 * c.kappa.cross(c.m);
  return c;
}

void addPlaneContact(const RodParams& p, const Plane& plane, const RodState& s, bool damping,
                     Eigen::Matrix3Xd& force, int first, int end) {
  // one-sided penalty on the surface gap (r_mid . n - R, with the rest radius, docs/model.md, Environment: a
  // gap using R / sqrt(e) would make the contact force depend on stretching without an energy behind
  // it, which shows up as a spurious unstable direction of the stiffness matrix) plus normal damping,
  // shared by the element's two nodes
  const int n = spanEnd(end, s.elements());
  const Vec3 nh = plane.normal();
  for (int i = first; i < n; ++i) {
    const Vec3 mid = 0.5 * (s.x.col(i) + s.x.col(i + 1));
    const double gap = mid.dot(nh) - p.radius;
    if (gap >= 0.0) continue;
    double fn = -plane.k * gap;
    if (damping) fn -= plane.c * 0.5 * (s.v.col(i) + s.v.col(i + 1)).dot(nh);
    const Vec3 f = 0.5 * fn * nh;
    force.col(i) += f;
    force.col(i + 1) += f;
  }
}

Eigen::VectorXd plateNormalForce(const RodParams& p, const Plane& plane, const RodState& s) {
  if (!plane.enabled) return Eigen::VectorXd::Zero(s.nodes());
  // the contact law itself (addPlaneContact, without damping), projected on the normal
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, s.nodes());
  addPlaneContact(p, plane, s, false, force);
  return (plane.normal().transpose() * force).transpose();
}

void addAdhesion(double k, const RodState& s, Eigen::Matrix3Xd& force, int first, int end) {
  const int n = spanEnd(end, s.nodes());
  for (int i = first; i < n; ++i)
    if (s.anchored[static_cast<size_t>(i)]) force.col(i) += k * (s.anchor.col(i) - s.x.col(i));
}

void addWeight(const RodParams& p, const Vec3& gravity, const RodState& s, Eigen::Matrix3Xd& force, int first,
               int end) {
  const double rhoA = p.density * units::pi * p.radius * p.radius;
  const int n = spanEnd(end, s.elements());
  for (int i = first; i < n; ++i) {
    const Vec3 w = 0.5 * rhoA * s.l0[i] * gravity;
    force.col(i) += w;
    force.col(i + 1) += w;
  }
}

void addTipLoads(const Environment& env, const RodState& s, Eigen::Matrix3Xd& force, Eigen::Matrix3Xd& torque) {
  const int n = s.elements();
  force.col(n) += env.tipForce;
  torque.col(n - 1) += s.Q[static_cast<size_t>(n - 1)] * env.tipTorque;
}

void addExternalForces(const RodParams& p, const Environment& env, const RodState& s,
                       const RodStrains& k, bool planeDamping, ContactWorkspace& cw,
                       Eigen::Matrix3Xd& force, Eigen::Matrix3Xd& torque, ForceSpan span, ForcePieces pieces) {
  // the contact pieces of contact.cpp act on the whole rod (contacts may couple any two nodes); on
  // nodes outside the span their forces are exact too
  const int from = std::max(span.first, span.outsideFrom);
  if (env.plane.enabled) addPlaneContact(p, env.plane, s, planeDamping, force, from, span.end);
  if (!env.obstacles.empty()) addObstacleContact(p, env, s, planeDamping, cw, force);
  if (env.selfContact.enabled && pieces == ForcePieces::All) addSelfContact(p, env, s, planeDamping, cw, force);
  if (!cw.neighbours.empty() && pieces == ForcePieces::All) addNeighbourContact(p, env, s, planeDamping, cw, force);
  if (env.friction.enabled) addFriction(p, env, s, cw, force);
  if (env.adhesion) addAdhesion(env.kAdhesion, s, force, from, span.end);
  if (env.gravity.squaredNorm() > 0.0) addWeight(p, env.gravity, s, force, from, span.end);
  if (env.base == BaseCondition::Clamped && span.first == 0) torque.col(0) += clampCouple(p, s, k.e[0]).torque;
  if (span.end < 0 || span.end >= s.elements()) addTipLoads(env, s, force, torque);
}

void holdClampedBase(const Environment& env, Eigen::Matrix3Xd& force) {
  if (env.base == BaseCondition::Clamped) force.col(0).setZero();
}

}  // namespace rootsim
