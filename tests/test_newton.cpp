// the quasi-static Newton solver (src/sim/relax_newton.cpp, src/sim/band.cpp): band algebra against
// dense, the coloured Jacobian against plain finite differences, the same equilibria as the explicit
// solver, stability from the factorisation, no allocation once warm
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "rod_fixture.hpp"
#include "rootsim/band.hpp"
#include "rootsim/rotation.hpp"
#include "rootsim/stability.hpp"

using namespace rootsim;
using rootsim::test::Cantilever;

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

TEST_CASE("the band Jacobian, in closed form and by coloured differences, equals one-dof-at-a-time central differences") {
  for (const bool closed : {true, false}) {
    CAPTURE(closed);
    Cantilever c(12);
    c.opt.closedFormStiffness = closed;
    c.env.plane.enabled = true;  // plate contact, adhesion and tip loads in play
    c.env.plane.alpha = 0.7;
    c.env.adhesion = true;
    c.s.anchored[4] = 1;
    c.env.tipForce = Vec3(2e-5, 1e-5, -3e-5);
    c.env.tipTorque = Vec3(1e-7, -2e-7, 3e-7);
    // a generic bent and twisted state with an intrinsic curvature; elements 7 and 8 turned by 0.6 rad
    // against their neighbours (the closed form's series and its exact branch)
    for (int i = 1; i < c.s.nodes(); ++i) c.s.x.col(i) += 1e-4 * Vec3(std::sin(0.7 * i), 0.3 * std::cos(i), 0.2 * i / 12.0);
    for (int i = 0; i < c.s.elements(); ++i) rotateInPlace(Vec3(0.02 * i, -0.01 * i, 0.03), c.s.Q[static_cast<size_t>(i)]);
    rotateInPlace(Vec3(0.3, -0.4, 0.3), c.s.Q[7]);
    rotateInPlace(Vec3(-0.2, 0.1, 0.5), c.s.Q[8]);
    for (int j = 0; j + 1 < c.s.elements(); ++j) c.s.kappa0.col(j) = Vec3(300.0 * std::sin(j), -200.0, 100.0 * std::cos(j));
    NewtonWorkspace nw;
    assembleStiffness(c.p, c.env, c.opt, c.s, c.ws, nw, 0);
    const Eigen::MatrixXd ref = rootsim::test::oneDofStiffness(c.p, c.env, c.s, c.ws, 1);  // clamped: node 0 is held
    const Eigen::MatrixXd K = rootsim::test::assembledStiffness(nw);
    const double worst = (K - ref).cwiseAbs().maxCoeff();
    const double scale = ref.cwiseAbs().maxCoeff();
    INFO("largest entry " << scale << ", largest difference " << worst);
    CHECK(worst <= 1e-6 * scale);
    // each kind of block on its own scale (bending entries are 1e-3 of the stretch ones): node-node,
    // node-element, element-node, element-element (unknown k is block 1 + k / 3)
    for (int rowNode = 0; rowNode < 2; ++rowNode)
      for (int colNode = 0; colNode < 2; ++colNode) {
        double kindWorst = 0, kindScale = 0;
        for (int i = 0; i < K.rows(); ++i)
          for (int j = 0; j < K.cols(); ++j)
            if (((1 + i / 3) % 2 == 0) == (rowNode == 1) && ((1 + j / 3) % 2 == 0) == (colNode == 1)) {
              kindWorst = std::max(kindWorst, std::abs(K(i, j) - ref(i, j)));
              kindScale = std::max(kindScale, std::abs(ref(i, j)));
            }
        INFO("rows " << std::string(rowNode ? "nodes" : "elements") << ", columns " << std::string(colNode ? "nodes" : "elements")
                     << ": largest entry " << kindScale << ", largest difference " << kindWorst);
        CHECK(kindScale > 0.0);
        CHECK(kindWorst <= 1e-6 * kindScale);
      }
  }
}

TEST_CASE("with a window, the Jacobian (the mature twists' rows and columns too) equals one-dof-at-a-time central differences") {
  for (const bool closed : {true, false}) {
    CAPTURE(closed);
    Cantilever c(30);
    c.opt.closedFormStiffness = closed;
    c.env.plane.enabled = true;
    c.env.plane.alpha = 0.7;
    c.env.adhesion = true;
    for (int i = 0; i < 16; ++i) c.s.anchored[static_cast<size_t>(i)] = 1;
    c.env.tipForce = Vec3(2e-5, 1e-5, -3e-5);
    for (int i = 1; i < c.s.nodes(); ++i) c.s.x.col(i) += 1e-4 * Vec3(std::sin(0.7 * i), 0.3 * std::cos(i), 0.2 * i / 30.0);
    for (int i = 0; i < c.s.elements(); ++i) rotateInPlace(Vec3(0.02 * i, -0.01 * i, 0.03 + 0.01 * std::sin(i)), c.s.Q[static_cast<size_t>(i)]);
    const int first = 13;  // the window: nodes 13.. and elements 13..; the twists of elements 0..12
    NewtonWorkspace nw;
    assembleStiffness(c.p, c.env, c.opt, c.s, c.ws, nw, first);
    std::vector<std::array<int, 2>> unknowns;
    for (int e = 0; e < first; ++e) unknowns.push_back({2 * e + 1, 2});
    for (int b = 2 * first; b <= 2 * c.s.elements(); ++b)
      for (int k = 0; k < 3; ++k) unknowns.push_back({b, k});
    const Eigen::MatrixXd ref = rootsim::test::oneDofStiffness(c.p, c.env, c.s, c.ws, unknowns);
    const Eigen::MatrixXd K = rootsim::test::assembledStiffness(nw);
    REQUIRE(K.rows() == ref.rows());
    const double worst = (K - ref).cwiseAbs().maxCoeff();
    const double scale = ref.cwiseAbs().maxCoeff();
    // the twist block alone (small entries beside the stretch ones): compared on its own scale
    const int m = first;
    const double twistWorst = (K.topLeftCorner(m, m) - ref.topLeftCorner(m, m)).cwiseAbs().maxCoeff();
    const double twistScale = ref.topLeftCorner(m, m).cwiseAbs().maxCoeff();
    INFO("largest entry " << scale << ", largest difference " << worst << "; twist block " << twistScale << " / " << twistWorst);
    CHECK(worst <= 1e-6 * scale);
    CHECK(twistScale > 0.0);
    CHECK(twistWorst <= 1e-6 * twistScale);
  }
}

TEST_CASE("Newton finds the explicit solver's cantilever equilibria (small and large load)") {
  for (double load : {1e-6, 1e-4}) {
    Cantilever a(40), b(40);
    a.env.tipForce = b.env.tipForce = Vec3(0, 0, -load);
    a.relax();
    b.opt.kind = SolverKind::Newton;
    NewtonWorkspace nw;
    const RelaxResult r = relaxNewton(b.p, b.env, b.opt, b.s, b.ws, nw, 0);
    INFO("load " << load << " N: " << r.iterations << " Newton iterations");
    CHECK(r.converged);
    // quadratic convergence from the straight start for the small load; the large one (P L^2 / B = 2.6,
    // tip rotation ~60 deg) from the straight start in one load step takes longer
    CHECK(r.iterations <= (load < 1e-5 ? 8 : 40));
    CHECK((a.tip() - b.tip()).norm() < 1e-6 * a.L);
  }
}

TEST_CASE("Newton's factorisation tells Euler buckling, as the stability check does") {
  for (double ratio : {0.9, 1.1}) {
    Cantilever c(30);
    const double Pcr = std::numbers::pi * std::numbers::pi * c.B1() / (4 * c.L * c.L);
    c.env.tipForce = Vec3(0, ratio * Pcr, 0);
    NewtonWorkspace nw;
    const RelaxResult r = relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, 0);
    REQUIRE(r.converged);
    CHECK(std::abs(c.tip().x()) < 1e-12);  // the straight column is an equilibrium either way
    CHECK(nw.negative == checkStability(c.p, c.env, c.s, c.ws).negative);
    CHECK(nw.negative == (ratio < 1 ? 0 : 2));
    if (ratio > 1) {
      CHECK(nw.lowestEigenvalue < 0);
      // following the mode with a short explicit relaxation reaches the buckled branch
      perturbAlong(c.s, nw.unstableMode(c.s, c.env), 1e-2 * c.p.radius);
      c.relax();
      REQUIRE(relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, 0).converged);
      CHECK(nw.negative == 0);
      CHECK(std::hypot(c.tip().x(), c.tip().z()) / c.L > 0.3);
    } else {
      CHECK(nw.lowestEigenvalue > 0);
    }
  }
}

TEST_CASE("a window freezes the positions of the rest of the rod exactly and leaves its twist free") {
  Cantilever c(30);
  c.env.tipForce = Vec3(0, 0, -1e-5);
  const RodState before = c.s;
  NewtonWorkspace nw;
  const RelaxResult r = relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, 20);
  CHECK(r.converged);
  for (int i = 0; i < 20; ++i) CHECK(c.s.x.col(i) == before.x.col(i));  // node 20 is the first free one
  // mature elements may only turn about their own axis: d3 stays where it was
  for (int i = 0; i < 20; ++i)
    CHECK((c.s.Q[static_cast<size_t>(i)].row(2) - before.Q[static_cast<size_t>(i)].row(2)).norm() < 1e-12);
  CHECK(c.s.x.col(30) != before.x.col(30));
}

TEST_CASE("a window carries torsion through the frozen root: the tip twists by T L / C under a tip couple") {
  // a clamped straight rod under a couple T about its axis: uniform twist rate T / C (C = B3), tip twist
  // T L / C. With the window from node 20 of 30, the twist of elements 0-19 is solved for, not frozen.
  for (int first : {0, 20}) {
    Cantilever c(30);
    const double C = c.p.bendStiffness().z();
    const Vec3 axis = (c.s.x.col(30) - c.s.x.col(0)).normalized();
    const double T = 1e-3 * C / c.L;  // tip twist 1e-3 rad
    c.env.tipTorque = T * axis;
    const Vec3 d1 = c.s.Q.back().row(0).transpose();
    NewtonWorkspace nw;
    const RelaxResult r = relaxNewton(c.p, c.env, c.opt, c.s, c.ws, nw, first);
    CHECK(r.converged);
    const Vec3 d1n = c.s.Q.back().row(0).transpose();
    const double twist = std::atan2(d1.cross(d1n).dot(axis), d1.dot(d1n));
    // the last element's d1 sits at the middle of the element: L - lbar / 2 of twisting length
    const double lbar = c.L / 30;
    INFO("window from node " << first << ": tip twist " << twist << " rad, T (L - lbar/2) / C = " << T * (c.L - 0.5 * lbar) / C);
    CHECK(twist == doctest::Approx(T * (c.L - 0.5 * lbar) / C).epsilon(1e-3));
  }
}
