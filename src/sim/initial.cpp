#include "rootsim/initial.hpp"

#include <cmath>
#include <numbers>

namespace rootsim {

double splitmixUniform(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;
}

double splitmixNormal(std::uint64_t& state) {
  const double u1 = 0.5 * (1.0 - splitmixUniform(state));  // (0, 1]
  const double u2 = 0.5 * (splitmixUniform(state) + 1.0);  // [0, 1)
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

RodState makeInitialRod(const RodParams& p, const Plane& plane, const InitialShape& shape) {
  const int n = std::max(2, static_cast<int>(std::ceil(shape.length / shape.elementLength - 1e-9)));
  const double l = shape.length / n;
  const Vec3 nh = plane.normal();
  Vec3 down = plane.downhill(), lat = plane.lateral();
  if (shape.angle != 0.0) {
    // a seedling sown at an angle: the same straight rod turned about the plate's normal
    const double c = std::cos(shape.angle), sn = std::sin(shape.angle);
    const Vec3 d3 = c * down + sn * lat;
    lat = nh.cross(d3);
    down = d3;
  }
  RodState s;
  s.resize(n);
  std::uint64_t rng = shape.seed;
  for (int i = 0; i <= n; ++i) {
    s.x.col(i) = p.radius * nh + (i * l) * down;
    if (i >= 2) s.x.col(i) += shape.perturbation * p.radius * splitmixUniform(rng) * lat;
    s.S[i] = i * l;
  }
  Mat3 Q;
  Q.row(0) = lat.transpose();
  Q.row(1) = nh.transpose();
  Q.row(2) = down.transpose();
  for (int i = 0; i < n; ++i) s.Q[static_cast<size_t>(i)] = Q;
  s.clampFrame = Q;
  s.v.setZero();
  s.w.setZero();
  s.l0.setConstant(l);
  s.kappa0.setZero();
  s.anchor = s.x;
  s.time = shape.startTime;
  return s;
}

}  // namespace rootsim
