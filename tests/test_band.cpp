// banded and sparse linear algebra of the Newton solver (src/sim/band.cpp; SparseStiffness, the KLU path,
// moves to src/sim/sparse_stiffness.cpp): band LU and LDL^T and the sparse LU and LDL^T against dense
// Eigen solves, on deterministic and on random banded matrices at the sizes the solver uses
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "rootsim/band.hpp"
#include "rootsim/sparse_stiffness.hpp"

using namespace rootsim;

namespace {
// a deterministic band matrix with a dominant but not overwhelming diagonal of both signs
Eigen::MatrixXd bandMatrix(int n, int kl, int ku, bool symmetric) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - kl); j <= std::min(n - 1, i + ku); ++j)
      A(i, j) = std::sin(1.0 + 3.7 * i + 1.3 * j * j) + (i == j ? (i % 3 == 0 ? -2.0 : 3.0) : 0.0);
  if (symmetric) A = (0.5 * (A + A.transpose())).eval();
  return A;
}
}  // namespace

TEST_CASE("band LU with partial pivoting solves what a dense LU solves") {
  for (int n : {1, 5, 40, 200}) {
    const int kl = 14, ku = 14;
    const Eigen::MatrixXd A = bandMatrix(n, kl, ku, false);
    BandLU lu;
    lu.reset(n, kl, ku);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (A(i, j) != 0.0) lu.add(i, j, A(i, j));
    REQUIRE(lu.factorize());
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = std::cos(0.3 * i);
    Eigen::VectorXd x = b;
    lu.solve(x.data());
    const Eigen::VectorXd ref = A.partialPivLu().solve(b);
    INFO("n " << n);
    CHECK((x - ref).norm() <= 1e-10 * ref.norm());
    CHECK((A * x - b).norm() <= 1e-10 * b.norm());
  }
}

TEST_CASE("band LU: diagonal blocks copied into a larger band are that block-diagonal matrix, factors included") {
  // two band matrices side by side (a plate's coupled system), each copied within half-bandwidth k: the
  // same entries as add() one by one, and the factors solve the block-diagonal system
  const int k = 3, n0 = 7, n1 = 12, n = n0 + n1;
  const Eigen::MatrixXd B0 = bandMatrix(n0, k, k, false), B1 = bandMatrix(n1, k, k, false);
  auto bandOf = [&](const Eigen::MatrixXd& m) {
    BandLU b;
    b.reset(static_cast<int>(m.rows()), k + 2, k + 2);  // a wider band than copied: its outer diagonals stay zero
    for (int i = 0; i < m.rows(); ++i)
      for (int j = 0; j < m.cols(); ++j)
        if (m(i, j) != 0.0) b.add(i, j, m(i, j));
    return b;
  };
  const BandLU b0 = bandOf(B0), b1 = bandOf(B1);
  BandLU whole, byEntry;
  whole.reset(n, k + 1, k + 1);
  byEntry.reset(n, k + 1, k + 1);
  whole.addDiagonalBlock(0, b0, k);
  whole.addDiagonalBlock(n0, b1, k);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  A.topLeftCorner(n0, n0) = B0;
  A.bottomRightCorner(n1, n1) = B1;
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - k - 1); i <= std::min(n - 1, j + k + 1); ++i) {
      if (A(i, j) != 0.0) byEntry.add(i, j, A(i, j));
      CHECK(whole.at(i, j) == A(i, j));
    }
  REQUIRE(whole.factorize());
  REQUIRE(byEntry.factorize());
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::cos(0.3 * i);
  Eigen::VectorXd x = b, y = b;
  whole.solve(x.data());
  byEntry.solve(y.data());
  CHECK((x - y).cwiseAbs().maxCoeff() == 0.0);  // the same structure: the same factors, bit for bit
  CHECK((A * x - b).norm() <= 1e-10 * b.norm());
}

TEST_CASE("band LDL^T counts the negative eigenvalues of a symmetric indefinite band matrix") {
  const int n = 60, k = 14;
  const Eigen::MatrixXd A = bandMatrix(n, k, k, true);
  BandLDLT f;
  f.reset(n, k);
  for (int j = 0; j < n; ++j)
    for (int i = j; i <= std::min(n - 1, j + k); ++i) f.addLower(i, j, A(i, j));
  REQUIRE(f.factorize());
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues();
  int neg = 0;
  for (int i = 0; i < n; ++i) neg += ev[i] < 0;
  CHECK(neg > 0);
  CHECK(f.negativePivots(1e-12) == neg);
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0), x = b;
  f.solve(x.data());
  CHECK((A * x - b).norm() <= 1e-9 * b.norm());
}

TEST_CASE("sparse LU (KLU): band plus off-band entries solved as a dense LU does, and a restored memory refactorises to the same bits") {
  const int n = 120, k = 11;
  // a band matrix plus far couplings, as self-contact makes them, in two versions (two Newton iterations)
  auto matrix = [&](double shift, BandLU& band, std::vector<OffBandEntry>& extra, Eigen::MatrixXd& dense) {
    dense = bandMatrix(n, k, k, false);
    dense.diagonal().array() += shift;
    band.reset(n, k, k);
    for (int j = 0; j < n; ++j)
      for (int i = std::max(0, j - k); i <= std::min(n - 1, j + k); ++i) band.add(i, j, dense(i, j));
    extra.clear();
    for (int a = 0; a < 6; ++a) {
      const int i = 3 + 7 * a, j = i + 30 + 9 * a;  // j <= 113 < n
      const double v = 0.3 * std::cos(a + shift);
      for (const auto& [r, c] : {std::pair{i, j}, std::pair{j, i}}) {
        extra.push_back({r, c, v});
        dense(r, c) += v;
      }
    }
  };
  BandLU band;
  std::vector<OffBandEntry> extra;
  Eigen::MatrixXd A;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::cos(0.3 * i);
  SparseStiffness one;
  one.beginRelaxation(n);
  matrix(0.0, band, extra, A);
  one.assemble(band, extra);
  REQUIRE(one.factorizeLU());
  Eigen::VectorXd x = b;
  one.solveLU(x.data());
  CHECK((A * x - b).norm() <= 1e-10 * b.norm());
  // a checkpoint here; the next iteration's matrix refactorised with the first one's pivots, by the
  // original and by a copy restored from the memory
  const SparseMemory mem = one.memory();
  CHECK(mem.n == n);
  CHECK(!mem.pivotValues.empty());
  SparseStiffness two;
  REQUIRE(two.restore(mem));
  matrix(0.1, band, extra, A);
  Eigen::VectorXd x1 = b, x2 = b;
  for (SparseStiffness* f : {&one, &two}) {
    f->beginRelaxation(n);
    f->assemble(band, extra);
    REQUIRE(f->factorizeLU());
  }
  one.solveLU(x1.data());
  two.solveLU(x2.data());
  CHECK((A * x1 - b).norm() <= 1e-10 * b.norm());
  CHECK(x1 == x2);  // bit for bit
  CHECK(two.luAnalyses() == 1);  // the restore's analysis served the refactorisation
  // the symmetric part's inertia, as a dense eigensolver counts it
  REQUIRE(one.factorizeSymmetric());
  const Eigen::MatrixXd S = 0.5 * (A + A.transpose());
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues();
  int neg = 0;
  for (int i = 0; i < n; ++i) neg += ev[i] < 0;
  CHECK(neg > 0);
  CHECK(one.negativePivots(1e-12) == neg);
  Eigen::VectorXd y = b;
  one.solveSymmetric(y.data());
  CHECK((S * y - b).norm() <= 1e-9 * b.norm());
  // a pattern that is not structurally symmetric (one far entry without its mirror) takes the general
  // route to (A + A^T) / 2 and gives the same symmetric part
  SparseStiffness three;
  three.beginRelaxation(n);
  extra.push_back({5, 90, 0.2});
  A(5, 90) += 0.2;
  three.assemble(band, extra);
  REQUIRE(three.factorizeSymmetric());
  const Eigen::MatrixXd S3 = 0.5 * (A + A.transpose());
  Eigen::VectorXd y3 = b;
  three.solveSymmetric(y3.data());
  CHECK((S3 * y3 - b).norm() <= 1e-9 * b.norm());
}

namespace {
// a random symmetric band matrix of half-bandwidth k: entries uniform in [-1, 1], each diagonal entry 1
// above the sum of its row's magnitudes, so strictly diagonally dominant: positive definite, or with
// indefinite every 7th diagonal entry negated, with exactly that many negative eigenvalues (Gershgorin)
Eigen::MatrixXd randomSymmetricBand(int n, int k, bool indefinite, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i <= std::min(n - 1, j + k); ++i) A(i, j) = A(j, i) = u(rng);
  for (int i = 0; i < n; ++i) A(i, i) = (indefinite && i % 7 == 0 ? -1.0 : 1.0) * (A.row(i).cwiseAbs().sum() + 1.0);
  return A;
}
}  // namespace

// the Newton solver's sizes: 3 (2 n + 1) unknowns for n elements, half-bandwidth 14 (node and element
// blocks interleaved); n = 20, 100 and 400 elements
TEST_CASE("band LU and LDL^T solve a random SPD band matrix as a dense Cholesky does, at the solver's sizes") {
  std::mt19937 rng(12345);
  for (int elements : {20, 100, 400}) {
    const int n = 3 * (2 * elements + 1), k = 14;
    CAPTURE(n);
    const Eigen::MatrixXd A = randomSymmetricBand(n, k, false, rng);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
    const Eigen::LLT<Eigen::MatrixXd> llt(A);
    REQUIRE(llt.info() == Eigen::Success);
    const Eigen::VectorXd ref = llt.solve(b);
    BandLU lu;
    lu.reset(n, k, k);
    for (int j = 0; j < n; ++j)
      for (int i = std::max(0, j - k); i <= std::min(n - 1, j + k); ++i) lu.add(i, j, A(i, j));
    REQUIRE(lu.factorize());
    Eigen::VectorXd x = b;
    lu.solve(x.data());
    CHECK((x - ref).norm() <= 1e-12 * ref.norm());
    BandLDLT ldlt;
    ldlt.reset(n, k);
    for (int j = 0; j < n; ++j)
      for (int i = j; i <= std::min(n - 1, j + k); ++i) ldlt.addLower(i, j, A(i, j));
    REQUIRE(ldlt.factorize());
    CHECK(ldlt.negativePivots(1e-12) == 0);  // positive definite
    Eigen::VectorXd y = b;
    ldlt.solve(y.data());
    CHECK((y - ref).norm() <= 1e-12 * ref.norm());
  }
}

TEST_CASE("sparse stiffness (KLU and sparse LDL^T): a random band matrix with far couplings solves and counts negative eigenvalues as dense Eigen does") {
  std::mt19937 rng(777);
  for (int elements : {20, 100}) {
    const int n = 3 * (2 * elements + 1), k = 14;
    CAPTURE(n);
    for (const bool indefinite : {false, true}) {
      CAPTURE(indefinite);
      Eigen::MatrixXd A = randomSymmetricBand(n, k, indefinite, rng);
      // self-contact couples nodes far apart along the rod: symmetric entries well outside the band
      std::vector<OffBandEntry> extra;
      for (int c = 0; c < 6; ++c) {
        const int i = 3 * c + 1, j = n - 1 - 5 * c;
        const double v = 0.5 * std::uniform_real_distribution<double>(-1.0, 1.0)(rng);  // keeps the dominance
        extra.push_back({i, j, v});
        extra.push_back({j, i, v});
        A(i, j) += v;
        A(j, i) += v;
      }
      BandLU band;
      band.reset(n, k, k);
      for (int j = 0; j < n; ++j)
        for (int i = std::max(0, j - k); i <= std::min(n - 1, j + k); ++i) band.add(i, j, A(i, j));
      SparseStiffness sp;
      sp.assemble(band, extra);
      REQUIRE(sp.size() == n);
      Eigen::VectorXd b(n);
      for (int i = 0; i < n; ++i) b[i] = std::cos(0.1 * i) + 0.5;
      const Eigen::VectorXd ref = A.partialPivLu().solve(b);
      REQUIRE(sp.factorizeLU());
      Eigen::VectorXd x = b;
      sp.solveLU(x.data());
      CHECK((x - ref).norm() <= 1e-10 * ref.norm());
      CHECK((A * x - b).norm() <= 1e-10 * b.norm());
      // the symmetric factorisation: the inertia of A (Sylvester) and its solve
      const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues();
      int neg = 0;
      for (int i = 0; i < n; ++i) neg += ev[i] < 0;
      CHECK(neg == (indefinite ? (n + 6) / 7 : 0));
      REQUIRE(sp.factorizeSymmetric());
      CHECK(sp.negativePivots(1e-12) == neg);
      Eigen::VectorXd y = b;
      sp.solveSymmetric(y.data());
      CHECK((A * y - b).norm() <= 1e-9 * b.norm());
    }
  }
}
