// Per-node quantities of a snapshot (node_fields.hpp): GL-free and format-free, shared by the renderer
// and the writers.
#include "rootsim/node_fields.hpp"

#include <algorithm>
#include <cmath>

#include "rootsim/rotation.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {
// directors of element e as the rows of a matrix (d2 = d3 x d1)
Eigen::Matrix3d directors(const Snapshot& s, int e) {
  Eigen::Matrix3d Q;
  const Eigen::Vector3d d1 = s.d1.col(e), d3 = s.d3.col(e);
  Q.row(0) = d1.transpose();
  Q.row(1) = d3.cross(d1).transpose();
  Q.row(2) = d3.transpose();
  return Q;
}
}  // namespace

std::vector<NodeFrame> nodeFrames(const Snapshot& s) {
  return nodeFrames(s, [](const Eigen::Vector3d& d) { return d; });
}

double materialAngle(const Eigen::Vector3d& t, const Eigen::Vector3d& d1, const PlateFrame& plate) {
  Eigen::Vector3d np = plate.normal - plate.normal.dot(t) * t, e;
  if (np.norm() > 1e-9) {
    np.normalize();
    e = np.cross(t);
  } else {
    e = (plate.lateral - plate.lateral.dot(t) * t).normalized();
    np = t.cross(e);
  }
  const double a = std::atan2(d1.dot(np), d1.dot(e));
  return a > -units::pi ? a : units::pi;  // atan2(-0, -1) = -pi: the half-open range (-pi, pi]
}

std::vector<VoronoiBend> voronoiBends(const Snapshot& s) {
  const int n = s.elements();
  std::vector<VoronoiBend> v(static_cast<std::size_t>(std::max(n - 1, 0)));
  for (int j = 0; j + 1 < n; ++j) {
    VoronoiBend& b = v[static_cast<std::size_t>(j)];
    b.kappa = rotationToVector(directors(s, j) * directors(s, j + 1).transpose());
    b.length = 0.5 * ((s.x.col(j + 1) - s.x.col(j)).norm() + (s.x.col(j + 2) - s.x.col(j + 1)).norm());
  }
  return v;
}

Eigen::VectorXd voronoiToNodes(const Eigen::VectorXd& voronoi, int n) {
  Eigen::VectorXd v(n + 1);
  if (n < 2) return Eigen::VectorXd::Zero(n + 1);
  v.segment(1, n - 1) = voronoi;
  v[0] = voronoi[0];
  v[n] = voronoi[n - 2];
  return v;
}

Eigen::VectorXd nodeStretch(const Snapshot& s, double restRadius) {
  const int n = s.elements();
  Eigen::VectorXd v(n + 1);
  auto lambda = [&](int e) { return std::pow(restRadius / s.radius[e], 2); };
  for (int i = 0; i <= n; ++i) {
    const int a = std::max(i - 1, 0), b = std::min(i, n - 1);
    v[i] = 0.5 * (lambda(a) + lambda(b));
  }
  return v;
}

Eigen::VectorXd growthZoneNodes(const Snapshot& s, double restRadius, double zoneLength) {
  const int n = s.elements();
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n + 1);
  double fromTip = 0.0;  // rest length from node i to the tip [m]
  for (int i = n; i >= 0; --i) {
    if (i < n) {
      const double lambda = std::pow(restRadius / s.radius[i], 2);
      fromTip += (s.x.col(i + 1) - s.x.col(i)).norm() / lambda;
    }
    // a relative tolerance: the zone's first node sits at exactly Lgz from the tip up to round-off
    if (fromTip <= zoneLength * (1 + 1e-9)) v[i] = 1.0;
  }
  return v;
}

}  // namespace rootsim
