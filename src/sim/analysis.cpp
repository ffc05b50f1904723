#include "rootsim/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "rootsim/growth.hpp"
#include "rootsim/rod.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

double planarAngle(const Plane& plane, const Vec3& t) {
  const Vec3 nh = plane.normal(), down = plane.downhill();
  return std::atan2(down.cross(t).dot(nh), t.dot(down));
}

double tipAngle(const Model& m, const RodState& s) {
  const int n = s.elements();
  const Vec3 t = (s.x.col(n) - s.x.col(n - 1)).normalized();
  if (!m.env.plane.enabled) {
    // free organ (Fig. 2C): angle from gravity in the vertical plane of motion, about +x
    const Vec3 g(0.0, 0.0, -1.0);
    return std::atan2(g.cross(t).x(), t.dot(g));
  }
  return planarAngle(m.env.plane, t);
}

namespace {

// the triple product of two segments and their offset, relative to the product of their lengths, below
// which they count as coplanar: rounding leaves about 1e-15 of it (positions ~1 mm, elements ~0.05 mm)
constexpr double kCoplanarTolerance = 1e-12;

// solid-angle contribution of segments (p1,p2) and (p3,p4) to the Gauss integral, divided by 4 pi
double gaussPair(const Vec3& p1, const Vec3& p2, const Vec3& p3, const Vec3& p4) {
  const Vec3 r13 = p3 - p1, r14 = p4 - p1, r23 = p3 - p2, r24 = p4 - p2;
  // coplanar segments (collinear ones included) contribute exactly 0: the integrand (t x t').r vanishes.
  // Up to rounding they are not coplanar, and the normals below, of rounding-noise length, would point
  // anywhere (a straight rod at a general orientation gave Wr of +-1..3 turns; docs/model.md, Observables)
  const double sg = (p4 - p3).cross(p2 - p1).dot(r13);
  if (std::abs(sg) <= kCoplanarTolerance * (p4 - p3).norm() * (p2 - p1).norm() * r13.norm()) return 0.0;
  Vec3 n[4] = {r13.cross(r14), r14.cross(r24), r24.cross(r23), r23.cross(r13)};
  for (auto& v : n) {
    const double l = v.norm();
    if (l < 1e-300) return 0.0;
    v /= l;
  }
  auto as = [](double x) { return std::asin(std::clamp(x, -1.0, 1.0)); };
  const double om = as(n[0].dot(n[1])) + as(n[1].dot(n[2])) + as(n[2].dot(n[3])) + as(n[3].dot(n[0]));
  return (sg > 0 ? om : -om) / (4.0 * std::numbers::pi);
}

}  // namespace

double writheOpen(const Eigen::Matrix3Xd& p, int first, int last) {
  double wr = 0.0;
  for (int i = first; i < last; ++i)
    for (int j = i + 2; j < last; ++j)
      wr += 2.0 * gaussPair(p.col(i), p.col(i + 1), p.col(j), p.col(j + 1));
  return wr;
}

double writheClosed(const Eigen::Matrix3Xd& p) {
  const int n = static_cast<int>(p.cols());
  double wr = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing segment
      wr += 2.0 * gaussPair(p.col(i), p.col((i + 1) % n), p.col(j), p.col((j + 1) % n));
    }
  return wr;
}

double linkingNumber(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  const int na = static_cast<int>(a.cols()), nb = static_cast<int>(b.cols());
  double lk = 0.0;
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j) lk += gaussPair(a.col(i), a.col((i + 1) % na), b.col(j), b.col((j + 1) % nb));
  return lk;
}

double zoneShare(const RodState& s, int j, double Sfrom, double Sto) {
  // Voronoi domain j runs from the centre of element j to the centre of element j + 1 (rest arc length)
  const double a = s.S[j + 1] - 0.5 * s.l0[j], b = s.S[j + 1] + 0.5 * s.l0[j + 1];
  return std::max(0.0, std::min(b, Sto) - std::max(a, Sfrom));
}

ZoneObservables observeZone(const Model& m, const RodState& s, const RodStrains& k) {
  // docs/model.md, Observables: every integral runs over exactly [S0, L] in rest arc length; the Voronoi
  // domain (and, for Wr, the element) that straddles S0 counts pro rata
  ZoneObservables o;
  const double S0 = growthZoneStart(m, s), L = s.restLength();
  const Vec3 Bd = m.rod.bendStiffness();
  double tw = 0.0;
  for (int j = 0; j + 1 < s.elements(); ++j) {
    const double share = zoneShare(s, j, S0, L);  // rest length of domain j inside the zone
    if (share <= 0.0) continue;
    const double ev = k.ev[j];
    const Vec3 dk = Vec3(k.kappa.col(j)) / ev - Vec3(s.kappa0.col(j));
    const Vec3 mc = Bd.cwiseProduct(dk) / (ev * ev);
    const double ds = share * ev;  // current arc length of that part
    o.Eb += (mc.x() * dk.x() + mc.y() * dk.y()) * ds;
    o.Et += mc.z() * dk.z() * ds;
    // kappa is per rest length (rotation / D0): kappa3 per current length (kappa3 / ev) times ds
    tw += k.kappa(2, j) * share;
  }
  o.Tw = tw / (2.0 * std::numbers::pi);
  // writhe of the centreline from S0 to the tip: the element straddling S0 is cut there, its first point
  // interpolated linearly along the element's chord
  int e = 0;
  while (e + 1 < s.nodes() - 1 && s.S[e + 1] <= S0) ++e;
  const double f = s.l0[e] > 0.0 ? std::clamp((S0 - s.S[e]) / s.l0[e], 0.0, 1.0) : 0.0;
  Eigen::Matrix3Xd zone(3, s.nodes() - e);
  zone.col(0) = s.x.col(e) + f * (s.x.col(e + 1) - s.x.col(e));
  zone.rightCols(s.nodes() - e - 1) = s.x.rightCols(s.nodes() - e - 1);
  o.Wr = writheOpen(zone, 0, static_cast<int>(zone.cols()) - 1);
  return o;
}

int matureLastNode(const Model& m, const RodState& s) {
  const int n = s.elements();
  if (!m.growth.enabled) return n;
  const double S0 = growthZoneStart(m, s);
  int last = 0;
  while (last < n && s.S[last + 1] <= S0 + 1e-15) ++last;
  return last;
}

ShapeAnalysis analyseShape(const Model& m, const RodState& s) {
  return analyseCentreline(s.x, matureLastNode(m, s), m.env.plane, m.analysis, m.rod.radius);
}

ShapeAnalysis analyseCentreline(const Eigen::Matrix3Xd& x, int last, const Plane& pl, const AnalysisParams& set,
                                double radius, double noiseSwing, double endSwing) {
  ShapeAnalysis a;
  const Vec3 down = pl.downhill(), lat = pl.lateral();
  const int n = static_cast<int>(x.cols()) - 1;
  if (n < 1) throw std::invalid_argument("analyseCentreline: a centreline needs at least two points");
  last = std::clamp(last, 0, n);
  // unwrapped planar tangent angle per element
  std::vector<double> th(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    double t = planarAngle(pl, x.col(i + 1) - x.col(i));
    if (i > 0) {
      const double prev = th[static_cast<size_t>(i - 1)];
      t += 2.0 * std::numbers::pi * std::round((prev - t) / (2.0 * std::numbers::pi));
    }
    th[static_cast<size_t>(i)] = t;
  }
  a.thetaMin = *std::min_element(th.begin(), th.end());
  a.thetaMax = *std::max_element(th.begin(), th.end());
  // projected curvature d theta / ds between neighbouring elements
  for (int j = 0; j + 1 < n; ++j) {
    const double ds = 0.5 * ((x.col(j + 1) - x.col(j)).norm() + (x.col(j + 2) - x.col(j + 1)).norm());
    a.maxKappa = std::max(a.maxKappa, std::abs(th[static_cast<size_t>(j + 1)] - th[static_cast<size_t>(j)]) / ds);
  }
  // skew: direction of the mature part as a whole (replaced below by the direction over whole waves)
  if (last >= 1) a.skew = planarAngle(pl, x.col(last) - x.col(0));
  // lateral and downhill plate coordinates of the mature nodes, in order along the rod
  std::vector<double> u, w;
  for (int i = 0; i <= last; ++i) {
    u.push_back(x.col(i).dot(lat));
    w.push_back(x.col(i).dot(down));
  }
  // turning points of u with hysteresis minSwing: a running extreme becomes a peak once u has come back
  // from it by more than minSwing, so ripples smaller than minSwing never make peaks and consecutive
  // peaks alternate sides. A traced root's noise threshold raises it (docs/experiments.md, Noise)
  const double minSwing = std::max(set.waveMinAmplitude * radius, noiseSwing);
  a.hysteresis = minSwing;
  std::vector<int> ext;
  {
    int cand = 0, dir = 0;
    auto U = [&](int i) { return u[static_cast<size_t>(i)]; };
    for (int i = 1; i < static_cast<int>(u.size()); ++i) {
      if (dir == 0) {
        if (std::abs(U(i) - U(0)) > minSwing) { dir = U(i) > U(0) ? 1 : -1; cand = i; }
      } else if (dir * (U(i) - U(cand)) > 0) {
        cand = i;  // the running extreme moves on
      } else if (dir * (U(cand) - U(i)) > minSwing) {
        ext.push_back(cand);  // turned back by more than minSwing: cand was a peak
        dir = -dir;
        cand = i;
      }
    }
  }
  // the train's ends: its first peak needs a departure from the first node of endSwing, its last a return
  // within the mature part of endSwing (the peaks a larger hysteresis would not find at the ends)
  const double endMin = std::max(minSwing, endSwing);
  if (endMin > minSwing) {
    auto U = [&](int i) { return u[static_cast<size_t>(i)]; };
    while (!ext.empty() && !(std::abs(U(ext.front()) - U(0)) > endMin)) ext.erase(ext.begin());
    while (!ext.empty()) {
      const int k = ext.back();
      const double side = U(k) >= (ext.size() >= 2 ? U(ext[ext.size() - 2]) : U(0)) ? 1.0 : -1.0;
      double back = 0.0;
      for (int i = k + 1; i < static_cast<int>(u.size()); ++i) back = std::max(back, side * (U(k) - U(i)));
      if (back > endMin) break;
      ext.pop_back();
    }
  }
  const size_t np = ext.size();
  a.peaks = static_cast<int>(np);
  a.peakNodes = ext;
  a.waves = np >= 1 ? 0.5 * static_cast<double>(np - 1) : 0.0;
  auto U = [&](size_t k) { return u[static_cast<size_t>(ext[k])]; };
  auto W = [&](size_t k) { return w[static_cast<size_t>(ext[k])]; };
  // a waving shape: the skew over whole waves (first peak to the last peak on its side), so an
  // incomplete first or last excursion does not bias it
  if (np >= 3) {
    const size_t lastSame = np - 1 - ((np - 1) % 2);
    a.skew = planarAngle(pl, x.col(ext[lastSame]) - x.col(ext[0]));
  }
  // A: mean lateral distance between neighbouring (opposite) peaks, the peak-to-peak excursion
  if (np >= 2) {
    double p2p = 0;
    for (size_t k = 1; k < np; ++k) p2p += std::abs(U(k) - U(k - 1));
    a.amplitude = p2p / static_cast<double>(np - 1);
    a.amplitudeHalf = 0.5 * a.amplitude;
  }
  // lambda: mean downhill distance between successive peaks on the same side (one full wave)
  if (np >= 3) {
    double sum = 0;
    for (size_t k = 2; k < np; ++k) sum += std::abs(W(k) - W(k - 2));
    a.wavelength = sum / static_cast<double>(np - 2);
  }
  judgePattern(a, set);
  return a;
}

void judgePattern(ShapeAnalysis& a, const AnalysisParams& set) {
  // a skew is judged only without waves or over enough whole waves
  const bool wavy = a.peaks >= 2;
  a.skewJudged = !wavy || a.waves >= set.skewMinWaves;
  const double turn = a.thetaMax - a.thetaMin;
  if (turn > set.coilTurnDeg * units::deg) a.pattern = "coiling";
  else if (a.skewJudged && std::abs(a.skew) > set.skewThresholdDeg * units::deg) a.pattern = "skewing";
  else if (wavy) a.pattern = "waving";
  else a.pattern = "straight";
}

}  // namespace rootsim
