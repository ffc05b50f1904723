#include "rootsim/traits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rootsim/units.hpp"
#include "rootsim/trace_match.hpp"

namespace rootsim {

namespace {

// the polyline without consecutive repeated points (their indices: trace_match.hpp's distinctPoints)
Eigen::Matrix3Xd distinctPolyline(const Eigen::Matrix3Xd& p) {
  const std::vector<int> keep = distinctPoints(p);
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
  const Eigen::Matrix3Xd q = distinctPolyline(p);
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

namespace {

// median of a copy
double medianOf(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h), v.end());
  if (v.size() % 2) return v[h];
  const double hi = v[h];
  return 0.5 * (hi + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h)));
}

// the LOESS value at arc length t: every point of q within the half-width b of t (in arc length s) with a
// tricube weight, so a point enters and leaves the fit with weight 0 and the curve is smooth in t. Where
// fewer than 4 points lie within b (a gap in the trace, or an end), b grows there to 1.25 times the
// distance to the 4th nearest point. self: the column of q at t exactly (its hat-matrix weight goes to
// *hii), or -1; *width: the half-width used
Eigen::Vector3d loessAt(const Eigen::Matrix3Xd& q, const std::vector<double>& s, double t, double b, int self,
                        double* hii, double* width) {
  const int n = static_cast<int>(s.size());
  auto S = [&](int i) { return s[static_cast<std::size_t>(i)]; };
  int first = static_cast<int>(std::lower_bound(s.begin(), s.end(), t - b) - s.begin());
  int last = static_cast<int>(std::upper_bound(s.begin(), s.end(), t + b) - s.begin()) - 1;
  while (first <= last && !(t - S(first) < b)) ++first;
  while (last >= first && !(S(last) - t < b)) --last;
  if (last - first + 1 < 4) {
    // the 4 nearest points: grow a window from the nearest
    int lo = std::clamp(static_cast<int>(std::lower_bound(s.begin(), s.end(), t) - s.begin()) - 2, 0, n - 4);
    while (lo > 0 && t - S(lo - 1) < S(lo + 3) - t) --lo;
    while (lo + 4 < n && S(lo + 4) - t < t - S(lo)) ++lo;
    b = 1.25 * std::max(std::abs(S(lo) - t), std::abs(S(lo + 3) - t));
    first = lo;
    last = lo + 3;
    while (first > 0 && t - S(first - 1) < b) --first;
    while (last + 1 < n && S(last + 1) - t < b) ++last;
  }
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Zero();  // columns: the coordinates' right-hand sides
  for (int j = first; j <= last; ++j) {
    const double u = (S(j) - t) / b;
    const double c = 1.0 - std::abs(u) * u * u;
    const double w = c * c * c;
    const Eigen::Vector3d basis(1.0, u, u * u);
    M += w * basis * basis.transpose();
    R += w * basis * q.col(j).transpose();
  }
  const Eigen::Matrix3d Minv = M.inverse();
  if (hii) *hii = self >= 0 ? Minv(0, 0) : 0.0;  // the query's own weight (u = 0, w = 1)
  if (width) *width = b;
  return (Minv.row(0) * R).transpose();
}

// the plane the plate coordinates are put on for the runs' own analysis: any tilt gives the same planar
// angles, so a vertical plate
Plane platePlane() {
  Plane plane;
  plane.alpha = 90.0 * units::deg;
  return plane;
}
const PlateFrame& plateFrame() {
  static const PlateFrame frame = PlateFrame::tilted(90.0 * units::deg);
  return frame;
}

// the first peak and the last on its side: the ends of the whole waves between peaks (at least 3)
std::pair<int, int> wholeWaveEnds(const std::vector<int>& peaks) {
  const std::size_t n = peaks.size();
  return {peaks[0], peaks[n - 1 - ((n - 1) % 2)]};
}

// column i's position across an axis phi from downhill (plate coordinates [mm], phi toward +lateral)
double acrossAxis(const Eigen::Matrix3Xd& c, int i, double phi) { return std::cos(phi) * c(0, i) - std::sin(phi) * c(1, i); }

// the runs' shape analysis of the curve's mature part (columns 0 .. last) with a hysteresis of at least
// swingMm, its waves taken about the root's own axis: its direction over whole waves (the skew's), else its
// mature part's chord. A root skewing by theta drifts sideways by tan theta lambda / 2 over each half-wave,
// so across downhill its swings alternate larger and smaller by that much, and the smaller ones of a traced
// skewing root fall to its tracing limit and are lost (docs/experiments.md, "Why a skewing root's trace
// lost peaks"); about its axis every swing is the wave's own. Lambda is then read along the axis and A
// across it; the skew, the tangent angles and the pattern stay the plate's. A root whose axis is downhill
// (no skew) is measured exactly as analyseCentreline measures it
ShapeAnalysis shapeOf(const Eigen::Matrix3Xd& curve, int last, double radiusMm, const AnalysisParams& set, double swingMm,
                      double* axisRad = nullptr, double endSwingMm = 0.0) {
  if (axisRad) *axisRad = 0.0;
  const ShapeAnalysis plain = analyseCentreline(plateMmToLab(curve, plateFrame()), last, platePlane(), set, radiusMm * units::mm,
                                                swingMm * units::mm, endSwingMm * units::mm);
  if (last < 3) return plain;
  // the axis: first peak to the last on its side (the skew over whole waves), else the mature part's chord
  Eigen::Vector3d d = curve.col(last) - curve.col(0);
  if (plain.peakNodes.size() >= 3) {
    const auto [first, lastSame] = wholeWaveEnds(plain.peakNodes);
    d = curve.col(lastSame) - curve.col(first);
  }
  const double phi = std::atan2(d.x(), d.y());
  if (phi == 0.0 || !std::isfinite(phi)) return plain;
  if (axisRad) *axisRad = phi;
  const double c = std::cos(phi), sn = std::sin(phi);
  Eigen::Matrix3Xd along = curve;
  for (int i = 0; i < curve.cols(); ++i) {
    along(0, i) = acrossAxis(curve, i, phi);
    along(1, i) = sn * curve(0, i) + c * curve(1, i);
  }
  ShapeAnalysis a =
      analyseCentreline(plateMmToLab(along, plateFrame()), last, platePlane(), set, radiusMm * units::mm, swingMm * units::mm, endSwingMm * units::mm);
  // the waves about the axis; the skew (over the axis frame's whole waves), the tangent angles and the
  // pattern in the plate's frame, by analyseCentreline's rule
  a.thetaMin = plain.thetaMin;
  a.thetaMax = plain.thetaMax;
  a.maxKappa = plain.maxKappa;
  if (a.peakNodes.size() >= 3) {
    const auto [first, lastSame] = wholeWaveEnds(a.peakNodes);
    const Eigen::Vector3d span = curve.col(lastSame) - curve.col(first);
    a.skew = planarAngle(platePlane(), plateMmToLab(span, plateFrame()).col(0));
  } else {
    const Eigen::Matrix3Xd lab = plateMmToLab(curve, plateFrame());
    a.skew = planarAngle(platePlane(), lab.col(last) - lab.col(0));
  }
  judgePattern(a, set);
  return a;
}

// a wave train (docs/experiments.md, "Noise"): a tilted plate's wave repeats, so its peaks are called a
// wave only when at least kTrainHalfWaves successive half-waves (downhill distances between neighbouring
// opposite peaks) lie within kTrainFactor of each other. Two half-waves merged into one where an excursion
// fell under the limit are 3 times as long as their neighbours; a meander's spacings are anything
struct WaveTrain {
  bool regular = false;
  std::string spacings;  // the half-wave spacings [mm] and their spread, for the note
};
constexpr int kTrainHalfWaves = 3;
constexpr double kTrainFactor = 2.0;
WaveTrain waveTrainOf(const Eigen::Matrix3Xd& curve, const std::vector<int>& peaks) {
  WaveTrain w;
  std::vector<double> d;
  for (std::size_t k = 1; k < peaks.size(); ++k) d.push_back(std::abs(curve(1, peaks[k]) - curve(1, peaks[k - 1])));
  const int n = static_cast<int>(d.size());
  for (int a = 0; a + kTrainHalfWaves <= n && !w.regular; ++a) {
    const auto [lo, hi] = std::minmax_element(d.begin() + a, d.begin() + a + kTrainHalfWaves);
    w.regular = *hi <= kTrainFactor * *lo;
  }
  char b[120];
  if (n < kTrainHalfWaves) {
    std::string list;
    for (double x : d) {
      std::snprintf(b, sizeof b, "%s%.3g", list.empty() ? "" : " and ", x);
      list += b;
    }
    w.spacings = list + " mm (a wave needs " + std::to_string(kTrainHalfWaves) + " successive within " + std::to_string(static_cast<int>(kTrainFactor)) + "x)";
  } else {
    const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
    std::snprintf(b, sizeof b, "%.3g to %.3g mm (no %d successive within %gx)", *lo, *hi, kTrainHalfWaves, kTrainFactor);
    w.spacings = b;
  }
  return w;
}

// the bend of the curve's mature part (columns 0 .. last, in the plate's plane): its bow, the largest
// distance of a point from the chord between its ends, and its turning angle, from the direction of its
// first third (the chord across it) to that of its last third, signed as theta. Chords over a third of
// the length: a smoothed curve's residual noise turns a tangent, not a chord that long
void bendOf(const Eigen::Matrix3Xd& curve, int last, RootTraits& t) {
  if (last < 2) return;
  const Eigen::Vector2d a = curve.col(0).head<2>(), b = curve.col(last).head<2>();
  const Eigen::Vector2d c = b - a;
  if (!(c.norm() > 0.0)) return;
  const Eigen::Vector2d n(-c.y() / c.norm(), c.x() / c.norm());
  for (int i = 1; i < last; ++i) t.bowMm = std::max(t.bowMm, std::abs((curve.col(i).head<2>() - a).dot(n)));
  const Eigen::Matrix3Xd mature = curve.leftCols(last + 1);
  const std::vector<double> s = arcLengths(mature);
  const double L = s.back();
  const Eigen::Vector3d first = pointAt(mature, s, L / 3.0) - mature.col(0);
  const Eigen::Vector3d end = mature.col(last) - pointAt(mature, s, 2.0 * L / 3.0);
  const Plane plane = platePlane();
  const double turn = planarAngle(plane, plateMmToLab(end, plateFrame()).col(0)) - planarAngle(plane, plateMmToLab(first, plateFrame()).col(0));
  t.bendDeg = std::remainder(turn, 2.0 * std::numbers::pi) / units::deg;
}

// the measurement shared by runs and traces: the raw trace q (distinct points) for length, chord,
// tortuosity and base-to-tip skew; the curve for the shape analysis and the field's traits
RootTraits measure(const Eigen::Matrix3Xd& q, const Eigen::Matrix3Xd& curve, double dsMm, double excludeTipMm,
                   double radiusMm, const AnalysisParams& set, double noiseThresholdMm, double endThresholdMm = 0.0) {
  RootTraits t;
  t.lengthMm = polylineLength(q);
  const Eigen::Vector3d chord = q.col(q.cols() - 1) - q.col(0);
  // on the plate: the chord's in-plane part (a trace's height is its own business)
  const Eigen::Vector2d c2(chord.x(), chord.y());
  t.chordMm = c2.norm();
  t.tortuosity = t.chordMm > 0.0 ? t.lengthMm / t.chordMm : std::numeric_limits<double>::infinity();
  // the skew angle by the runs' own planarAngle
  const Plane plane = platePlane();
  t.skewDeg = planarAngle(plane, plateMmToLab(chord, plateFrame()).col(0)) / units::deg;
  // the shape analysis on the mature part of the curve
  t.dsMm = dsMm;
  t.curveMm = curve;
  t.curveLengthMm = polylineLength(curve);
  const double matureMm = t.curveLengthMm - std::max(0.0, excludeTipMm);
  const std::vector<double> s = arcLengths(curve);
  int last = 0;
  while (last + 1 < static_cast<int>(s.size()) && s[static_cast<std::size_t>(last + 1)] <= matureMm + 1e-12 * t.curveLengthMm) ++last;
  t.matureLast = last;
  t.noiseThresholdMm = noiseThresholdMm;
  t.shape = shapeOf(curve, last, radiusMm, set, noiseThresholdMm, nullptr, endThresholdMm);
  // the field's traits (Grabov et al. 2005): the tip's displacement over the curve's length
  const Eigen::Vector3d d = curve.col(curve.cols() - 1) - curve.col(0);
  if (t.curveLengthMm > 0.0) {
    t.straightness = Eigen::Vector2d(d.x(), d.y()).norm() / t.curveLengthMm;
    t.hgi = d.x() / t.curveLengthMm;
    t.vgi = d.y() / t.curveLengthMm;
  }
  t.thetaTipDeg = planarAngle(plane, plateMmToLab(curve.col(curve.cols() - 1) - curve.col(curve.cols() - 2), plateFrame()).col(0)) / units::deg;
  bendOf(curve, last, t);
  // why the waves are not numbers (no commas: a CSV cell); a trace's reasons are traceTraits'
  if (t.shape.peaks < 3) {
    char b[200];
    if (t.shape.peaks < 2)
      std::snprintf(b, sizeof b, "no lateral excursion above the hysteresis %g R = %.3g mm", set.waveMinAmplitude,
                    t.shape.hysteresis / units::mm);
    else
      std::snprintf(b, sizeof b, "one excursion (2 peaks): no wavelength");
    t.wavesNote = b;
  }
  return t;
}

}  // namespace

TraceNoise estimateTraceNoise(const Eigen::Matrix3Xd& p) {
  const Eigen::Matrix3Xd q = distinctPolyline(p);
  TraceNoise out;
  const int n = static_cast<int>(q.cols());
  std::vector<double> gaps;
  for (int i = 1; i < n; ++i) gaps.push_back((q.col(i) - q.col(i - 1)).norm());
  out.spacing = medianOf(gaps);
  // at least 5 residuals: a sigma from fewer is a guess
  constexpr int kMinPoints = 9;
  if (n < kMinPoints) return out;
  // r[i - 2]: point i against the cubic through i-2, i-1, i+1, i+2, in the frame of its stencil's chord
  // (i-2 to i+2): the neighbours' positions along the chord are the abscissae, their offsets across it
  // the ordinates, point i the origin. A noisy polyline's own arc length would run ahead where its noise
  // zigzags (and reorder points whose jitter is half their spacing); the chord's frame does neither.
  std::vector<double> r(static_cast<std::size_t>(n - 4), 0.0);
  std::vector<char> valid(r.size(), 0);
  const double minGap = 0.05 * out.spacing;
  for (int i = 2; i + 2 < n; ++i) {
    const Eigen::Vector2d chord = q.col(i + 2).head<2>() - q.col(i - 2).head<2>();
    if (chord.norm() == 0.0) continue;
    const Eigen::Vector2d tan = chord / chord.norm(), nrm(-tan.y(), tan.x());
    const int idx[4] = {i - 2, i - 1, i + 1, i + 2};
    double t[4], v[4];
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector2d d = q.col(idx[a]).head<2>() - q.col(i).head<2>();
      t[a] = d.dot(tan);
      v[a] = d.dot(nrm);
    }
    bool distinct = true;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) distinct = distinct && std::abs(t[a] - t[b]) > minGap;
    if (!distinct) continue;
    double pred = 0.0, w2 = 0.0;
    for (int a = 0; a < 4; ++a) {
      double w = 1.0;
      for (int b = 0; b < 4; ++b)
        if (b != a) w *= (0.0 - t[b]) / (t[a] - t[b]);
      pred += w * v[a];
      w2 += w * w;
    }
    r[static_cast<std::size_t>(i - 2)] = -pred / std::sqrt(1.0 + w2);
    valid[static_cast<std::size_t>(i - 2)] = 1;
  }
  std::vector<double> absR;
  double rms = 0.0;
  for (std::size_t k = 0; k < r.size(); ++k)
    if (valid[k]) {
      absR.push_back(std::abs(r[k]));
      rms += r[k] * r[k];
    }
  if (absR.empty()) return out;
  rms = std::sqrt(rms / static_cast<double>(absR.size()));
  // a robust start: 1.4826 median |r| (a normal's sigma), or the RMS where more than half the residuals
  // are exactly 0 (a whole-pixel trace of a root along a pixel axis)
  const double mad = 1.4826 * medianOf(absR);
  double sig = mad > 0.0 ? mad : rms;
  // then the RMS of the residuals clipped at 3 sigma, iterated: a point outside the clip (a tracer's
  // snap to an edge) also leaves out the residuals of the neighbours whose cubic it enters; a normal's
  // RMS inside +-3 sigma is 0.98658 of its sigma
  constexpr double kClip = 3.0, kClipRms = 0.98658;  // and a normal's RMS inside +-3 sigma
  int used = 0;
  std::vector<char> outlier(static_cast<std::size_t>(n), 0);
  for (int it = 0; it < 100 && sig > 0.0; ++it) {
    std::fill(outlier.begin(), outlier.end(), 0);
    for (std::size_t k = 0; k < r.size(); ++k)
      if (valid[k] && std::abs(r[k]) > kClip * sig) outlier[k + 2] = 1;
    double sum = 0.0;
    int m = 0;
    for (std::size_t k = 0; k < r.size(); ++k) {
      if (!valid[k]) continue;
      bool clean = true;
      for (std::size_t j = k; j <= k + 4; ++j) clean = clean && !outlier[j];
      if (!clean) continue;
      sum += r[k] * r[k];
      ++m;
    }
    const double next = m > 0 ? std::sqrt(sum / m) / kClipRms : 0.0;
    used = m;
    if (std::abs(next - sig) <= 1e-12 * sig) {
      sig = next;
      break;
    }
    sig = next;
  }
  out.sigma = sig;
  out.residuals = used;
  for (int i = 0; i < n; ++i)
    if (outlier[static_cast<std::size_t>(i)]) out.outliers.push_back(i);
  return out;
}

namespace {

// the LOESS half-width by GCV over the points of q at arc-length parameters s: candidates from 2.5 to 30
// median point spacings h, at most a sixth of the length (the first candidate always). GCV with each
// degree of freedom counted 1.4 times, n RSS / (n - 1.4 tr H)^2 (Kim & Gu, J. R. Stat. Soc. B 66, 337,
// 2004): plain GCV picks near-interpolating windows now and then (on a noisy straight line, 2.5 spacings
// with tr H / n = 0.7)
double gcvHalfWidth(const Eigen::Matrix3Xd& q, const std::vector<double>& s, double h, double* leverage = nullptr) {
  static constexpr double kSpacings[] = {2.5, 3, 3.5, 4, 5, 6, 7, 8, 10, 12, 15, 18, 22, 26, 30};
  const int n = static_cast<int>(q.cols());
  double bestGcv = std::numeric_limits<double>::infinity(), best = kSpacings[0] * h;
  for (double c : kSpacings) {
    const double b = c * h;
    if (c > kSpacings[0] && b > s.back() / 6.0) break;
    double rss = 0.0, trace = 0.0;
    for (int i = 0; i < n; ++i) {
      double hii = 0.0;
      const Eigen::Vector3d z = loessAt(q, s, s[static_cast<std::size_t>(i)], b, i, &hii, nullptr);
      rss += (q.col(i) - z).squaredNorm();
      trace += hii;
    }
    constexpr double kGamma = 1.4;
    const double dof = n - kGamma * trace;
    const double gcv = dof > 0.0 ? n * rss / (dof * dof) : std::numeric_limits<double>::infinity();
    if (gcv < bestGcv) {
      bestGcv = gcv;
      best = b;
      if (leverage) *leverage = trace / n;
    }
  }
  return best;
}

// the LOESS curve of q (parameters s) with half-width b at the parameters at; widths: each one used
Eigen::Matrix3Xd loessCurve(const Eigen::Matrix3Xd& q, const std::vector<double>& s, double b, const std::vector<double>& at,
                            std::vector<double>* widths) {
  Eigen::Matrix3Xd z(3, static_cast<Eigen::Index>(at.size()));
  for (std::size_t i = 0; i < at.size(); ++i) {
    double used = 0.0;
    z.col(static_cast<Eigen::Index>(i)) = loessAt(q, s, at[i], b, -1, nullptr, &used);
    if (widths) widths->push_back(used);
  }
  return z;
}

}  // namespace

TraceSmoothing smoothTrace(const Eigen::Matrix3Xd& p, double ds) {
  const Eigen::Matrix3Xd q = distinctPolyline(p);
  if (q.cols() < 2) throw std::invalid_argument("smoothTrace: the polyline has no length");
  const int n = static_cast<int>(q.cols());
  TraceSmoothing out;
  constexpr int kMinPoints = 7;
  if (n < kMinPoints) {
    out.points = ds > 0.0 ? resampleByArcLength(q, ds) : q;
    return out;
  }
  std::vector<double> gaps;
  for (int i = 1; i < n; ++i) gaps.push_back((q.col(i) - q.col(i - 1)).norm());
  const double h = medianOf(gaps);
  // two passes: the noisy polyline's arc length runs ahead where its noise zigzags, so the second pass
  // smooths against the arc length of the first pass's curve (a parameter the noise barely moves)
  const std::vector<double> s1 = arcLengths(q);
  const Eigen::Matrix3Xd z1 = loessCurve(q, s1, gcvHalfWidth(q, s1, h), s1, nullptr);
  std::vector<double> s2 = arcLengths(z1);
  for (std::size_t i = 1; i < s2.size(); ++i) s2[i] = std::max(s2[i], s2[i - 1] + 1e-12 * (1.0 + s2.back()));
  const double b = gcvHalfWidth(q, s2, h, &out.leverage);
  // the smoothed curve at the query arc lengths
  const double L = s2.back();
  std::vector<double> at;
  if (ds > 0.0) {
    const int m = std::max(1, static_cast<int>(std::lround(L / ds)));
    for (int i = 0; i <= m; ++i) at.push_back(i == m ? L : L * i / m);
  } else {
    at = s2;
  }
  std::vector<double> widths;
  out.points = loessCurve(q, s2, b, at, &widths);
  out.halfWidth = b;
  return out;
}

double tracingLimitMm(double smoothedSigmaMm, double radiusMm) {
  return kPlacementDiameters * 2.0 * radiusMm + (std::isfinite(smoothedSigmaMm) ? kNoisePeakK * std::sqrt(2.0) * smoothedSigmaMm : 0.0);
}

namespace {

// a run's nodes q (distinct points) measured as they are, at a run's resolution dsMm, the ends of its
// wave train at endThresholdMm (0: its hysteresis)
RootTraits measureAsIs(const Eigen::Matrix3Xd& q, double dsMm, double excludeTipMm, double radiusMm, const AnalysisParams& set,
                       double endThresholdMm) {
  RootTraits t = measure(q, dsMm > 0.0 ? resampleByArcLength(q, dsMm) : q, dsMm, excludeTipMm, radiusMm, set, 0.0, endThresholdMm);
  t.noiseMm = estimateTraceNoise(q).sigma;
  return t;
}

}  // namespace

RootTraits rootTraits(const Eigen::Matrix3Xd& plateMm, double dsMm, double excludeTipMm, double radiusMm,
                      const AnalysisParams& set) {
  const Eigen::Matrix3Xd q = distinctPolyline(plateMm);
  if (q.cols() < 2) throw std::invalid_argument("rootTraits: a root needs at least two distinct points");
  return measureAsIs(q, dsMm, excludeTipMm, radiusMm, set, 0.0);
}

RootTraits rootTraitsAs(const Eigen::Matrix3Xd& plateMm, const RootTraits& as, double excludeTipMm, double radiusMm,
                        const AnalysisParams& set) {
  const Eigen::Matrix3Xd q = distinctPolyline(plateMm);
  if (q.cols() < 2) throw std::invalid_argument("rootTraitsAs: a root needs at least two distinct points");
  // the ends of the wave train at the trace's tracing limit, its inner swings at the run's own hysteresis
  if (!(as.smoothingMm > 0.0)) return measureAsIs(q, as.dsMm, excludeTipMm, radiusMm, set, as.noiseThresholdMm);
  // the trace's two passes at its width: the second against the arc length of the first pass's curve,
  // which a flattened wave shortens (a window as many of its millimetres spans more of the root)
  const double b = as.smoothingMm;
  const std::vector<double> s1 = arcLengths(q);
  std::vector<double> s = arcLengths(loessCurve(q, s1, b, s1, nullptr));
  for (std::size_t i = 1; i < s.size(); ++i) s[i] = std::max(s[i], s[i - 1] + 1e-12 * (1.0 + s.back()));
  std::vector<double> at;
  if (as.dsMm > 0.0) {
    const double L = s.back();
    const int m = std::max(1, static_cast<int>(std::lround(L / as.dsMm)));
    for (int i = 0; i <= m; ++i) at.push_back(i == m ? L : L * i / m);
  } else {
    at = s;
  }
  RootTraits t = measure(q, loessCurve(q, s, b, at, nullptr), as.dsMm, excludeTipMm, radiusMm, set, 0.0, as.noiseThresholdMm);
  t.noiseMm = estimateTraceNoise(q).sigma;
  t.smoothingMm = as.smoothingMm;
  return t;
}

namespace {

// a root that is not waving, coiling or skewing but turned once (docs/experiments.md, "One bend"): at most
// one excursion above the tracing limit (one half-wave), its bow beyond the limit and its turning beyond
// both the skew threshold and the turning the limit alone can give the chords of its thirds,
// 2 atan(3 limit / L). A straight root traced with a root diameter of drift bows by up to the limit but
// does not turn: its thirds' chords are too long for the drift to tilt
void markBend(RootTraits& t, int excursions, double limitMm, const AnalysisParams& set) {
  if (t.shape.pattern != "straight" || excursions > 1 || !(t.bowMm > limitMm)) return;
  const std::vector<double> s = arcLengths(t.curveMm.leftCols(t.matureLast + 1));
  const double bendLimitDeg = std::max(set.skewThresholdDeg, 2.0 * std::atan(3.0 * limitMm / s.back()) / units::deg);
  if (!(std::abs(t.bendDeg) > bendLimitDeg)) return;
  t.shape.pattern = "curved";
  char b[200];
  std::snprintf(b, sizeof b, "; curved: bow %.3g mm beyond the tracing limit %.3g mm and turning %.3g deg beyond %.3g deg", t.bowMm, limitMm,
                t.bendDeg, bendLimitDeg);
  t.wavesNote += b;
}

}  // namespace

RootTraits traceTraits(const Eigen::Matrix3Xd& plateMm, double dsMm, double excludeTipMm, double radiusMm,
                       const AnalysisParams& set) {
  const Eigen::Matrix3Xd q = distinctPolyline(plateMm);
  if (q.cols() < 2) throw std::invalid_argument("traceTraits: a root needs at least two distinct points");
  const TraceNoise noise = estimateTraceNoise(q);
  // the points outside the noise's clip (a tracer's snaps to an edge) are left out of the smoothing
  Eigen::Matrix3Xd kept(3, q.cols() - static_cast<Eigen::Index>(noise.outliers.size()));
  for (int i = 0, k = 0, o = 0; i < q.cols(); ++i) {
    if (o < static_cast<int>(noise.outliers.size()) && noise.outliers[static_cast<std::size_t>(o)] == i) {
      ++o;
      continue;
    }
    kept.col(k++) = q.col(i);
  }
  const TraceSmoothing sm = smoothTrace(kept, dsMm);
  const double limit = tracingLimitMm(noise.sigma * std::sqrt(sm.leverage), radiusMm);
  RootTraits t = measure(q, sm.points, dsMm, excludeTipMm, radiusMm, set, limit);
  t.noiseMm = noise.sigma;
  t.smoothingMm = sm.halfWidth;
  if (t.shape.peaks >= 2) {
    // peaks above the limit, but a wave only when they repeat as a tilted plate's wave does
    const WaveTrain train = waveTrainOf(sm.points, t.shape.peakNodes);
    if (train.regular) return t;
    ShapeAnalysis none = shapeOf(sm.points, t.matureLast, radiusMm, set, std::numeric_limits<double>::infinity());
    none.hysteresis = t.shape.hysteresis;
    char b[320];
    std::snprintf(b, sizeof b, "not a wave train: %d excursion%s of %.3g mm above the tracing limit %.3g mm with half-wave spacing%s %s",
                  t.shape.peaks - 1, t.shape.peaks > 2 ? "s" : "", t.shape.amplitude / units::mm, limit, t.shape.peaks > 2 ? "s" : "",
                  train.spacings.c_str());
    const int excursions = t.shape.peaks - 1;
    t.shape = none;
    t.wavesNote = b;
    markBend(t, excursions, limit, set);
    return t;
  }
  {
    // what the curve does under the limit: its excursions above the white noise alone
    const double noiseSwing = std::isfinite(noise.sigma) ? kNoisePeakK * noise.sigma : 0.0;
    double axis = 0.0;  // the excursions' axis: their sizes across it
    const ShapeAnalysis under = shapeOf(sm.points, t.matureLast, radiusMm, set, noiseSwing, &axis);
    char b[320];
    if (under.peaks >= 2) {
      double top = 0.0;
      for (std::size_t k = 1; k < under.peakNodes.size(); ++k)
        top = std::max(top, std::abs(acrossAxis(sm.points, under.peakNodes[k], axis) - acrossAxis(sm.points, under.peakNodes[k - 1], axis)));
      char why[96];
      if (std::isfinite(noise.sigma))
        std::snprintf(why, sizeof why, "one root diameter %.3g mm + %g sqrt(2) sigma_s %.2g mm", 2.0 * kPlacementDiameters * radiusMm, kNoisePeakK,
                      limit - 2.0 * kPlacementDiameters * radiusMm);
      else
        std::snprintf(why, sizeof why, "one root diameter %.3g mm; sigma unknown", 2.0 * kPlacementDiameters * radiusMm);
      std::snprintf(b, sizeof b, "below the tracing limit %.3g mm (%s): fewer than 2 peaks beyond it; %d excursion%s of %.3g mm (largest %.3g mm) above the noise",
                    limit, why, under.peaks - 1, under.peaks > 2 ? "s" : "", under.amplitude / units::mm, top);
    } else if (std::isfinite(noise.sigma) && noiseSwing > set.waveMinAmplitude * radiusMm) {
      std::snprintf(b, sizeof b, "below the noise: no lateral excursion above %g sigma = %.3g mm", kNoisePeakK, noiseSwing);
    } else {
      std::snprintf(b, sizeof b, "no lateral excursion above the hysteresis %g R = %.3g mm", set.waveMinAmplitude,
                    under.hysteresis / units::mm);
    }
    t.wavesNote = b;
  }
  markBend(t, 0, limit, set);
  return t;
}

double insertionAngleDeg(const Eigen::Matrix3Xd& parentMm, const Eigen::Matrix3Xd& lateralMm, double spanMm) {
  const Eigen::Matrix3Xd par = distinctPolyline(parentMm), lat = distinctPolyline(lateralMm);
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
