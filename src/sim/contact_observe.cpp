// What is observed of a state's contacts (contact_observe.hpp): counts, closest approach, force per node.
#include "rootsim/contact_observe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_geometry.hpp"
#include "rootsim/environment.hpp"

namespace rootsim {

using namespace contact_detail;

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

}  // namespace rootsim
