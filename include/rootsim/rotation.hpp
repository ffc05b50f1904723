#pragma once
// rotation helpers: exponential and logarithm maps of SO(3)
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rootsim {

// rotation matrix exp([phi]x) (Rodrigues); exact to round-off at every angle
Eigen::Matrix3d rotationFromVector(const Eigen::Vector3d& phi);

// Q <- exp([phi]x) Q without forming the rotation matrix: each column q of Q becomes
// q + a (phi x q) + b phi x (phi x q) (Rodrigues); the hot path of the relaxation's drift
void rotateInPlace(const Eigen::Vector3d& phi, Eigen::Matrix3d& Q);

// rotation vector phi with exp([phi]x) = R, |phi| <= pi
Eigen::Vector3d rotationToVector(const Eigen::Matrix3d& R);

}  // namespace rootsim
