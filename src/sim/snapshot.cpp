#include "rootsim/snapshot.hpp"

#include "rootsim/assert.hpp"
#include "rootsim/model.hpp"
#include "rootsim/rod.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

Snapshot makeSnapshot(const RodParams& p, const RodState& s, const RodStrains& k, int step) {
  ROOTSIM_ASSERT(k.e.size() == 0 || k.e.size() == s.elements(), "strains of this state (or none)");
  Snapshot sn;
  const int n = s.elements();
  sn.step = step;
  sn.timeH = s.time / units::hour;
  sn.x = s.x;
  sn.d1.resize(3, n);
  sn.d3.resize(3, n);
  sn.radius.resize(n);
  for (int i = 0; i < n; ++i) {
    sn.d1.col(i) = s.Q[static_cast<size_t>(i)].row(0).transpose();
    sn.d3.col(i) = s.Q[static_cast<size_t>(i)].row(2).transpose();
    sn.radius[i] = elementRadius(p, k.e.size() == n ? k.e[i] : 1.0);
  }
  // |(kappa0_1, kappa0_2)| of each interior (Voronoi) node, 0 at the two ends
  sn.kappa0 = Eigen::VectorXd::Zero(n + 1);
  for (int j = 0; j + 1 < n && j < s.kappa0.cols(); ++j) sn.kappa0[j + 1] = s.kappa0.col(j).head<2>().norm();
  return sn;
}

SceneInfo sceneInfoOf(const Model& m) {
  SceneInfo si;
  si.alphaDeg = m.env.plane.alpha / units::deg;
  si.beta = m.tropism.beta;
  si.gamma = m.tropism.gamma;
  si.rTau = m.tropism.rTau;
  si.radius = m.rod.radius;
  si.zoneLength = m.growth.zoneLength;
  si.plate = m.env.plane.enabled;
  si.title = m.name;
  for (const Obstacle& o : m.env.obstacles) {
    SceneInfo::ObstacleShape sh;
    sh.peg = o.shape == Obstacle::Shape::Peg;
    sh.fromU = o.from.x() / units::mm, sh.fromV = -o.from.y() / units::mm;  // downhill -> uphill
    sh.toU = o.to.x() / units::mm, sh.toV = -o.to.y() / units::mm;
    sh.radiusMm = o.radius / units::mm;
    si.obstacles.push_back(sh);
  }
  return si;
}

}  // namespace rootsim
