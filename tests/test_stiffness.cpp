// the closed-form stiffness of the rod (src/sim/stiffness.cpp) and the Newton solver's Jacobian built from
// it or by coloured differences (assembleStiffness, src/sim/relax_newton.cpp), against one-dof-at-a-time
// central differences of the forces
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <vector>

#include "physics_support.hpp"
#include "rootsim/rotation.hpp"

using namespace rootsim;
using rootsim::test::Cantilever;

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
