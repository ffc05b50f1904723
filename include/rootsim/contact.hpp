#pragma once
// Contact beyond the paper (docs/model.md, Contact and friction): the rod against itself, against rigid
// obstacles on the plate, and Coulomb friction on the plate and the obstacles. Each is a force piece that
// addExternalForces (environment.cpp) calls, so every solver that evaluates computeForces shares them.
//
// Conventions, as the plate's (environment.cpp): penalty springs act on the surface gap computed with
// the rest radius R, per element (per element pair for self-contact), with normal damping c (only with
// physical masses); a force applied at a point inside an element is split to its two nodes by the
// point's segment parameter (linear interpolation), which keeps every pair of contact forces free of
// net force and net moment about any point.
//
// Friction is quasi-static and incremental: within one relaxation the tangential force of a node is a
// pure function of its position and of the stick point committed after the previous relaxation
// (a backward-Euler step, as the return mapping of elastoplasticity), so the force evaluation stays a
// function of the state (what a Newton solver needs); commitFriction moves the stick points once the
// equilibrium is reached.
#include <array>
#include <cstdint>
#include <vector>

#include "rootsim/environment.hpp"
#include "rootsim/fields.hpp"

namespace rootsim {

// the stiffness of one self-contact pair, K = -dF/dx over the 12 coordinates of its four nodes
// (i, i+1, j, j+1 in that order) [N/m]
struct PairStiffness {
  int i = 0, j = 0;
  Eigen::Matrix<double, 12, 12> K;
};

// the other roots on a plate as one root's contact pieces see them (docs/model.md, "A plate of roots"):
// their elements as capsules, in this root's own frame, fixed during one relaxation; set by the plate
// (plate.cpp) before each relaxation, empty for a root alone
struct NeighbourCapsules {
  Eigen::Matrix3Xd a, b;                  // ends of each capsule's centreline, this root's frame [m]
  Eigen::VectorXd radius;                 // each capsule's radius [m]
  std::vector<std::uint8_t> first;        // 1 where this root is the pair's first root (lower plate index):
                                          // a pair's force is always computed in the first root's order, so
                                          // the two roots feel exactly opposite forces
  std::vector<std::array<int, 2>> pairs;  // candidate pairs (element of this root, capsule), within
                                          // R + r + skin when listed
  std::vector<std::array<int, 2>> source; // (root, element) each capsule was read from (the plate's)
  bool empty() const { return pairs.empty(); }
  void clear() { pairs.clear(); }
};

// the stiffness of one contact between this root's element i and capsule c of its neighbours: K = -dF/dx,
// rows the forces on nodes i, i + 1, columns the coordinates of nodes i, i + 1 and of the capsule's ends a,
// b (the other root's nodes) [N/m]
struct NeighbourStiffness {
  int i = 0, c = 0;
  Eigen::Matrix<double, 6, 12> K;
};

// scratch memory of the contact pieces, sized once per element count (resize) so that a force
// evaluation allocates nothing
struct ContactWorkspace {
  // filled by addObstacleContact, read by addFriction (elastic part of the contact force only)
  Eigen::VectorXd obstacleN;        // obstacle normal force per node [N]                (n+1)
  Eigen::Matrix3Xd obstacleNormal;  // sum of the obstacle contact normals per node, lab (3 x n+1)

  // self-contact broad phase: a Verlet list of element pairs that are within 2R + skin (and far enough
  // apart along the rod), found by sorting element midpoints along one axis; rebuilt when a node has moved
  // more than skin/2 since the list was built, or when the element count or the rod's rest length
  // changed (growth)
  std::vector<std::array<int, 2>> pairs;  // candidate element pairs (i < j), sorted
  std::vector<int> order;                 // scratch of a build: elements sorted along the sweep axis (n)
  Eigen::VectorXd key;                    // scratch of a build: midpoint coordinate on that axis (n)
  Eigen::Matrix3Xd xBuilt;                // node positions when the list was built (3 x n+1)
  Eigen::Matrix3Xd mid;                   // scratch of a build: element midpoints (3 x n)
  Eigen::VectorXd halfLength;             // scratch of a build: element half-lengths (n)
  int builtElements = -1;                 // element count when the list was built (-1: never)
  double builtRestLength = -1.0;          // rest length when the list was built [m]
  long builds = 0;                        // how often the list was built (for tests and benchmarks)
  std::vector<std::uint8_t> contactNode;  // markSelfContactNodes: 1 for nodes of pairs in contact (n+1)
  std::vector<std::uint8_t> elementFlag;  // scratch of countContacts (n)
  std::vector<PairStiffness> stiffness;   // selfContactStiffness: one per pair in contact (grows once)
  std::vector<NeighbourStiffness> neighbourStiffness;  // neighbourContactStiffness: one per pair in contact
  NeighbourCapsules neighbours;           // other roots on a plate (not scratch: the plate's input, kept
                                          // by resize; not in fields(): a plate lists them anew from the
                                          // roots' states before every relaxation and when restored)

  void resize(int n);
  void invalidate() { builtElements = -1; }
  // what the next relaxation depends on (the Verlet list), in the checkpoint's order (fields.hpp)
  static constexpr auto fields() {
    using W = ContactWorkspace;
    return std::tuple{field("pairs", &W::pairs), field("xBuilt", &W::xBuilt), field("builtElements", &W::builtElements),
                      field("builtRestLength", &W::builtRestLength), field("builds", &W::builds)};
  }
};

// obstacles: each element against each obstacle (a 2-D segment-segment distance in the plate: the
// obstacles are infinitely tall); fills cw.obstacleN / cw.obstacleNormal for friction
void addObstacleContact(const RodParams& p, const Environment& env, const RodState& s, bool damping,
                        ContactWorkspace& cw, Eigen::Matrix3Xd& force);

// self-contact: element pairs whose rest arc-length separation is at least kSelfExclusionRadii * R,
// closer than 2R between the closest points of their centrelines
void addSelfContact(const RodParams& p, const Environment& env, const RodState& s, bool damping,
                    ContactWorkspace& cw, Eigen::Matrix3Xd& force);
inline constexpr double kSelfExclusionRadii = 3.0;

// contact with other roots (cw.neighbours): the self-contact law between this root's elements and each
// listed capsule, closer than R + r between the contact points; the force on this root only (the other
// root feels the opposite force when it relaxes)
void addNeighbourContact(const RodParams& p, const Environment& env, const RodState& s, bool damping,
                         ContactWorkspace& cw, Eigen::Matrix3Xd& force);
// the elastic force of capsule c of nb on this root's element x0-x1 (capsule ends b0, b1: where they are
// now, or nudged by a Newton solver's differences) and the weight w1 of its second node (the first gets
// 1 - w1); computed in the pair's first root's order (nb.first), so the two roots feel exactly opposite
// forces. False when they do not touch.
// (up: env.plane.normal(), the blend's plane normal)
bool neighbourPairForce(const RodParams& p, const Environment& env, const Vec3& up, const NeighbourCapsules& nb, int c,
                        const Vec3& x0, const Vec3& x1, const Vec3& b0, const Vec3& b1, Vec3& F, double& w1);

// the contact of one element (a0-a1, radius ra) of root A with one capsule (b0-b1, radius rb) of root
// B, A before B on the plate: the force on A's segment and the weights of its two nodes (B feels -F
// at weights 1 - sb, sb); false when they do not touch
struct RootPairForce {
  Vec3 F = Vec3::Zero();
  double sa = 0, sb = 0;
};
bool rootPairForce(double ra, double rb, double k, const Vec3& up, const Vec3& a0, const Vec3& a1, const Vec3& b0,
                   const Vec3& b1, RootPairForce& out);

// Coulomb friction on the plate and on obstacles from the committed stick points (needs the obstacle
// normal forces of addObstacleContact in cw); adhered nodes are excluded
void addFriction(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw,
                 Eigen::Matrix3Xd& force);

// what one commit did: nodes that slipped and the work done by friction against the slip [J]
struct FrictionCommit {
  int slips = 0;
  double work = 0.0;
};
// after an equilibrium (or before the first relaxation): nodes in contact get a stick point where they
// are (new contacts) or move it by the return mapping (slip); nodes off contact or adhered lose it
FrictionCommit commitFriction(const RodParams& p, const Environment& env, RodState& s,
                              ContactWorkspace& cw);

// closest points of segments a0-a1 and b0-b1: parameters sa, sb in [0, 1] (Ericson, Real-Time
// Collision Detection, 5.1.9; near-parallel segments take the middle of their overlap)
void closestSegmentPoints(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double& sa,
                          double& sb);

// where contact forces act between two segments (self-contact, obstacle walls): the closest points,
// except for nearly parallel segments (sin^2 of their angle below kParallelSin2), whose closest points
// jump from one end of their overlap to the other as they pass through parallel. There the point on a
// blends smoothly (smoothstep in sin^2) into the middle of a's part facing b, and the point on b is its
// projection. The force then acts along the line between the two points (no net moment) and is a
// continuous function of the nodes, so that a static equilibrium exists where turns of a coil lie side
// by side (with the closest points the residual jumps there and neither solver settles; the plain
// penalty law names the closest points, this is the deviation: docs/model.md, Deviations). The distance
// between the points is at least the closest distance.
void contactSegmentPoints(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double& sa,
                          double& sb);
inline constexpr double kParallelSin2 = 0.030153689607045803;  // sin^2(10 degrees)

}  // namespace rootsim
