// observables (src/sim/analysis.cpp): writhe, twist, linking number
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "rootsim/analysis.hpp"

using namespace rootsim;

namespace {
constexpr double pi = std::numbers::pi;
}

TEST_CASE("a planar curve has zero writhe") {
  Eigen::Matrix3Xd p(3, 60);
  for (int i = 0; i < 60; ++i) p.col(i) = Vec3(std::cos(0.2 * i) * (1 + 0.01 * i), std::sin(0.2 * i), 0.0);
  CHECK(std::abs(writheOpen(p, 0, 59)) < 1e-12);
  CHECK(std::abs(writheClosed(p)) < 1e-12);
}

TEST_CASE("Calugareanu: Lk = Tw + Wr for a closed ribbon on a trefoil-like curve") {
  // closed curve: a (2,3) torus knot; ribbon: the Frenet-free frame u = normalised (p - axis point)
  // rotated by k full turns; Lk from the Gauss linking integral of the centreline and the ribbon edge
  const int N = 600;
  Eigen::Matrix3Xd c(3, N), e(3, N);
  std::vector<Vec3> u(N), t(N);
  auto curve = [](double s) {
    const double r = 2 + std::cos(3 * s);
    return Vec3(r * std::cos(2 * s), r * std::sin(2 * s), std::sin(3 * s));
  };
  for (int i = 0; i < N; ++i) c.col(i) = curve(2 * pi * i / N);
  for (int i = 0; i < N; ++i) t[i] = (c.col((i + 1) % N) - c.col((i + N - 1) % N)).normalized();
  const int k = 2;
  for (int i = 0; i < N; ++i) {
    const double s = 2 * pi * i / N;
    Vec3 radial = Vec3(c(0, i), c(1, i), 0).normalized();
    Vec3 a = (radial - radial.dot(t[i]) * t[i]).normalized();
    Vec3 b = t[i].cross(a);
    u[i] = std::cos(k * s) * a + std::sin(k * s) * b;
    e.col(i) = c.col(i) + 0.01 * u[i];
  }
  // twist: (1/2pi) sum of the rotation of u about t between neighbours
  double tw = 0;
  for (int i = 0; i < N; ++i) {
    const int j = (i + 1) % N;
    // parallel-transport u_i to j's normal plane, then the signed angle to u_j about t_j
    Vec3 ui = u[i] - u[i].dot(t[j]) * t[j];
    ui.normalize();
    tw += std::atan2(ui.cross(u[j]).dot(t[j]), ui.dot(u[j]));
  }
  tw /= 2 * pi;
  const double wr = writheClosed(c);
  const double lk = linkingNumber(c, e);
  INFO("Tw " << tw << " Wr " << wr << " Lk " << lk);
  CHECK(std::abs(lk - std::round(lk)) < 1e-6);
  CHECK(std::abs(tw + wr - lk) < 0.01);
  CHECK(std::abs(wr) > 0.5);  // a knotted curve writhes
}

TEST_CASE("a helix writhes, and its mirror image writhes the opposite way") {
  Eigen::Matrix3Xd p(3, 200);
  for (int i = 0; i < 200; ++i) {
    const double s = 0.1 * i;
    p.col(i) = Vec3(std::cos(s), std::sin(s), 0.3 * s);  // right-handed
  }
  const double wr = writheOpen(p, 0, 199);
  CHECK(std::abs(wr) > 0.1);
  Eigen::Matrix3Xd q = p;
  q.row(2) *= -1.0;  // mirror: left-handed
  CHECK(writheOpen(q, 0, 199) == doctest::Approx(-wr).epsilon(1e-12));
}
