#pragma once
// Everything that acts on the rod from outside: the tilted plane, adhesion springs, the clamped base,
// tip loads (docs/model.md, Frames and signs, and Environment).
#include <vector>

#include "rootsim/rod.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

// The frame of a plate tilted by alpha from the vertical (docs/model.md, Frames and signs): the one place it
// is computed; the physics, the renderer and the figure panels all use it. Plate coordinates are taken
// from the origin, which is where the base node's foot lies (the base node sits at R n).
struct PlateFrame {
  Vec3 normal = Vec3(0, -1, 0);    // unit normal (0, -cos a, sin a), pointing to the side the root lies on
  Vec3 downhill = Vec3(0, 0, -1);  // in-plane downhill unit vector g_par = (0, -sin a, -cos a)
  Vec3 lateral = Vec3(1, 0, 0);    // in-plane lateral unit vector x

  // exact at multiples of 90 degrees: cos(pi/2) = 6e-17 would seed out-of-plane modes on a horizontal plate
  static PlateFrame tilted(double alpha);  // alpha [rad]
  Vec3 uphill() const { return -downhill; }
  // plate coordinates of a lab point: (lateral, downhill, height above the plate), same unit as lab
  Vec3 coords(const Vec3& lab) const { return Vec3(lateral.dot(lab), downhill.dot(lab), normal.dot(lab)); }
  // the top view's coordinates [mm] of a lab point [m]: (lateral, uphill, height); uphill is up the image
  Vec3 toPlateMm(const Vec3& labM) const;
  // components of a lab direction along (lateral, uphill, normal)
  Vec3 dirToPlate(const Vec3& dir) const { return Vec3(lateral.dot(dir), -downhill.dot(dir), normal.dot(dir)); }
};

// the tilted plate as a contact surface: through the origin, normal PlateFrame::normal
struct Plane {
  bool enabled = true;
  double alpha = 40.0 * units::deg;  // tilt from the vertical [rad]
  // normal penalty spring, per element [N/m]. The paper: 100 N/m. Measured here (fig2b scene,
  // 700 steps): with 100 N/m the tip, pressed into the plate by gravitropism, sinks 0.17-0.34 R into it;
  // 1000 N/m keeps it below 0.03 R with the same waves (lambda 2.34 vs 2.35 mm) and the same cost.
  double k = 1000.0;
  double c = 0.01;             // normal damping, per element [kg/s]
  PlateFrame frame() const { return PlateFrame::tilted(alpha); }
  Vec3 normal() const { return frame().normal; }
  Vec3 downhill() const { return frame().downhill; }
  Vec3 lateral() const { return frame().lateral; }
};

enum class BaseCondition { Clamped, Free };

// contact of the rod with itself (docs/model.md, Contact and friction): capsules of the rest radius R,
// penalty along the line between the closest points of two elements that are not neighbours along the rod
struct SelfContact {
  bool enabled = true;
  // penalty spring per element pair [N/m]; damping is the plate's c (the plate's law:
  // docs/model.md, Contact and friction).
  // Measured (fig2a alpha = 90, 0.1 mm elements, 900 steps): with 1000 N/m the coil's turns squeeze to
  // 1.75 R apart, with 1e4 N/m they stay 1.96 R apart; but 1e4 N/m jammed the explicit relaxation of the
  // quick figure's alpha = 90 root (residual at the tip, 2e6 sub-steps; 1000 and 3000 N/m pass), so the
  // default stays the plate's.
  double k = 1000.0;
};

// Coulomb friction on the plate and on obstacles (docs/model.md, Contact and friction): incremental stick
// points, return mapping on slip, mu along the rod's in-plane axis = axialRatio * mu across it
struct Friction {
  bool enabled = false;
  double muStatic = 0.0;       // static coefficient across the rod's axis
  double muKinetic = 0.0;      // kinetic coefficient across the rod's axis (<= muStatic)
  double axialRatio = 1.0;     // mu along the rod's in-plane axis / mu across it
  // slip over which the sliding coefficient falls from mu_s to mu_k [m] (slip weakening, contact.cpp;
  // 0: at once). 1e-3 R: far below any slip that matters, far above a solver's overshoot
  double slipWeakening = 1e-7;
};

// a rigid obstacle on the plate, infinitely tall along the plate normal (docs/model.md, Contact and
// friction): the set of plate points within `radius` of the segment from-to. A peg has from == to (a
// cylinder); a wall is a segment with rounded ends of radius thickness/2. Plate coordinates (lateral,
// downhill) are taken from the foot of the base node (PlateFrame's origin).
struct Obstacle {
  enum class Shape { Peg, Wall };
  Shape shape = Shape::Peg;
  Eigen::Vector2d from = Eigen::Vector2d::Zero();  // (lateral, downhill) [m]; a peg's centre
  Eigen::Vector2d to = Eigen::Vector2d::Zero();    // (lateral, downhill) [m]; == from for a peg
  double radius = 0.0;                             // peg radius, or half the wall thickness [m]
};

struct Environment {
  Plane plane;
  bool adhesion = true;        // pin material leaving the growth zone
  double kAdhesion = 1000.0;   // adhesion spring [N/m]
  // clamped: node 0 is held and element 0 is tied to the state's clampFrame at s = 0 by a boundary
  // Voronoi domain of rest length l0/2 (clampCouple)
  BaseCondition base = BaseCondition::Clamped;
  Vec3 tipForce = Vec3::Zero();    // dead load on the last node, lab [N]
  Vec3 tipTorque = Vec3::Zero();   // couple on the last element, lab [N m]
  Vec3 gravity = Vec3::Zero();     // body acceleration, lab [m/s^2] (off by default: weight is negligible)
  SelfContact selfContact;         // on by default (coils climb over themselves)
  Friction friction;               // off by default (the paper's frictionless plate)
  std::vector<Obstacle> obstacles; // none by default
};

struct ContactWorkspace;  // contact.hpp

// The outside forces, one piece each (docs/model.md, Environment). Forces are lab components on nodes
// (3 x n+1), torques material components on elements (3 x n); each piece adds to what is there, for
// the elements (nodes) from `first` on and before `end` (end < 0: to the tip), for a solver that moves
// only those.

// plate contact, per element: one-sided penalty on the surface gap, plus normal damping (damping: only
// meaningful with physical masses)
void addPlaneContact(const RodParams& p, const Plane& plane, const RodState& s, bool damping,
                     Eigen::Matrix3Xd& force, int first = 0, int end = -1);
// adhesion springs of stiffness k [N/m] pin anchored nodes; directors stay free
void addAdhesion(double k, const RodState& s, Eigen::Matrix3Xd& force, int first = 0, int end = -1);
// weight, lumped to nodes; gravity [m/s^2]
void addWeight(const RodParams& p, const Vec3& gravity, const RodState& s, Eigen::Matrix3Xd& force,
               int first = 0, int end = -1);
// dead force on the last node, lab-fixed couple on the last element
void addTipLoads(const Environment& env, const RodState& s, Eigen::Matrix3Xd& force, Eigen::Matrix3Xd& torque);

// which outside forces to add: all, or all but the contact of element pairs (self-contact and the
// contact with other roots on a plate: the Newton solver's coloured Jacobian passes, which take their
// stiffness pair by pair: relax_newton.cpp)
enum class ForcePieces { All, NoPairContact };

// the part of the rod a force evaluation covers, for a solver that moves only part of it: strains and
// internal forces of the elements [first, end) (end < 0: to the tip), the node-wise outside forces
// (plate, adhesion, weight) from element `outsideFrom` (>= first) on: the Newton solver's frozen nodes
// before its window need their elements' couples but none of their forces. The contact pieces act on
// the whole rod. Near the span's ends forces and couples are inexact (computeInternalForces); callers
// read only those inside.
struct ForceSpan {
  int first = 0, end = -1, outsideFrom = 0;
};

// all of the above that env switches on, the contact pieces of contact.hpp (obstacles, self-contact,
// friction; cw is their scratch memory, sized by ContactWorkspace::resize) and the clamp's couple on
// element 0, in this order
void addExternalForces(const RodParams& p, const Environment& env, const RodState& s,
                       const RodStrains& k, bool planeDamping, ContactWorkspace& cw,
                       Eigen::Matrix3Xd& force, Eigen::Matrix3Xd& torque, ForceSpan span = {},
                       ForcePieces pieces = ForcePieces::All);

// normal force of the plate on each node (n+1) [N]: addPlaneContact without its
// damping, each element's force shared by its two nodes; zeros without a plate
Eigen::VectorXd plateNormalForce(const RodParams& p, const Plane& plane, const RodState& s);

// couple of the clamp on element 0 (material frame) and the clamp curvature [1/m]: the clamp is a
// boundary Voronoi domain of rest length l0[0]/2 between the state's clampFrame and element 0
struct ClampCouple { Vec3 kappa, m, torque; };
ClampCouple clampCouple(const RodParams& p, const RodState& s, double e0);

// the clamp's kinematic half, the one place it is enforced: node 0 does not move, so the force on it is
// a reaction and is removed (a solver then never moves it: its velocity stays zero)
void holdClampedBase(const Environment& env, Eigen::Matrix3Xd& force);

}  // namespace rootsim
