#pragma once
// Per-node quantities of a snapshot, computed from the Snapshot alone (no solver state, no file format,
// no GL), for everything that draws or exports the root: the material frame averaged at the nodes (the
// renderer's tube rings, ParaView's point data), the material-frame angle of d1 about the tangent (ParaView,
// RSML), the bending and twist per Voronoi node, the stretch and the growth zone (docs/paraview.md, Point
// data).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "rootsim/environment.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// the material frame at a node: unit tangent t, unit d1 normal to t, d2 = t x d1, and the radius
struct NodeFrame {
  Eigen::Vector3d t, d1, d2;
  double radius = 0;  // mean of the adjacent elements' radii (one element at the ends) [m]
};

// The frame at every node (n+1) from the element directors: t is the normalised sum of the adjacent
// elements' d3, d1 the sum of their d1 made normal to t and normalised, d2 = t x d1 (a node between two
// elements takes their mean; an end node its one element). `dir` maps a lab direction into the
// coordinates wanted (the identity for the lab frame; PlateFrame::dirToPlate for the top view's) before
// the sums, so that the renderer's rings keep their bytes.
template <class DirMap>
std::vector<NodeFrame> nodeFrames(const Snapshot& s, DirMap&& dir) {
  const int n = s.elements();
  std::vector<NodeFrame> frames(static_cast<std::size_t>(n + 1));
  for (int i = 0; i <= n; ++i) {
    Eigen::Vector3d t = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero();
    double r = 0.0;
    int cnt = 0;
    for (int e : {i - 1, i}) {
      if (e < 0 || e >= n) continue;
      t += dir(Eigen::Vector3d(s.d3.col(e)));
      a += dir(Eigen::Vector3d(s.d1.col(e)));
      r += s.radius[e];
      ++cnt;
    }
    NodeFrame& g = frames[static_cast<std::size_t>(i)];
    if (t.norm() < 1e-12) t = Eigen::Vector3d::UnitY();
    g.t = t.normalized();
    a -= a.dot(g.t) * g.t;
    if (a.norm() < 1e-12) a = g.t.unitOrthogonal();
    g.d1 = a.normalized();
    g.d2 = g.t.cross(g.d1);
    g.radius = r / cnt;
  }
  return frames;
}
// the frames in the lab frame
std::vector<NodeFrame> nodeFrames(const Snapshot& s);

// The material-frame angle [rad, in (-pi, pi]] of d1 about the tangent t (both unit, lab): the angle from
// the in-plate reference e = n_perp x t (n_perp: the plate normal made normal to t) to d1, positive
// right-handed about t (towards n_perp): atan2(d1 . n_perp, d1 . e). 0: d1 lies in the plate, to the
// right of the tangent seen from above (the initial root's d1, the lateral axis); +90 deg: d1 points away
// from the plate. Where t is along the plate normal (|n_perp| < 1e-9) e is the plate's lateral axis made
// normal to t and n_perp = t x e. One definition for every writer (ParaView's point data, RSML).
double materialAngle(const Eigen::Vector3d& t, const Eigen::Vector3d& d1, const PlateFrame& plate);

// the rotation vector kappa = log(Q_j Q_{j+1}^T) between the directors of elements j and j+1 (material
// components, as rod.cpp's curvature: kappa1, kappa2 bending, kappa3 twist) and the current Voronoi
// length between them, the mean of the two elements' lengths [m]; one per interior node (n-1)
struct VoronoiBend {
  Eigen::Vector3d kappa;  // [rad]
  double length = 0;      // [m]
};
std::vector<VoronoiBend> voronoiBends(const Snapshot& s);

// interior Voronoi values (n-1) spread to the n+1 nodes, the ends copying their neighbour (zeros when
// n < 2)
Eigen::VectorXd voronoiToNodes(const Eigen::VectorXd& voronoi, int n);

// the stretch lambda_e = (R / radius_e)^2 of each element from its radius (Snapshot::radius is
// R / sqrt(lambda_e)), at the nodes: the mean of the adjacent elements' (one at the ends) [-]
Eigen::VectorXd nodeStretch(const Snapshot& s, double restRadius);

// 1 at the nodes of the growth zone, 0 elsewhere: a node is in it when the rest length from it to the tip
// is at most zoneLength (docs/model.md, Growth: the zone is the last Lgz of material). Rest lengths come
// from the snapshot: element e's current length over its stretch (R / radius_e)^2.
Eigen::VectorXd growthZoneNodes(const Snapshot& s, double restRadius, double zoneLength);

}  // namespace rootsim
