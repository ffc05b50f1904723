#pragma once
// Discrete Cosserat rod (docs/model.md, Rod mechanics; Gazzola et al. 2018, "Forward and inverse problems in
// the mechanics of soft filaments", the scheme PyElastica implements).
//
//   nodes 0..n           positions x, velocities v                      (3 x n+1)
//   elements 0..n-1      directors Q (rows d1, d2, d3), angular velocity w (material frame), rest length l0
//   Voronoi 0..n-2       interior node between element j and j+1: curvature kappa, intrinsic kappa0
//
// Nothing here knows about growth, scenes or pictures.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rootsim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// constant material description of the rod
struct RodParams {
  double radius = 1e-4;           // rest radius R [m]
  double youngs = 50e6;           // Young's modulus E [Pa]
  double density = 1000.0;        // density [kg/m^3] (physical-mass relaxation only)
  Vec3 shearFactors{8.0 / 9.0, 8.0 / 9.0, 1.0};   // S = E pi R^2 diag(shearFactors)
  Vec3 bendFactors{0.25, 0.25, 1.0 / 6.0};        // B = E pi R^4 diag(bendFactors)

  Vec3 shearStiffness() const;    // diagonal of S [N]
  Vec3 bendStiffness() const;     // diagonal of B [N m^2]
};

// changing state of the rod; its members are listed once, with where each lives and how a split treats
// it, in rootsim/rod_fields.hpp (resize, splitLongElements, the checkpoint and Python's State walk that
// list; a member left out of it stops the build)
struct RodState {
  Eigen::Matrix3Xd x;        // node positions [m]                             (3 x n+1)
  Eigen::Matrix3Xd v;        // node velocities [m/s] (pseudo-velocities when mass is scaled) (3 x n+1)
  std::vector<Mat3> Q;       // directors, rows d1 d2 d3 (lab components)       (n)
  Eigen::Matrix3Xd w;        // angular velocity, material components [rad/s]   (3 x n)
  Eigen::VectorXd l0;        // rest lengths, changed only by growth [m]        (n)
  Eigen::VectorXd S;         // material coordinate of each node, rest arc length from the base [m] (n+1)
  Eigen::Matrix3Xd kappa0;   // intrinsic curvature per unit rest length, material comps [1/m] (3 x n-1)
  Eigen::Matrix3Xd anchor;   // adhesion anchor of each node [m]               (3 x n+1)
  std::vector<std::uint8_t> anchored;  // 1 if the node is pinned to its anchor   (n+1)
  // friction history (docs/model.md, Contact and friction), committed once per growth step by commitFriction:
  // the stick point of each node on the plate and on an obstacle [m] (3 x n+1), valid where the flag is 1
  Eigen::Matrix3Xd plateStick;
  std::vector<std::uint8_t> hasPlateStick;     // (n+1)
  Eigen::Matrix3Xd obstacleStick;
  std::vector<std::uint8_t> hasObstacleStick;  // (n+1)
  // frame of the clamped base at s = 0, rows d1 d2 d3 (lab): the first element's directors when the
  // rod was made (makeInitialRod); element 0 is tied to it through a half Voronoi domain (clampCouple)
  Mat3 clampFrame = Mat3::Identity();
  double time = 0.0;         // growth time [s]

  int elements() const { return static_cast<int>(l0.size()); }
  int nodes() const { return elements() + 1; }
  double restLength() const { return l0.sum(); }
  // resize every listed field for n elements (arrays left unset, flags 0)
  void resize(int n);
};

// per-element and per-Voronoi strains and stresses, computed from a state
struct RodStrains {
  Eigen::VectorXd l;         // current element lengths [m]                   (n)
  Eigen::VectorXd e;         // dilatation l / l0 (the paper's lambda_e)       (n)
  Eigen::Matrix3Xd t;        // unit tangents (lab)                            (3 x n)
  Eigen::Matrix3Xd sigma;    // shear/stretch strain Q (e t - d3), material    (3 x n)
  Eigen::Matrix3Xd nMat;     // internal force S sigma / e, material [N]       (3 x n)
  Eigen::Matrix3Xd nLab;     // internal force, lab [N]                        (3 x n)
  Eigen::VectorXd D0;        // Voronoi rest lengths [m]                       (n-1)
  Eigen::VectorXd ev;        // Voronoi dilatation                             (n-1)
  Eigen::Matrix3Xd kappa;    // curvature log(Q_j Q_{j+1}^T) / D0, material [1/m] (3 x n-1)
  Eigen::Matrix3Xd m;        // internal couple B (kappa/ev - kappa0)/ev^2, material [N m] (3 x n-1)

  void resize(int n);
};

// strains and stresses of the rod (docs/model.md, Rod mechanics; paper Eqs. 24-25 with the incompressibility
// rescaling S -> S/e, B -> B/e^2, kappa -> kappa/e)
// (first > 0: only elements and Voronoi domains from `first` on, for a solver that moves only those;
// end >= 0: only those before element `end` (Voronoi domains before end - 1); what lies outside is left
// as it was)
void computeStrains(const RodParams& p, const RodState& s, RodStrains& k, int first = 0, int end = -1);

// internal forces on nodes (lab) and couples on elements (material), from computed strains;
// force (3 x n+1) and torque (3 x n) are overwritten (from node and element `first` on; node `first`
// then lacks the force of element first - 1, and element `first` the couple of Voronoi first - 1;
// end >= 0: up to node and element `end` - 1, element end - 1 then lacking the couple of Voronoi end - 1)
void computeInternalForces(const RodState& s, const RodStrains& k, Eigen::Matrix3Xd& force,
                           Eigen::Matrix3Xd& torque, int first = 0, int end = -1);

// where a loop over `count` elements or nodes stops for a span ending at `end` (end < 0: at the tip)
inline int spanEnd(int end, int count) { return end >= 0 && end < count ? end : count; }

// radius of element i, shrinking with dilatation as R / sqrt(e) [m]
inline double elementRadius(const RodParams& p, double e) { return p.radius / std::sqrt(e); }

}  // namespace rootsim
