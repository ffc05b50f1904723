// rotations (src/sim/rotation.cpp): the exponential map and its inverse, rotating directors in place
#include <doctest/doctest.h>

#include <Eigen/Geometry>

#include "rootsim/rotation.hpp"

using namespace rootsim;

TEST_CASE("rotation exp/log round trip at small, moderate and near-pi angles") {
  for (double t : {1e-9, 3e-5, 1e-3, 0.04, 0.3, 1.0, 2.5, 3.14159}) {
    const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
    const Eigen::Vector3d phi = t * axis;
    const Eigen::Matrix3d R = rotationFromVector(phi);
    const Eigen::Matrix3d Ref = Eigen::AngleAxisd(t, axis).toRotationMatrix();
    CHECK((R - Ref).norm() < 1e-14);
    CHECK((rotationToVector(R) - phi).norm() < 1e-12 * std::max(1.0, t));
  }
}

TEST_CASE("rotateInPlace equals exp([phi]x) Q") {
  Eigen::Matrix3d Q = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  for (double t : {1e-7, 5e-3, 0.2, 2.0}) {
    const Eigen::Vector3d phi = t * Eigen::Vector3d(-0.3, 0.9, 0.2).normalized();
    Eigen::Matrix3d A = Q;
    rotateInPlace(phi, A);
    CHECK((A - rotationFromVector(phi) * Q).norm() < 1e-15);
  }
}
