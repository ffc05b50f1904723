// The Newton step's sparse Jacobian (src/sim/sparse_stiffness.cpp): a band matrix with off-band entries,
// solved by KLU's LU and by the LDL^T of its symmetric part, against Eigen's dense solvers; the inertia
// of the symmetric part (negative pivots = negative eigenvalues, Sylvester); the pattern and pivots kept
// across relaxations of one size and carried by a checkpoint's memory.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "physics_support.hpp"
#include "rootsim/band.hpp"
#include "rootsim/sparse_stiffness.hpp"

using namespace rootsim;

namespace {
constexpr int kN = 30, kBand = 3;
// a band matrix (kl = ku = 3) with diag[i] on the diagonal and a fixed pattern off it (symmetric when
// asked), plus off-band entries coupling far nodes, and the same matrix dense
struct Case {
  BandLU band;
  std::vector<OffBandEntry> extra;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(kN, kN);
  Case(bool symmetric, int negatives) {
    band.reset(kN, kBand, kBand);
    for (int i = 0; i < kN; ++i)
      for (int j = std::max(0, i - kBand); j <= std::min(kN - 1, i + kBand); ++j) {
        double v = i == j ? (i < negatives ? -10.0 : 10.0) + 0.1 * i : 0.3 * std::sin(1.3 * i + 0.7 * j);
        if (symmetric && i != j) v = 0.3 * std::sin(1.3 * std::min(i, j) + 0.7 * std::max(i, j));
        band.add(i, j, v);
        dense(i, j) += v;
      }
    for (const auto& [i, j, v] : std::vector<std::tuple<int, int, double>>{{2, 25, 0.8}, {25, 2, symmetric ? 0.8 : -0.4},
                                                                           {10, 29, 0.5}, {29, 10, 0.5}}) {
      extra.push_back({i, j, v});
      dense(i, j) += v;
    }
  }
};
Eigen::VectorXd rhs() {
  Eigen::VectorXd b(kN);
  for (int i = 0; i < kN; ++i) b(i) = std::cos(0.4 * i) + 0.1 * i;
  return b;
}
}  // namespace

TEST_CASE("sparse stiffness: KLU's LU of band + off-band entries solves as the dense LU") {
  Case c(false, 0);
  SparseStiffness sp;
  sp.beginRelaxation(kN);
  sp.assemble(c.band, c.extra);
  CHECK(sp.size() == kN);
  REQUIRE(sp.factorizeLU());
  CHECK(sp.hasFactors());
  Eigen::VectorXd x = rhs();
  sp.solveLU(x.data());
  const Eigen::VectorXd want = c.dense.partialPivLu().solve(rhs());
  CHECK((x - want).norm() <= 1e-12 * want.norm());
  CHECK((c.dense * x - rhs()).norm() <= 1e-12 * rhs().norm());
}

TEST_CASE("sparse stiffness: the symmetric part's LDL^T counts the negative eigenvalues and solves as the dense solver") {
  for (const int negatives : {0, 3, 7}) {
    INFO(negatives << " negative diagonal entries");
    Case c(true, negatives);
    const Eigen::MatrixXd sym = 0.5 * (c.dense + c.dense.transpose());
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(sym).eigenvalues();
    const int want = static_cast<int>((ev.array() < 0).count());
    CHECK(want == negatives);  // the diagonal dominates: Gershgorin
    SparseStiffness sp;
    sp.beginRelaxation(kN);
    sp.assemble(c.band, c.extra);
    REQUIRE(sp.factorizeSymmetric());
    CHECK(sp.negativePivots(1e-12) == want);
    Eigen::VectorXd x = rhs();
    sp.solveSymmetric(x.data());
    CHECK((sym * x - rhs()).norm() <= 1e-12 * rhs().norm());
  }
}

TEST_CASE("sparse stiffness: one symbolic analysis serves relaxations of one size, and a restored memory factorises to the same bits") {
  Case c(false, 0);
  SparseStiffness sp;
  sp.beginRelaxation(kN);
  sp.assemble(c.band, c.extra);
  REQUIRE(sp.factorizeLU());
  const long analyses = sp.luAnalyses();
  CHECK(analyses >= 1);
  sp.beginRelaxation(kN);
  sp.assemble(c.band, c.extra);
  REQUIRE(sp.factorizeLU());
  CHECK(sp.luAnalyses() == analyses);
  Eigen::VectorXd a = rhs();
  sp.solveLU(a.data());

  SparseStiffness resumed;
  REQUIRE(resumed.restore(sp.memory()));
  resumed.beginRelaxation(kN);
  resumed.assemble(c.band, c.extra);
  REQUIRE(resumed.factorizeLU());
  Eigen::VectorXd b = rhs();
  resumed.solveLU(b.data());
  CHECK(a == b);
  // an inconsistent memory is refused
  SparseMemory bad = sp.memory();
  bad.places.push_back(kN + 5);
  SparseStiffness other;
  CHECK_FALSE(other.restore(bad));
}
