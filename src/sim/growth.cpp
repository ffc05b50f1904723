#include "rootsim/growth.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "rootsim/rod_fields.hpp"
#include "rootsim/rotation.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {
void recomputeMaterialCoordinates(RodState& s) {
  s.S[0] = 0.0;
  for (int i = 0; i < s.elements(); ++i) s.S[i + 1] = s.S[i] + s.l0[i];
}
// frame of Voronoi node j (between elements j and j+1): the mean of the two elements' directors,
// re-orthonormalised (neighbouring frames differ by a small rotation)
Mat3 voronoiFrame(const RodState& s, int j) {
  const Mat3 A = s.Q[static_cast<size_t>(j)] + s.Q[static_cast<size_t>(j + 1)];
  Vec3 d3 = A.row(2).transpose().normalized();
  Vec3 d1 = A.row(0).transpose();
  d1 = (d1 - d1.dot(d3) * d3).normalized();
  Mat3 F;
  F.row(0) = d1.transpose();
  F.row(1) = d3.cross(d1).transpose();
  F.row(2) = d3.transpose();
  return F;
}
}  // namespace

double setPointAt(const TropismParams& tp, double age) {
  if (!tp.setPointFinal || *tp.setPointFinal == tp.setPoint) return tp.setPoint;  // no drift: the constant, bit for bit
  const double last = *tp.setPointFinal;
  const double a = std::max(age, 0.0) / tp.setPointDriftTime;
  if (tp.setPointDrift == SetPointDrift::Linear) return a >= 1.0 ? last : tp.setPoint + (last - tp.setPoint) * a;
  return last + (tp.setPoint - last) * std::exp(-a);
}

double growthZoneStart(const Model& m, const RodState& s) {
  return std::max(0.0, s.restLength() - m.growth.zoneLength);
}

void anchorMatureNodes(const Model& m, RodState& s) {
  if (!m.env.adhesion) return;
  const double S0 = growthZoneStart(m, s);
  for (int i = 1; i < s.nodes(); ++i) {
    if (s.anchored[static_cast<size_t>(i)] || s.S[i] >= S0) continue;
    s.anchored[static_cast<size_t>(i)] = 1;
    s.anchor.col(i) = s.x.col(i);
  }
}

double growRestLengths(const Model& m, RodState& s, double dt) {
  const double S0 = growthZoneStart(m, s);
  const double g = m.growth.rate * dt;  // relative elongation of zone material in this step
  const int n = s.elements();
  // grow each element by the part of it inside the zone, and carry the shape along: every node
  // beyond a grown element moves with the element's stretched chord, so the configuration stays
  // close to equilibrium and the relaxation only has to correct it
  Vec3 shift = Vec3::Zero();
  double added = 0.0;
  for (int i = 0; i < n; ++i) {
    const double a = s.S[i], b = s.S[i + 1];
    const double inside = std::max(0.0, b - std::max(a, S0));
    if (inside > 0.0) {
      const double dl = g * inside;
      // the element's chord as it was before this loop (node i has already moved by shift) stretched
      // in proportion to its rest length
      const Vec3 seg = s.x.col(i + 1) - s.x.col(i) + shift;
      shift += (dl / s.l0[i]) * seg;
      s.l0[i] += dl;
      added += dl;
    }
    s.x.col(i + 1) += shift;
  }
  recomputeMaterialCoordinates(s);
  return added;
}

void updateIntrinsicCurvature(const Model& m, RodState& s, const RodStrains& k, double dt) {
  const int n = s.elements();
  if (n < 2) return;
  const double S0 = growthZoneStart(m, s);
  const double R = m.rod.radius;
  const double rate = m.growth.rate;  // eps_g in the zone
  const TropismParams& tp = m.tropism;
  Vec3 g(0.0, 0.0, -1.0);
  const double phiS = setPointAt(tp, s.time - m.initial.startTime);
  if (phiS != 0.0) {
    // the set-point direction g_s = cos(phi_s) g + sin(phi_s) h, h the horizontal direction of the
    // apex's tangent; an apex along g takes the side the organ started towards (its initial angle's)
    const Vec3 t = s.Q[static_cast<size_t>(n - 1)].row(2).transpose();
    Vec3 h = t - t.dot(g) * g;
    const double hn = h.norm();
    h = hn > 1e-9 ? Vec3(h / hn) : Vec3((m.initial.angle < 0.0 ? -1.0 : 1.0) * m.env.plane.lateral());
    g = std::cos(phiS) * g + std::sin(phiS) * h;
  }
  // apical sensing: gravity's components in the apex frame, reused as components in the local frame
  const Vec3 gApex = s.Q[static_cast<size_t>(n - 1)] * g;
  // circumnutation: a twist-free (Bishop) frame parallel-transported from the base
  const bool cn = tp.cnGain > 0.0;
  Vec3 m1 = s.Q[0].row(0).transpose();
  Vec3 tPrev = s.Q[0].row(2).transpose();
  const double phase = cn ? 2.0 * units::pi * s.time / tp.cnPeriod : 0.0;
  for (int j = 0; j + 1 < n; ++j) {
    const Mat3 F = voronoiFrame(s, j);
    Vec3 dcn = Vec3::Zero();
    if (cn) {
      // transport m1 from element j's tangent to the Voronoi tangent by the minimal rotation
      const Vec3 t = F.row(2).transpose();
      const Vec3 axis = tPrev.cross(t);
      const double sn = axis.norm(), cs = tPrev.dot(t);
      if (sn > 1e-15) m1 = rotationFromVector(axis / sn * std::atan2(sn, cs)) * m1;
      m1 = (m1 - m1.dot(t) * t).normalized();
      tPrev = t;
      const Vec3 m2 = t.cross(m1);
      dcn = tp.cnGain * (std::cos(phase) * m1 + std::sin(phase) * m2);
    }
    const double Sj = s.S[j + 1];
    if (Sj < S0) continue;  // mature: kappa0 frozen
    const Vec3 d1 = F.row(0).transpose(), d2 = F.row(1).transpose(), d3 = F.row(2).transpose();
    const Vec3 gs = tp.sensing == Sensing::Apical ? Vec3(F.transpose() * gApex) : g;
    // current curvature per current length, material components; curvature vector kappa N = k2 d1 - k1 d2
    const Vec3 kap = k.kappa.col(j) / k.ev[j];
    const Vec3 kN = kap.y() * d1 - kap.x() * d2;
    const Vec3 delta = tp.beta * gs - tp.gamma * R * kN + dcn;
    const Vec3 rhs = d3.cross(delta) * (rate / R);
    s.kappa0(0, j) += dt * rhs.dot(d1);
    s.kappa0(1, j) += dt * rhs.dot(d2);
  }
}

void applyTwistProfile(const Model& m, RodState& s) {
  const double tau = m.tropism.rTau / m.rod.radius;
  const double L = s.restLength();
  for (int j = 0; j + 1 < s.elements(); ++j) {
    const double u = std::clamp((L - s.S[j + 1]) / m.growth.zoneLength, 0.0, 1.0);
    s.kappa0(2, j) = tau * u;
  }
}

namespace {

// value i of a listed field (a column of a 3 x k array)
template <class T>
decltype(auto) item(T& v, int i) {
  using U = std::remove_const_t<T>;
  if constexpr (std::is_same_v<U, Eigen::Matrix3Xd>) return v.col(i);
  else if constexpr (std::is_same_v<U, Eigen::VectorXd>) return (v[i]);
  else return (v[static_cast<size_t>(i)]);
}

// field I of s split into t (t sized for the new element count), by the rule the field list gives it
// (rod_fields.hpp, OnSplit); `split(i)` says whether input element i is split
template <std::size_t I, class Split>
void splitField(const RodState& s, RodState& t, const Split& split) {
  constexpr auto f = std::get<I>(FieldsOf<RodState>::list());
  const auto& from = s.*f.member;
  auto& to = t.*f.member;
  using T = std::remove_cvref_t<decltype(to)>;
  const int n = s.elements();
  if constexpr (f.split == OnSplit::Zero) {
    static_assert(std::is_base_of_v<Eigen::DenseBase<T>, T>, "OnSplit::Zero: an Eigen array");
    to.setZero();
  } else if constexpr (f.split == OnSplit::Recompute) {
    // splitLongElements recomputes it
  } else if constexpr (f.along == Along::Rod) {
    static_assert(f.split == OnSplit::Copy, "a whole-rod field is copied");
    to = from;
  } else if constexpr (f.along == Along::Node) {
    static_assert(f.split == OnSplit::Mean || f.split == OnSplit::Both, "a node field: Mean, Both, Zero or Recompute");
    item(to, 0) = item(from, 0);
    for (int i = 0, o = 0; i < n; ++i) {
      if (split(i)) {
        if constexpr (f.split == OnSplit::Mean) item(to, o + 1) = 0.5 * (item(from, i) + item(from, i + 1));
        else item(to, o + 1) = item(from, i) && item(from, i + 1) ? 1 : 0;
        o += 2;
      } else {
        o += 1;
      }
      item(to, o) = item(from, i + 1);
    }
  } else if constexpr (f.along == Along::Element) {
    static_assert(f.split == OnSplit::Copy || f.split == OnSplit::Halve, "an element field: Copy, Halve or Zero");
    for (int i = 0, o = 0; i < n; ++i) {
      if constexpr (f.split == OnSplit::Halve) item(to, o) = split(i) ? 0.5 * item(from, i) : item(from, i);
      else item(to, o) = item(from, i);
      if (split(i)) item(to, o + 1) = item(to, o);
      o += split(i) ? 2 : 1;
    }
  } else {
    static_assert(f.along == Along::Voronoi && f.split == OnSplit::Mean, "a Voronoi field: Mean");
    static_assert(std::is_same_v<T, Eigen::Matrix3Xd>, "a Voronoi field: a 3 x n-1 array");
    // the domain on the left of output element o (between o-1 and o) is an input one; the new one inside
    // a split element takes the mean of its neighbours (an end one's of its one neighbour)
    for (int i = 0, o = 0; i < n; ++i) {
      if (i > 0) to.col(o - 1) = from.col(i - 1);
      if (split(i)) {
        if (n > 1) {
          Vec3 left = i > 0 ? Vec3(from.col(i - 1)) : Vec3(from.col(i));
          const Vec3 right = i + 1 < n ? Vec3(from.col(i)) : left;
          if (i == 0) left = right;
          to.col(o) = 0.5 * (left + right);
        } else {
          to.col(o).setZero();  // one element has no domain to take it from
        }
        o += 2;
      } else {
        o += 1;
      }
    }
  }
}

}  // namespace

int splitLongElements(const Model& m, RodState& s) {
  const double limit = m.growth.splitFactor * m.initial.elementLength;
  int count = 0;
  for (int i = 0; i < s.elements(); ++i)
    if (s.l0[i] > limit) ++count;
  if (count == 0) return 0;
  RodState t;
  t.resize(s.elements() + count);
  const auto split = [&](int i) { return s.l0[i] > limit; };
  // every listed field by its rule (rod_fields.hpp): a field added to the list is split with it
  forEachRodField([&](auto index) { splitField<decltype(index)::value>(s, t, split); });
  recomputeMaterialCoordinates(t);
  s = std::move(t);
  return count;
}

}  // namespace rootsim
