// The initial state (src/sim/initial.cpp): a straight rod lying on the plate, pointing downhill (or at the
// sown angle), its element count and lengths, the seeded lateral perturbation and its splitmix64 stream.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "physics_support.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;

TEST_CASE("initial rod: n = ceil(L0 / h) equal elements from R n along downhill, frames d1 = lateral, d2 = n, d3 = downhill") {
  RodParams p;
  Plane plane;
  plane.alpha = 40.0 * units::deg;
  InitialShape sh;
  sh.length = 1.1e-3;
  sh.elementLength = 0.3e-3;  // 1.1 / 0.3 = 3.67: four elements of 0.275 mm
  sh.perturbation = 0.0;
  const RodState s = makeInitialRod(p, plane, sh);
  REQUIRE(s.elements() == 4);
  REQUIRE(s.nodes() == 5);
  const Vec3 n = plane.normal(), down = plane.downhill(), lat = plane.lateral();
  for (int i = 0; i <= 4; ++i) {
    const Vec3 want = p.radius * n + (i * 0.275e-3) * down;
    ROOTSIM_CHECK_REL("node on the line", (s.x.col(i) - want).norm(), 0.0, 1e-15);
    ROOTSIM_CHECK_REL("material coordinate", s.S[i], i * 0.275e-3, 1e-14);
  }
  for (int i = 0; i < 4; ++i) {
    ROOTSIM_CHECK_REL("rest length", s.l0[i], 0.275e-3, 1e-14);
    const Mat3& Q = s.Q[static_cast<size_t>(i)];
    CHECK((Q.row(0).transpose() - lat).norm() < 1e-15);
    CHECK((Q.row(1).transpose() - n).norm() < 1e-15);
    CHECK((Q.row(2).transpose() - down).norm() < 1e-15);
  }
  CHECK((s.clampFrame - s.Q[0]).norm() == 0.0);
  CHECK(s.kappa0.norm() == 0.0);
  CHECK(s.v.norm() == 0.0);
  CHECK((s.anchor - s.x).norm() == 0.0);

  // a length that is a whole number of elements is not rounded up by its rounding error; never fewer than 2
  sh.length = 1.0e-3;
  sh.elementLength = 0.1e-3;
  CHECK(makeInitialRod(p, plane, sh).elements() == 10);
  sh.elementLength = 5e-3;
  CHECK(makeInitialRod(p, plane, sh).elements() == 2);
}

TEST_CASE("initial rod: a seedling sown at an angle points cos a downhill + sin a lateral, its frame turned about the normal") {
  RodParams p;
  Plane plane;
  InitialShape sh;
  sh.perturbation = 0.0;
  sh.angle = 30.0 * units::deg;
  sh.startTime = 7200.0;
  const RodState s = makeInitialRod(p, plane, sh);
  const Vec3 d3 = std::cos(sh.angle) * plane.downhill() + std::sin(sh.angle) * plane.lateral();
  const Vec3 tangent = (s.x.col(s.nodes() - 1) - s.x.col(0)).normalized();
  CHECK((tangent - d3).norm() < 1e-14);
  const Mat3& Q = s.Q[0];
  CHECK((Q.row(2).transpose() - d3).norm() < 1e-15);
  CHECK((Q.row(1).transpose() - plane.normal()).norm() < 1e-15);
  CHECK((Q.row(0).transpose() - plane.normal().cross(d3)).norm() < 1e-15);
  CHECK(std::abs(Q.determinant() - 1.0) < 1e-14);
  CHECK(s.time == 7200.0);
}

TEST_CASE("initial rod: the perturbation moves nodes 2.. laterally by at most its amplitude times R, the same for the same seed") {
  RodParams p;
  Plane plane;
  InitialShape sh;
  sh.perturbation = 0.01;
  sh.seed = 42;
  const RodState a = makeInitialRod(p, plane, sh), b = makeInitialRod(p, plane, sh);
  sh.perturbation = 0.0;
  const RodState flat = makeInitialRod(p, plane, sh);
  CHECK((a.x - b.x).norm() == 0.0);
  double largest = 0.0;
  for (int i = 0; i < a.nodes(); ++i) {
    const Vec3 d = a.x.col(i) - flat.x.col(i);
    CHECK(std::abs(d.dot(plane.downhill())) < 1e-18);
    CHECK(std::abs(d.dot(plane.normal())) < 1e-18);
    const double off = std::abs(d.dot(plane.lateral()));
    if (i < 2) CHECK(off == 0.0);
    CHECK(off <= 0.01 * p.radius);
    largest = std::max(largest, off);
  }
  CHECK(largest > 0.0);
  // node i >= 2 takes the (i - 1)-th number of the seed's stream
  std::uint64_t rng = 42;
  for (int i = 2; i < a.nodes(); ++i) {
    const double u = splitmixUniform(rng);
    CHECK(std::abs((a.x.col(i) - flat.x.col(i)).dot(plane.lateral()) - 0.01 * p.radius * u) < 1e-18);
  }
  sh.perturbation = 0.01;
  sh.seed = 43;
  CHECK((makeInitialRod(p, plane, sh).x - a.x).norm() > 0.0);
}

TEST_CASE("splitmixUniform: the splitmix64 stream's first value, and uniform from -1 to 1 (mean and variance within 5 sigma)") {
  // splitmix64 of seed 0 is 0xe220a8397b1dcdaf (the reference sequence of Steele, Lea and Flood)
  std::uint64_t st = 0;
  CHECK(splitmixUniform(st) == static_cast<double>(0xe220a8397b1dcdafULL >> 11) * 0x1.0p-52 - 1.0);
  CHECK(st == 0x9e3779b97f4a7c15ULL);
  const int N = 200000;
  double sum = 0, sum2 = 0, lo = 1, hi = -1;
  std::uint64_t s = 12345;
  for (int k = 0; k < N; ++k) {
    const double u = splitmixUniform(s);
    sum += u;
    sum2 += u * u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  CHECK(lo >= -1.0);
  CHECK(hi < 1.0);
  // U(-1, 1): mean 0 (sd of the mean sqrt(1/3 / N)), E u^2 = 1/3 (sd of its mean sqrt(4/45 / N))
  CHECK(std::abs(sum / N) < 5.0 * std::sqrt(1.0 / 3.0 / N));
  CHECK(std::abs(sum2 / N - 1.0 / 3.0) < 5.0 * std::sqrt(4.0 / 45.0 / N));
}
