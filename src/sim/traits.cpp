#include "rootsim/traits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "rootsim/units.hpp"

namespace rootsim {

namespace {

// the polyline without consecutive repeated points
Eigen::Matrix3Xd distinctPoints(const Eigen::Matrix3Xd& p) {
  std::vector<int> keep;
  for (int i = 0; i < p.cols(); ++i)
    if (keep.empty() || (p.col(i) - p.col(keep.back())).norm() > 0.0) keep.push_back(i);
  Eigen::Matrix3Xd q(3, static_cast<Eigen::Index>(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) q.col(static_cast<Eigen::Index>(k)) = p.col(keep[k]);
  return q;
}

// cumulative arc length at each point
std::vector<double> arcLengths(const Eigen::Matrix3Xd& p) {
  std::vector<double> s(static_cast<std::size_t>(p.cols()), 0.0);
  for (int i = 1; i < p.cols(); ++i) s[static_cast<std::size_t>(i)] = s[static_cast<std::size_t>(i - 1)] + (p.col(i) - p.col(i - 1)).norm();
  return s;
}

// the point at arc length t along p (s: arcLengths(p)), linear between points
Eigen::Vector3d pointAt(const Eigen::Matrix3Xd& p, const std::vector<double>& s, double t) {
  if (t <= 0.0) return p.col(0);
  if (t >= s.back()) return p.col(p.cols() - 1);
  const auto it = std::upper_bound(s.begin(), s.end(), t);
  const int j = static_cast<int>(it - s.begin());  // s[j-1] <= t < s[j]
  const double f = (t - s[static_cast<std::size_t>(j - 1)]) / (s[static_cast<std::size_t>(j)] - s[static_cast<std::size_t>(j - 1)]);
  return p.col(j - 1) + f * (p.col(j) - p.col(j - 1));
}

}  // namespace

double polylineLength(const Eigen::Matrix3Xd& p) {
  double l = 0.0;
  for (int i = 1; i < p.cols(); ++i) l += (p.col(i) - p.col(i - 1)).norm();
  return l;
}

Eigen::Matrix3Xd resampleByArcLength(const Eigen::Matrix3Xd& p, double ds) {
  if (!(ds > 0.0)) throw std::invalid_argument("resampleByArcLength: the step must be > 0");
  const Eigen::Matrix3Xd q = distinctPoints(p);
  if (q.cols() < 2) throw std::invalid_argument("resampleByArcLength: the polyline has no length");
  const std::vector<double> s = arcLengths(q);
  const double L = s.back();
  const int n = std::max(1, static_cast<int>(std::lround(L / ds)));
  Eigen::Matrix3Xd r(3, n + 1);
  for (int i = 0; i <= n; ++i) r.col(i) = i == n ? Eigen::Vector3d(q.col(q.cols() - 1)) : pointAt(q, s, L * i / n);
  return r;
}

Eigen::Matrix3Xd plateMmToLab(const Eigen::Matrix3Xd& plateMm, const PlateFrame& f) {
  Eigen::Matrix3Xd x(3, plateMm.cols());
  for (int i = 0; i < plateMm.cols(); ++i)
    x.col(i) = (plateMm(0, i) * f.lateral + plateMm(1, i) * f.downhill + plateMm(2, i) * f.normal) * units::mm;
  return x;
}

RootTraits rootTraits(const Eigen::Matrix3Xd& plateMm, double dsMm, double excludeTipMm, double radiusMm,
                      const AnalysisParams& set) {
  const Eigen::Matrix3Xd q = distinctPoints(plateMm);
  if (q.cols() < 2) throw std::invalid_argument("rootTraits: a root needs at least two distinct points");
  RootTraits t;
  t.lengthMm = polylineLength(q);
  const Eigen::Vector3d chord = q.col(q.cols() - 1) - q.col(0);
  // on the plate: the chord's in-plane part (a trace's height is its own business)
  const Eigen::Vector2d c2(chord.x(), chord.y());
  t.chordMm = c2.norm();
  t.tortuosity = t.chordMm > 0.0 ? t.lengthMm / t.chordMm : std::numeric_limits<double>::infinity();
  // the skew angle by the runs' own planarAngle, on a plate put into the lab frame (any tilt gives the same
  // angle: a vertical plate)
  const PlateFrame frame = PlateFrame::tilted(90.0 * units::deg);
  Plane plane;
  plane.alpha = 90.0 * units::deg;
  const Eigen::Matrix3Xd lab = plateMmToLab(q, frame);
  t.skewDeg = planarAngle(plane, lab.col(lab.cols() - 1) - lab.col(0)) / units::deg;
  // the shape analysis at a run's resolution, on the mature part
  t.dsMm = dsMm;
  const Eigen::Matrix3Xd r = dsMm > 0.0 ? resampleByArcLength(q, dsMm) : q;
  const double matureMm = t.lengthMm - std::max(0.0, excludeTipMm);
  const std::vector<double> s = arcLengths(r);
  int last = 0;
  while (last + 1 < static_cast<int>(s.size()) && s[static_cast<std::size_t>(last + 1)] <= matureMm + 1e-12 * t.lengthMm) ++last;
  t.matureLast = last;
  t.shape = analyseCentreline(plateMmToLab(r, frame), last, plane, set, radiusMm * units::mm);
  return t;
}

double insertionAngleDeg(const Eigen::Matrix3Xd& parentMm, const Eigen::Matrix3Xd& lateralMm, double spanMm) {
  const Eigen::Matrix3Xd par = distinctPoints(parentMm), lat = distinctPoints(lateralMm);
  if (par.cols() < 2 || lat.cols() < 2) return std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> sp = arcLengths(par), sl = arcLengths(lat);
  // the lateral's direction over its first spanMm
  const Eigen::Vector3d base = lat.col(0);
  const Eigen::Vector3d dl = pointAt(lat, sl, std::min(spanMm, sl.back())) - base;
  // the parent point nearest the lateral's base (over the parent's segments), as an arc length
  double best = std::numeric_limits<double>::infinity(), at = 0.0;
  for (int i = 0; i + 1 < par.cols(); ++i) {
    const Eigen::Vector3d a = par.col(i), b = par.col(i + 1), ab = b - a;
    const double f = std::clamp((base - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const double d = (a + f * ab - base).norm();
    if (d < best) {
      best = d;
      at = sp[static_cast<std::size_t>(i)] + f * ab.norm();
    }
  }
  const Eigen::Vector3d dp = pointAt(par, sp, at + spanMm) - pointAt(par, sp, at - spanMm);
  if (dp.norm() == 0.0 || dl.norm() == 0.0) return std::numeric_limits<double>::quiet_NaN();
  const double c = std::clamp(dp.normalized().dot(dl.normalized()), -1.0, 1.0);
  return std::acos(c) / units::deg;
}

}  // namespace rootsim
