#include "rootsim/rotation.hpp"

#include <cmath>
#include <utility>

namespace rootsim {

namespace {
// Rodrigues coefficients a = sin t / t, b = (1 - cos t) / t^2 for t^2 = t2; a series to t^8 below
// t = 1e-2 is exact to round-off and avoids sin/cos in the sub-step
std::pair<double, double> rodrigues(double t2) {
  if (t2 < 1e-4)
    return {1.0 - t2 * (1.0 / 6.0 - t2 * (1.0 / 120.0 - t2 * (1.0 / 5040.0 - t2 / 362880.0))),
            0.5 - t2 * (1.0 / 24.0 - t2 * (1.0 / 720.0 - t2 * (1.0 / 40320.0 - t2 / 3628800.0)))};
  const double t = std::sqrt(t2);
  return {std::sin(t) / t, (1.0 - std::cos(t)) / t2};
}
}  // namespace

Eigen::Matrix3d rotationFromVector(const Eigen::Vector3d& phi) {
  // Rodrigues: R = I + a [phi]x + b [phi]x^2, a = sin t / t, b = (1 - cos t) / t^2
  const auto [a, b] = rodrigues(phi.squaredNorm());
  Eigen::Matrix3d K;
  K << 0, -phi.z(), phi.y(), phi.z(), 0, -phi.x(), -phi.y(), phi.x(), 0;
  return Eigen::Matrix3d::Identity() + a * K + b * (K * K);
}

void rotateInPlace(const Eigen::Vector3d& phi, Eigen::Matrix3d& Q) {
  const auto [a, b] = rodrigues(phi.squaredNorm());
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d q = Q.col(c);
    const Eigen::Vector3d u = phi.cross(q);
    const Eigen::Vector3d w = phi.cross(u);
    Q.col(c) = q + a * u + b * w;
  }
}

Eigen::Vector3d rotationToVector(const Eigen::Matrix3d& R) {
  // antisymmetric part (R - R^T)/2 = sin t [axis]x ; trace = 1 + 2 cos t
  Eigen::Vector3d v(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  v *= 0.5;
  const double c = 0.5 * (R.trace() - 1.0);
  const double s2 = v.squaredNorm();
  if (c > 0.0 && s2 < 2.5e-3) {
    // t / sin t with t = asin(s): 1 + s^2/6 + 3 s^4/40 + 5 s^6/112 + 35 s^8/1152 (+ O(s^10) < 1e-15 here)
    const double f = 1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0 + s2 * (5.0 / 112.0 + s2 * (35.0 / 1152.0))));
    return f * v;
  }
  const double s = std::sqrt(s2);
  const double t = std::atan2(s, c);
  if (c > -0.9) return (t / s) * v;  // axis from the antisymmetric part is accurate away from pi
  // near t = pi: axis from the symmetric part (R + R^T)/2 - c I = (1 - c) a a^T
  Eigen::Matrix3d Bm = 0.5 * (R + R.transpose()) - c * Eigen::Matrix3d::Identity();
  int k = 0;
  Bm.diagonal().maxCoeff(&k);
  Eigen::Vector3d a = Bm.col(k) / std::sqrt(std::max(Bm(k, k), 1e-300));
  a.normalize();
  if (a.dot(v) < 0) a = -a;
  return t * a;
}

}  // namespace rootsim
