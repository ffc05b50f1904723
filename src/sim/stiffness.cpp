// The rod's stiffness in closed form (stiffness.hpp). Notation as in rod.cpp: element i has nodes a = i,
// b = i + 1, dx = x_b - x_a, length l, tangent t, directors Q (rows d1 d2 d3), q = Q dx (material),
// shear strain sigma = q / l0 - e3, internal force n = S sigma l0 / l (material), N = Q^T n (lab) on node
// a and -N on node b, shear couple q x n on element i. A rotation theta of element i (Q <- (I - [theta]x) Q
// to first order) changes q by q x theta... i.e. dq = [q]x theta, and Q^T by Q^T [theta]x.
// Voronoi domain j between elements j and j+1: phi = log(Q_j Q_{j+1}^T) = kappa D0, dilatation
// ev = (l_j + l_{j+1}) / (2 D0), couple m = B (phi / (D0 ev) - kappa0) / ev^2, acting as
// m + phi x m / 2 on element j and -m + phi x m / 2 on element j+1. Turning element j multiplies the
// relative rotation from the left, element j+1 from the right: dphi = -Jl^-1(phi) theta_j +
// Jr^-1(phi) theta_{j+1}, with the inverse Jacobians of SO(3) (Jr^-1(phi) = Jl^-1(phi)^T).
#include "rootsim/stiffness.hpp"

#include <cmath>

#include "rootsim/rotation.hpp"

namespace rootsim {

namespace {

Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Jl^-1(phi) = I - [phi]x / 2 + c [phi]x^2 with c(t^2) = 1/t^2 - (1 + cos t) / (2 t sin t); a series
// below t^2 = 0.1 (the next term, t^8 / 47 900 160, is below 3e-12 of c there)
double inverseJacobianCoefficient(double t2) {
  if (t2 < 0.1) return 1.0 / 12.0 + t2 * (1.0 / 720.0 + t2 * (1.0 / 30240.0 + t2 / 1209600.0));
  const double t = std::sqrt(t2);
  return 1.0 / t2 - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t));
}
Mat3 inverseLeftJacobian(const Vec3& phi) {
  const Mat3 K = skew(phi);
  return Mat3::Identity() - 0.5 * K + inverseJacobianCoefficient(phi.squaredNorm()) * (K * K);
}

// a Voronoi-like couple m(phi, ev) = B (phi / (D0 ev) - kappa0) / ev^2 acting as s m + phi x m / 2 on an
// element (s = +1 on the element before the domain, -1 on the one after): the derivatives of that action
// with respect to phi (C = P diag(dm/dphi) - [m]x / 2, P = s I + [phi]x / 2) and to ev (P dm/dev)
struct CoupleDerivative {
  Mat3 dPhi;
  Vec3 dEv;
};
CoupleDerivative coupleDerivative(double side, const Vec3& phi, const Vec3& m, const Vec3& dmdphi,
                                  const Vec3& dmdev) {
  Mat3 P = 0.5 * skew(phi);
  P.diagonal().array() += side;
  return {P * dmdphi.asDiagonal() - 0.5 * skew(m), P * dmdev};
}

}  // namespace

bool stiffnessInClosedForm(const Environment& env) { return env.obstacles.empty() && !env.friction.enabled; }

void addStiffness(const RodParams& p, const Environment& env, const RodState& s, const RodStrains& k,
                  int firstFreeNode, StiffnessSink& sink) {
  const int n = s.elements();
  const Vec3 Sd = p.shearStiffness();
  const Vec3 Bd = p.bendStiffness();
  // stretch and shear, element by element
  for (int i = 0; i < n; ++i) {
    const Mat3& Q = s.Q[static_cast<size_t>(i)];
    const Vec3 q = Q * (s.x.col(i + 1) - s.x.col(i));
    const Vec3 nm = k.nMat.col(i);
    const double il = 1.0 / k.l[i];
    const int E = 2 * i + 1;
    if (i + 1 < firstFreeNode) {
      // both nodes frozen: the twist alone, K(E, E)(2, 2) of the full block below
      sink.addTwist(i, i, -(nm.x() * q.x() + nm.y() * q.y()) + (Sd.x() * q.y() * q.y() + Sd.y() * q.x() * q.x()) * il);
      continue;
    }
    const Mat3 Sq = Sd.asDiagonal() * skew(q);
    // dn/d(dx) and dn/dtheta
    const Mat3 A = (Sd.asDiagonal() * Q - nm * Vec3(k.t.col(i)).transpose()) * il;
    const Mat3 G = -skew(nm) + Sq * il;
    const Mat3 QtA = Q.transpose() * A, QtG = Q.transpose() * G;
    // the shear couple: d(q x n)/d(dx) and -d(q x n)/dtheta
    const Mat3 TA = skew(q) * A - skew(nm) * Q;
    const Mat3 TG = skew(nm) * skew(q) - skew(q) * Sq * il;
    const int a = 2 * i, b = 2 * i + 2;
    if (i >= firstFreeNode) {
      sink.add(a, a, QtA);
      sink.add(a, b, -QtA);
      sink.add(a, E, -QtG);
    }
    sink.add(b, a, -QtA);
    sink.add(b, b, QtA);
    sink.add(b, E, QtG);
    sink.add(E, a, TA);
    sink.add(E, b, -TA);
    sink.add(E, E, TG);
  }
  // bending and twist, Voronoi domain by Voronoi domain
  for (int j = 0; j + 1 < n; ++j) {
    const double D0 = k.D0[j], g = 1.0 / k.ev[j];
    const Vec3 phi = Vec3(k.kappa.col(j)) * D0;
    const Vec3 m = k.m.col(j);
    const Vec3 dmdphi = Bd * (g * g * g / D0);
    if (j + 2 < firstFreeNode) {
      // every node frozen: the twists alone, the (2, 2) entries of the blocks below written out (this
      // loop runs over the whole frozen root at every Jacobian): row 2 of dPhi = P diag(dm/dphi) - [m]x / 2
      // (P = side I + [phi]x / 2), and column 2 of Jl and of Jl^T, e3 -/+ phi x e3 / 2 + c phi x (phi x e3)
      const double t2 = phi.squaredNorm(), c = inverseJacobianCoefficient(t2);
      const Vec3 even(c * phi.x() * phi.z(), c * phi.y() * phi.z(), 1.0 + c * (phi.z() * phi.z() - t2));
      const Vec3 odd(0.5 * phi.y(), -0.5 * phi.x(), 0.0);
      const Vec3 cl = even - odd, cr = even + odd;
      const double r0 = 0.5 * (m.y() - phi.y() * dmdphi.x()), r1 = 0.5 * (phi.x() * dmdphi.y() - m.x());
      const Vec3 before(r0, r1, dmdphi.z()), after(r0, r1, -dmdphi.z());
      sink.addTwist(j, j, before.dot(cl));
      sink.addTwist(j, j + 1, -before.dot(cr));
      sink.addTwist(j + 1, j, after.dot(cl));
      sink.addTwist(j + 1, j + 1, -after.dot(cr));
      continue;
    }
    const Vec3 dmdev = Bd.cwiseProduct(-3.0 * g * g * g * g / D0 * phi + 2.0 * g * g * g * Vec3(s.kappa0.col(j)));
    const CoupleDerivative before = coupleDerivative(1.0, phi, m, dmdphi, dmdev);
    const CoupleDerivative after = coupleDerivative(-1.0, phi, m, dmdphi, dmdev);
    const Mat3 Jl = inverseLeftJacobian(phi);  // dphi/dtheta_j = -Jl, dphi/dtheta_{j+1} = Jl^T
    const int E1 = 2 * j + 1, E2 = 2 * j + 3;
    sink.add(E1, E1, before.dPhi * Jl);
    sink.add(E1, E2, -before.dPhi * Jl.transpose());
    sink.add(E2, E1, after.dPhi * Jl);
    sink.add(E2, E2, -after.dPhi * Jl.transpose());
    // the dilatation: dev/dx over nodes j, j+1, j+2
    const double h = 0.5 / D0;
    const Vec3 tj = k.t.col(j), tk = k.t.col(j + 1);
    const Vec3 dev[3] = {-h * tj, h * (tj - tk), h * tk};
    for (int c = 0; c < 3; ++c) {
      sink.add(E1, 2 * (j + c), -before.dEv * dev[c].transpose());
      sink.add(E2, 2 * (j + c), -after.dEv * dev[c].transpose());
    }
  }
  // the clamp: a half Voronoi domain between the clamp frame and element 0 (clampCouple), acting as
  // -m + phi x m / 2 on element 0, its dilatation that of element 0; phi = log(C Q0^T), so turning
  // element 0 multiplies it from the right
  if (env.base == BaseCondition::Clamped) {
    const ClampCouple cc = clampCouple(p, s, k.e[0]);
    const double D0 = 0.5 * s.l0[0], e0 = k.e[0];
    const Vec3 phi = cc.kappa * D0;
    const Vec3 dmdphi = Bd / (D0 * e0 * e0 * e0);
    const Vec3 dmdev = -3.0 / e0 * cc.m;
    const CoupleDerivative after = coupleDerivative(-1.0, phi, cc.m, dmdphi, dmdev);
    sink.add(1, 1, -after.dPhi * inverseLeftJacobian(phi).transpose());
    const Vec3 de = Vec3(k.t.col(0)) / s.l0[0];  // de0/dx1 = -de0/dx0
    sink.add(1, 0, after.dEv * de.transpose());
    sink.add(1, 2, -after.dEv * de.transpose());
  }
  // the tip couple, lab-fixed: its material components Q tau turn with the element
  if (env.tipTorque.squaredNorm() > 0.0) {
    const Vec3 tau = s.Q[static_cast<size_t>(n - 1)] * env.tipTorque;
    sink.add(2 * n - 1, 2 * n - 1, -skew(tau));
  }
  // plate contact: -k gap n / 2 on both nodes of an element below the plate, gap from its midpoint
  if (env.plane.enabled) {
    const Vec3 nh = env.plane.normal();
    const Mat3 Kp = 0.25 * env.plane.k * nh * nh.transpose();
    for (int i = std::max(0, firstFreeNode - 1); i < n; ++i) {
      const double gap = 0.5 * (s.x.col(i) + s.x.col(i + 1)).dot(nh) - p.radius;
      if (gap >= 0.0) continue;
      for (int a = 2 * i; a <= 2 * i + 2; a += 2)
        for (int b = 2 * i; b <= 2 * i + 2; b += 2) sink.add(a, b, Kp);
    }
  }
  if (env.adhesion) {
    const Mat3 Ka = env.kAdhesion * Mat3::Identity();
    for (int i = firstFreeNode; i <= n; ++i)
      if (s.anchored[static_cast<size_t>(i)]) sink.add(2 * i, 2 * i, Ka);
  }
}

}  // namespace rootsim
