#pragma once
// rotation helpers: exponential and logarithm maps of SO(3)
#include <Eigen/Core>

namespace rootsim {

// rotation matrix exp([phi]x) (Rodrigues); exact to round-off at every angle
Eigen::Matrix3d rotationFromVector(const Eigen::Vector3d& phi);

// rotation vector phi with exp([phi]x) = R, |phi| <= pi
Eigen::Vector3d rotationToVector(const Eigen::Matrix3d& R);

}  // namespace rootsim
