// The geometry of the contact pieces (contact_geometry.hpp, contact.hpp): closest points of segments and
// the self-contact Verlet list.
#include "contact_geometry.hpp"

#include <algorithm>

#include "rootsim/assert.hpp"

namespace rootsim {

using namespace contact_detail;

void closestSegmentPoints(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double& sa,
                          double& sb) {
  const Vec3 d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (a <= 0.0 && e <= 0.0) { sa = sb = 0.0; return; }
  if (a <= 0.0) { sa = 0.0; sb = clamp01(f / e); return; }
  const double c = d1.dot(r);
  if (e <= 0.0) { sb = 0.0; sa = clamp01(-c / a); return; }
  const double b = d1.dot(d2), denom = a * e - b * b;
  if (denom > 1e-12 * a * e) {
    sa = clamp01((b * f - c * e) / denom);
  } else {
    // parallel: any point of the overlap is closest; take the middle of a's part that faces b
    const double lo = clamp01(-c / a), hi = clamp01((b - c) / a);
    sa = 0.5 * (lo + hi);
  }
  sb = (b * sa + f) / e;
  if (sb < 0.0) { sb = 0.0; sa = clamp01(-c / a); }
  else if (sb > 1.0) { sb = 1.0; sa = clamp01((b - c) / a); }
}

void contactSegmentPoints(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double& sa,
                          double& sb) {
  closestSegmentPoints(a0, a1, b0, b1, sa, sb);
  const Vec3 d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm();
  if (a <= 0.0 || e <= 0.0) return;
  const double b = d1.dot(d2), c = d1.dot(r);
  const double sin2 = std::max(0.0, (a * e - b * b) / (a * e));
  if (sin2 >= kParallelSin2) return;
  // nearly parallel: the closest points jump from one end of the overlap to the other as the segments
  // pass through parallel (the distance does not): blend towards the middle of a's part facing b, so
  // that the point, and the force applied there, are continuous functions of the nodes
  const double t = sin2 / kParallelSin2, w = t * t * (3.0 - 2.0 * t);
  const double lo = clamp01(-c / a), hi = clamp01((b - c) / a);
  sa = w * sa + (1.0 - w) * 0.5 * (lo + hi);
  sb = clamp01((a0 + sa * d1 - b0).dot(d2) / e);
}

namespace contact_detail {

void updatePairs(const RodParams& p, const RodState& s, ContactWorkspace& cw) {
  const int n = s.elements();
  const double skin = kSkinRadii * p.radius;
  if (listServes(s, skin, cw.xBuilt, cw.builtElements, cw.builtRestLength)) return;
  ROOTSIM_ASSERT(static_cast<int>(cw.order.size()) == n, "a contact workspace sized for the rod");
  ++cw.builds;
  const double reach = 2.0 * p.radius + skin;
  double lmax = 0.0;
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  for (int i = 0; i < n; ++i) {
    cw.mid.col(i) = 0.5 * (s.x.col(i) + s.x.col(i + 1));
    cw.halfLength[i] = 0.5 * (s.x.col(i + 1) - s.x.col(i)).norm();
    lmax = std::max(lmax, 2.0 * cw.halfLength[i]);
    lo = lo.cwiseMin(cw.mid.col(i));
    hi = hi.cwiseMax(cw.mid.col(i));
  }
  // sort and sweep along the axis of the midpoints' widest spread: two elements within `reach` have
  // midpoints within lmax + reach along it. (It replaced a spatial hash of 27 cells per element, whose
  // fixed cost per element was most of a rebuild on a long waving root: 8 % of a fig2b run.)
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const double slab = lmax + reach;
  for (int i = 0; i < n; ++i) {
    cw.key[i] = std::isfinite(cw.mid(axis, i)) ? cw.mid(axis, i) : 0.0;
    cw.order[static_cast<size_t>(i)] = i;
  }
  std::sort(cw.order.begin(), cw.order.end(), [&](int a, int b) {
    return cw.key[a] < cw.key[b] || (cw.key[a] == cw.key[b] && a < b);
  });
  cw.pairs.clear();
  for (int u = 0; u < n; ++u) {
    const int a = cw.order[static_cast<size_t>(u)];
    for (int v = u + 1; v < n; ++v) {
      const int b = cw.order[static_cast<size_t>(v)];
      if (cw.key[b] - cw.key[a] >= slab) break;
      const int i = std::min(a, b), j = std::max(a, b);
      if (excludedAlongRod(p, s, i, j)) continue;
      // no point of two segments is closer than their midpoints' distance less the half-lengths: a
      // cheap test that spares the exact one most pairs
      const double far = cw.halfLength[i] + cw.halfLength[j] + reach;
      if ((cw.mid.col(i) - cw.mid.col(j)).squaredNorm() >= far * far) continue;
      double sa = 0, sb = 0;
      closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), sa, sb);
      const Vec3 d = (s.x.col(i) + sa * (s.x.col(i + 1) - s.x.col(i))) - (s.x.col(j) + sb * (s.x.col(j + 1) - s.x.col(j)));
      if (d.squaredNorm() < reach * reach) cw.pairs.push_back({i, j});
    }
  }
  // canonical order: the forces sum the pairs in contact in the same order whichever list serves, so
  // they do not depend on when the list was built (nor does a resumed run)
  std::sort(cw.pairs.begin(), cw.pairs.end());
  cw.xBuilt = s.x;
  cw.builtElements = n;
  cw.builtRestLength = s.S[n];
}

}  // namespace contact_detail

}  // namespace rootsim
