#pragma once
// Everything that acts on the rod from outside: the tilted plane, adhesion springs, the clamped base,
// tip loads (MODEL.md sections 3 and 6).
#include "rootsim/rod.hpp"

namespace rootsim {

// the tilted plate (MODEL.md section 3): through the origin, unit normal n = (0, -cos a, sin a)
struct Plane {
  bool enabled = true;
  double alpha = 0.0;          // tilt from the vertical [rad]
  double k = 1000.0;           // normal penalty spring, per element [N/m] (paper: 100; scene_schema.cpp)
  double c = 0.01;             // normal damping, per element [kg/s]
  Vec3 normal() const;         // unit normal, pointing to the side the root lies on
  Vec3 downhill() const;       // in-plane downhill unit vector (0, -sin a, -cos a)
  Vec3 lateral() const { return Vec3::UnitX(); }
};

enum class BaseCondition { Clamped, Free };

struct Environment {
  Plane plane;
  bool adhesion = true;        // pin material leaving the growth zone
  double kAdhesion = 1000.0;   // adhesion spring [N/m]
  // clamped: node 0 is held and element 0 is tied to the fixed frame baseFrame at s = 0 by a boundary
  // Voronoi domain of rest length l0/2 (see addExternalForces)
  BaseCondition base = BaseCondition::Clamped;
  Mat3 baseFrame = Mat3::Identity();  // clamp frame, rows d1 d2 d3 (lab); set from the initial rod
  Vec3 tipForce = Vec3::Zero();    // dead load on the last node, lab [N]
  Vec3 tipTorque = Vec3::Zero();   // couple on the last element, lab [N m]
  Vec3 gravity = Vec3::Zero();     // body acceleration, lab [m/s^2] (off by default: weight is negligible)
};

// adds contact, adhesion, tip loads and body forces to force (lab, 3 x n+1) and torque (material, 3 x n);
// dampedVelocity selects whether the plane's normal damping acts (only meaningful with physical masses)
void addExternalForces(const RodParams& p, const Environment& env, const RodState& s,
                       const RodStrains& k, bool planeDamping, Eigen::Matrix3Xd& force,
                       Eigen::Matrix3Xd& torque);

// couple of the clamp on element 0 (material frame) and the clamp curvature [1/m]: the clamp is a
// boundary Voronoi domain of rest length l0[0]/2 between baseFrame and element 0
struct ClampCouple { Vec3 kappa, m, torque; };
ClampCouple clampCouple(const RodParams& p, const Environment& env, const RodState& s, double e0);

}  // namespace rootsim
