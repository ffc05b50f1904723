#pragma once
// shared set-up for mechanics tests: a horizontal cantilever (alpha = 90 deg, plane off) along -y,
// d1 = x, d2 = z, d3 = -y, clamped at the origin side
#include "rootsim/initial.hpp"
#include "rootsim/relax.hpp"

namespace rootsim::test {

struct Cantilever {
  RodParams p;
  Environment env;
  SolverOptions opt;
  RodState s;
  RelaxWorkspace ws;
  double L;

  Cantilever(int n, double length = 1e-2, double forceTol = 1e-8) : L(length) {
    env.plane.enabled = false;
    env.plane.alpha = 1.5707963267948966;
    env.adhesion = false;
    opt.forceTol = forceTol;
    opt.speedTol = 1e-9;
    InitialShape sh;
    sh.length = length;
    sh.elementLength = length / n;
    sh.perturbation = 0.0;
    s = makeInitialRod(p, env.plane, sh);
  }
  double B1() const { return p.bendStiffness().x(); }
  Vec3 tip() const { return s.x.col(s.nodes() - 1) - s.x.col(0); }
  RelaxResult relax() { return rootsim::relax(p, env, opt, s, ws); }
};

}  // namespace rootsim::test
