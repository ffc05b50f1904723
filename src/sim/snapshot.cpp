#include "rootsim/snapshot.hpp"

#include <algorithm>
#include <stdexcept>

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

Snapshot mergeRoots(const std::vector<Snapshot>& roots) {
  Snapshot m;
  if (roots.empty()) return m;
  m.step = roots.front().step;
  m.timeH = roots.front().timeH;
  long nodes = 0;
  for (const Snapshot& r : roots) nodes += r.x.cols();
  const long elements = nodes - 1;
  const bool fields = std::all_of(roots.begin(), roots.end(), [](const Snapshot& r) { return r.kappa0.size() > 0; });
  const bool contact = std::all_of(roots.begin(), roots.end(), [](const Snapshot& r) { return r.contactForce.cols() > 0; });
  m.x.resize(3, nodes);
  m.d1.resize(3, elements);
  m.d3.resize(3, elements);
  m.radius.resize(elements);
  if (fields) {
    m.kappa0.resize(nodes);
    m.plateForce.resize(nodes);
  }
  if (contact) m.contactForce.resize(3, nodes);
  long node = 0, element = 0;
  for (size_t k = 0; k < roots.size(); ++k) {
    const Snapshot& r = roots[k];
    const long nn = r.x.cols(), ne = r.radius.size();
    if (k > 0) {
      m.rootStarts.push_back(static_cast<int>(node));
      // the joining element: the next root's first element's fields
      m.d1.col(element) = r.d1.col(0);
      m.d3.col(element) = r.d3.col(0);
      m.radius[element] = r.radius[0];
      ++element;
    }
    m.x.middleCols(node, nn) = r.x;
    m.d1.middleCols(element, ne) = r.d1;
    m.d3.middleCols(element, ne) = r.d3;
    m.radius.segment(element, ne) = r.radius;
    if (fields) {
      m.kappa0.segment(node, nn) = r.kappa0;
      m.plateForce.segment(node, nn) = r.plateForce;
    }
    if (contact) m.contactForce.middleCols(node, nn) = r.contactForce;
    node += nn;
    element += ne;
  }
  return m;
}

Snapshot rootOf(const Snapshot& m, int k) {
  if (m.rootStarts.empty()) return m;
  const long first = k == 0 ? 0 : m.rootStarts[static_cast<size_t>(k - 1)];
  const long end = k + 1 < rootCount(m) ? m.rootStarts[static_cast<size_t>(k)] : m.x.cols();
  const long nn = end - first, ne = nn - 1;
  Snapshot r;
  r.step = m.step;
  r.timeH = m.timeH;
  r.x = m.x.middleCols(first, nn);
  // root k's elements start after the k joining elements before it
  r.d1 = m.d1.middleCols(first, ne);
  r.d3 = m.d3.middleCols(first, ne);
  r.radius = m.radius.segment(first, ne);
  if (m.kappa0.size() > 0) {
    r.kappa0 = m.kappa0.segment(first, nn);
    r.plateForce = m.plateForce.segment(first, nn);
  }
  if (m.contactForce.cols() > 0) r.contactForce = m.contactForce.middleCols(first, nn);
  return r;
}

int nearestSnapshot(const std::vector<double>& timesH, double timeH) {
  if (timesH.empty()) throw std::invalid_argument("nearestSnapshot: no snapshots");
  // the first at or after timeH, then the earlier neighbour when it is as near or nearer
  const auto it = std::lower_bound(timesH.begin(), timesH.end(), timeH);
  if (it == timesH.end()) return static_cast<int>(timesH.size()) - 1;
  const int i = static_cast<int>(it - timesH.begin());
  if (i > 0 && timeH - timesH[static_cast<std::size_t>(i - 1)] <= *it - timeH) return i - 1;
  return i;
}

}  // namespace rootsim
