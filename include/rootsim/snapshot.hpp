#pragma once
// What a picture needs of one moment of a run: the rod's shape and material frame, in the lab frame of
// docs/model.md, Frames and signs. Saved in the run directory's trajectory and handed to the renderer;
// carries no solver state.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace rootsim {

struct Snapshot {
  int step = 0;                // growth step
  double timeH = 0.0;          // growth time [h]
  Eigen::Matrix3Xd x;          // node positions [m]                         (3 x n+1)
  Eigen::Matrix3Xd d1;         // director d1 of each element, lab, unit     (3 x n)
  Eigen::Matrix3Xd d3;         // director d3 of each element, lab, unit     (3 x n); d2 = d3 x d1
  Eigen::VectorXd radius;      // element radius R / sqrt(lambda_e) [m]      (n)
  // per node, for colouring the tube; empty when the trajectory predates them
  Eigen::VectorXd kappa0;      // |(kappa0_1, kappa0_2)| intrinsic bending curvature per rest length,
                               // Voronoi value at interior nodes, 0 at the two ends [1/m]   (n+1)
  Eigen::VectorXd plateForce;  // normal force of the plate on the node (the law of
                               // addPlaneContact without damping) [N]                        (n+1)
  // |contact force| on each node from the plate (with friction), from self-contact and from obstacles
  // (with friction) [N] (3 x n+1); empty when the trajectory did not record it
  Eigen::Matrix3Xd contactForce;
  // a plate's roots in one snapshot (mergeRoots): the first node of each root after the first; the
  // element before each such node joins two roots and is not part of either (empty: one root)
  std::vector<int> rootStarts;
  int elements() const { return static_cast<int>(radius.size()); }
};

// the snapshot nearest timeH (ties to the earlier one); timesH increasing; std::invalid_argument when empty
int nearestSnapshot(const std::vector<double>& timesH, double timeH);
// the roots of a plate as one snapshot (the renderer draws each root as its own tube): their nodes in
// turn, each root's positions as given (already in one frame), the joining elements' fields copied
// from the next root's first element. Step and time are the first root's.
Snapshot mergeRoots(const std::vector<Snapshot>& roots);
// root k of a merged snapshot (k from 0), as a snapshot of its own; the snapshot itself for one root
Snapshot rootOf(const Snapshot& merged, int k);
inline int rootCount(const Snapshot& s) { return static_cast<int>(s.rootStarts.size()) + 1; }

struct RodParams;
struct RodState;
struct RodStrains;
// the snapshot of a state: shape, directors, radius R / sqrt(e) (strains must belong to the state)
Snapshot makeSnapshot(const RodParams& p, const RodState& s, const RodStrains& k, int step);

// the constant facts a picture shows beside the rod: the plate and the parameters
struct SceneInfo {
  double alphaDeg = 40.0;      // plate tilt from the vertical [deg]
  double beta = 0.1;           // gravitropic gain
  double gamma = 0.1;          // proprioceptive gain
  double rTau = 0.0;           // intrinsic twist R tau
  double radius = 1e-4;        // rest radius R [m]
  double zoneLength = 1e-3;    // growth zone length Lgz [m] (the last Lgz of material grows)
  bool plate = true;           // draw the plate (false for a free organ)
  // obstacles on the plate (docs/model.md, Contact and friction), in the top view's plate coordinates [mm]:
  // u lateral, v uphill (PlateFrame::toPlateMm); a peg has from == to
  struct ObstacleShape {
    bool peg = true;
    double fromU = 0, fromV = 0, toU = 0, toV = 0;
    double radiusMm = 0;       // peg radius, or half the wall's thickness [mm]
  };
  std::vector<ObstacleShape> obstacles;
  std::string title;           // e.g. the scene name
};

// one root of a plate's run as the exports show it (docs/plate.md): its name, its snapshots in the
// plate's lab frame, the first of them at the plate's snapshot firstFrame (a lateral root emerges after
// the plate's first snapshot)
struct RootSeries {
  std::string name;
  std::vector<Snapshot> snaps;
  int firstFrame = 0;
};

struct Model;
// the facts of a model: its plate tilt, tropism gains, radius, plate, obstacles and its name as title
SceneInfo sceneInfoOf(const Model& m);

}  // namespace rootsim
