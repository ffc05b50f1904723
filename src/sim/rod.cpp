#include "rootsim/rod.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "rootsim/rod_fields.hpp"
#include "rootsim/rotation.hpp"

namespace rootsim {

Vec3 RodParams::shearStiffness() const {
  return youngs * std::numbers::pi * radius * radius * shearFactors;
}
Vec3 RodParams::bendStiffness() const {
  const double r2 = radius * radius;
  return youngs * std::numbers::pi * r2 * r2 * bendFactors;
}

void RodState::resize(int n) {
  forEachField<RodState>([&](const auto& f) {
    auto& slot = this->*f.member;
    using T = std::remove_cvref_t<decltype(slot)>;
    const int count = valuesAlong(f.along, n);
    if constexpr (std::is_same_v<T, Eigen::Matrix3Xd>) slot.resize(3, count);
    else if constexpr (std::is_same_v<T, Eigen::VectorXd>) slot.resize(count);
    else if constexpr (std::is_same_v<T, std::vector<std::uint8_t>>) slot.assign(static_cast<size_t>(count), 0);
    else if constexpr (std::is_same_v<T, std::vector<Mat3>>) slot.resize(static_cast<size_t>(count));
    else static_assert(std::is_same_v<T, Mat3> || std::is_arithmetic_v<T>, "resize: a slot of a type it cannot size");
  });
}

const char* fieldOffElementCount(const RodState& s) {
  const char* off = nullptr;
  const int n = s.elements();
  forEachField<RodState>([&](const auto& f) {
    if (!off && valueCount(s.*f.member) != valuesAlong(f.along, n)) off = f.name;
  });
  return off;
}

void RodStrains::resize(int n) {
  const int nv = std::max(n - 1, 0);
  l.resize(n);
  e.resize(n);
  t.resize(3, n);
  sigma.resize(3, n);
  nMat.resize(3, n);
  nLab.resize(3, n);
  D0.resize(nv);
  ev.resize(nv);
  kappa.resize(3, nv);
  m.resize(3, nv);
}

namespace {

// rotation vector of R = A B^T, computed from the rows of A and B without forming R
// (R(a,b) = row a of A . row b of B); see rotationToVector for the branches
inline Vec3 relativeRotation(const Mat3& A, const Mat3& B) {
  const double r00 = A.row(0).dot(B.row(0)), r11 = A.row(1).dot(B.row(1)), r22 = A.row(2).dot(B.row(2));
  const double r21 = A.row(2).dot(B.row(1)), r12 = A.row(1).dot(B.row(2));
  const double r02 = A.row(0).dot(B.row(2)), r20 = A.row(2).dot(B.row(0));
  const double r10 = A.row(1).dot(B.row(0)), r01 = A.row(0).dot(B.row(1));
  const Vec3 v(0.5 * (r21 - r12), 0.5 * (r02 - r20), 0.5 * (r10 - r01));
  const double c = 0.5 * (r00 + r11 + r22 - 1.0);
  const double s2 = v.squaredNorm();
  if (c > 0.0 && s2 < 0.05) {
    // theta / sin(theta) = asin(x) / x with x = sin(theta) = |v|: the series sum_k C(2k, k) / (4^k (2k + 1))
    // x^2k, here to k = 12 (the rest < 2e-18 for x^2 < 0.05, |theta| < 13 deg: every Voronoi domain of
    // a root at h = 0.05 mm bends less). Cheaper than sqrt + atan2 + a division, which were 12 % of a
    // fig2b run (it was to k = 4 for x^2 < 2.5e-3).
    const double f =
        1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0 + s2 * (5.0 / 112.0 + s2 * (35.0 / 1152.0 + s2 * (63.0 / 2816.0 +
        s2 * (231.0 / 13312.0 + s2 * (143.0 / 10240.0 + s2 * (6435.0 / 557056.0 + s2 * (12155.0 / 1245184.0 +
        s2 * (46189.0 / 5505024.0 + s2 * (88179.0 / 12058624.0 + s2 * (676039.0 / 104857600.0))))))))))));
    return f * v;
  }
  if (c > -0.9) {  // the antisymmetric part gives the axis accurately away from pi
    const double sn = std::sqrt(s2);
    return (std::atan2(sn, c) / sn) * v;
  }
  return rotationToVector(A * B.transpose());
}

}  // namespace

void computeStrains(const RodParams& p, const RodState& s, RodStrains& k, int first, int end) {
  const int n = spanEnd(end, s.elements());
  const Vec3 Sd = p.shearStiffness();
  const Vec3 Bd = p.bendStiffness();
  // elements: length, dilatation, tangent, shear strain, internal force (Eq. 24, S -> S/e)
  // (reciprocals instead of repeated divisions: this loop is most of a relaxation sub-step)
  for (int i = first; i < n; ++i) {
    const Vec3 dx = s.x.col(i + 1) - s.x.col(i);
    const double l = dx.norm();
    const double il = 1.0 / l;
    const double e = l / s.l0[i];
    const Vec3 t = dx * il;
    const Mat3& Q = s.Q[static_cast<size_t>(i)];
    Vec3 sigma = e * (Q * t);
    sigma.z() -= 1.0;
    const Vec3 nm = Sd.cwiseProduct(sigma) * (s.l0[i] * il);  // S sigma / e
    k.l[i] = l;
    k.e[i] = e;
    k.t.col(i) = t;
    k.sigma.col(i) = sigma;
    k.nMat.col(i) = nm;
    k.nLab.col(i) = Q.transpose() * nm;
  }
  // Voronoi domains: curvature from the relative rotation of neighbouring elements, kappa defined by
  // d(d_j)/ds = kappa x d_j; with rows of Q the directors, Q_j Q_{j+1}^T = exp([kappa D0]x) in material
  // components. Couple (Eq. 25) with the rescaling B -> B/e^2, kappa -> kappa/e.
  for (int j = first; j + 1 < n; ++j) {
    const double D0 = 0.5 * (s.l0[j] + s.l0[j + 1]);
    const double iD0 = 1.0 / D0;
    const double ev = 0.5 * (k.l[j] + k.l[j + 1]) * iD0;
    const double iev = 1.0 / ev;
    const Vec3 kap = relativeRotation(s.Q[static_cast<size_t>(j)], s.Q[static_cast<size_t>(j + 1)]) * iD0;
    k.D0[j] = D0;
    k.ev[j] = ev;
    k.kappa.col(j) = kap;
    k.m.col(j) = Bd.cwiseProduct(kap * iev - s.kappa0.col(j)) * (iev * iev);
  }
}

void computeInternalForces(const RodState& s, const RodStrains& k, Eigen::Matrix3Xd& force,
                           Eigen::Matrix3Xd& torque, int first, int end) {
  const int n = spanEnd(end, s.elements());
  // nodes: difference of element internal forces (Eq. 22, discrete)
  force.col(first) = k.nLab.col(first);
  for (int i = first + 1; i < n; ++i) force.col(i) = k.nLab.col(i) - k.nLab.col(i - 1);
  if (n == s.elements()) force.col(n) = -k.nLab.col(n - 1);
  // elements (Eq. 23, discrete, material frame): difference of Voronoi couples, the averaged
  // kappa x m term, and the shear couple (Q t) x n l
  for (int i = first; i < n; ++i) {
    Vec3 tq = s.Q[static_cast<size_t>(i)] * k.t.col(i);
    tq = tq.cross(Vec3(k.nMat.col(i))) * k.l[i];
    if (i + 1 < n) {
      const Vec3 mr = k.m.col(i);
      tq += mr + 0.5 * k.D0[i] * Vec3(k.kappa.col(i)).cross(mr);
    }
    if (i > first) {
      const Vec3 ml = k.m.col(i - 1);
      tq += -ml + 0.5 * k.D0[i - 1] * Vec3(k.kappa.col(i - 1)).cross(ml);
    }
    torque.col(i) = tq;
  }
}

}  // namespace rootsim
