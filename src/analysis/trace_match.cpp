#include "rootsim/trace_match.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include <Eigen/Dense>

#include "rootsim/units.hpp"
#include "analysis_numbers.hpp"

namespace rootsim {

namespace {

}  // namespace

double arcLengthDistanceMm(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b, double dsMm) {
  if (!(dsMm > 0.0)) throw std::invalid_argument("arcLengthDistanceMm: the step must be > 0");
  const double La = polylineLength(a), Lb = polylineLength(b);
  if (!(La > 0.0) || !(Lb > 0.0)) throw std::invalid_argument("arcLengthDistanceMm: a polyline has no length");
  // points at equal fractions of each length: a traced polyline's noise lengthens it, and its points then
  // run ahead of the root's along it; fractions keep them level
  const int n = std::max(1, static_cast<int>(std::lround(std::max(La, Lb) / dsMm)));
  const Eigen::Matrix3Xd pa = resampleByArcLength(a, La / n), pb = resampleByArcLength(b, Lb / n);
  const int m = static_cast<int>(std::min(pa.cols(), pb.cols()));
  double sum = 0.0;
  for (int i = 0; i < m; ++i) sum += (pa.col(i) - pb.col(i)).squaredNorm();
  return std::sqrt(sum / static_cast<double>(m));
}

double frechetDistanceMm(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b, double dsMm) {
  const Eigen::Matrix3Xd pa = resampleByArcLength(a, dsMm), pb = resampleByArcLength(b, dsMm);
  const int n = static_cast<int>(pa.cols()), m = static_cast<int>(pb.cols());
  // c[j]: the coupling distance ending at (i, j), one row at a time
  std::vector<double> prev(static_cast<std::size_t>(m)), cur(static_cast<std::size_t>(m));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double d = (pa.col(i) - pb.col(j)).norm();
      double reach;
      if (i == 0 && j == 0) reach = d;
      else if (i == 0) reach = std::max(cur[static_cast<std::size_t>(j - 1)], d);
      else if (j == 0) reach = std::max(prev[0], d);
      else
        reach = std::max(std::min({prev[static_cast<std::size_t>(j)], prev[static_cast<std::size_t>(j - 1)],
                                   cur[static_cast<std::size_t>(j - 1)]}),
                         d);
      cur[static_cast<std::size_t>(j)] = reach;
    }
    std::swap(prev, cur);
  }
  return prev[static_cast<std::size_t>(m - 1)];
}

std::vector<Observation> observeBoth(const RootTraits& t, const RootTraits& s, double sp) {
  std::vector<Observation> obs;
  const ShapeAnalysis& a = t.shape;
  const double kPeak = std::max(a.maxKappa * units::mm, 1e-3);  // curvature at a peak [1/mm]
  // a peak's downhill position: the noise moves the lateral maximum along a flat top x = A/2 - k y^2 / 2
  // by as far as the top stays within sigma of its height
  const double peakAlongMm = std::sqrt(2.0 * sp / kPeak);
  const bool waves = a.peaks >= 3;  // at least one full wave: lambda and a skew over whole waves
  {
    Observation o{"skew_deg", "deg", 0, 0, 0, true, ""};
    if (waves) {
      // over whole waves: the mean direction between peaks waves * lambda apart downhill, each end known
      // to sigma across it
      o.trace = a.skew / units::deg;
      o.sim = s.shape.skew / units::deg;
      const double spanMm = std::max(a.waves * a.wavelength / units::mm, 1e-9);
      o.sigma = std::sqrt(2.0) * sp / spanMm / units::deg;
      o.why = "over whole waves: sqrt(2) sigma / (waves * lambda)";
    } else {
      o.trace = t.skewDeg;
      o.sim = s.skewDeg;
      o.sigma = std::sqrt(2.0) * sp / std::max(t.chordMm, 1e-9) / units::deg;
      o.why = "base to tip (no whole wave in the trace): sqrt(2) sigma / chord";
    }
    obs.push_back(o);
  }
  {
    Observation o{"wavelength_mm", "mm", a.wavelength / units::mm, s.shape.wavelength / units::mm, kNaN, waves, ""};
    if (waves) {
      // the mean of (peaks - 2) same-side distances telescopes to its end peaks' positions
      o.sigma = 2.0 * peakAlongMm / std::max(1, a.peaks - 2);
      o.why = "2 sqrt(2 sigma / kappa_peak) / (peaks - 2)";
    } else {
      o.why = "not used: fewer than 3 peaks in the trace";
    }
    obs.push_back(o);
  }
  {
    const bool any = a.peaks >= 2;
    Observation o{"amplitude_mm", "mm", a.amplitude / units::mm, s.shape.amplitude / units::mm, kNaN, any, ""};
    if (any) {
      // each of the (peaks - 1) peak-to-peak distances differs by two lateral positions
      o.sigma = std::sqrt(2.0) * sp / std::sqrt(static_cast<double>(a.peaks - 1));
      o.why = "sqrt(2) sigma / sqrt(peaks - 1)";
    } else {
      o.why = "not used: fewer than 2 peaks in the trace";
    }
    obs.push_back(o);
  }
  // shown beside the others, not fitted: a traced polyline's length, curvature and tangents carry its
  // points' noise amplified by the point spacing (docs/experiments.md)
  obs.push_back(Observation{"tortuosity", "", t.tortuosity, s.tortuosity, kNaN, false,
                            "not used: the length of a noisy polyline is biased by its point spacing"});
  obs.push_back(Observation{"max_kappa_per_mm", "1/mm", a.maxKappa * units::mm, s.shape.maxKappa * units::mm, kNaN, false,
                            "not used: a second derivative of the traced points"});
  obs.push_back(Observation{"theta_range_deg", "deg", (a.thetaMax - a.thetaMin) / units::deg,
                            (s.shape.thetaMax - s.shape.thetaMin) / units::deg, kNaN, false,
                            "not used: a first derivative of the traced points"});
  obs.push_back(Observation{"lateral_peaks", "", double(a.peaks), double(s.shape.peaks), kNaN, false,
                            "not used: a count (its mismatch shows in lambda and A)"});
  obs.push_back(Observation{"length_mm", "mm", t.lengthMm, s.lengthMm, kNaN, false,
                            "not used: the simulated root is grown to the trace's length"});
  return obs;
}

double chiSquare(const std::vector<Observation>& obs) {
  double c = 0.0;
  for (const Observation& o : obs)
    if (o.used) {
      // a simulated root without the waves the trace has: its missing value counts as 0
      const double sim = std::isfinite(o.sim) ? o.sim : 0.0;
      const double r = (sim - o.trace) / o.sigma;
      c += r * r;
    }
  return c;
}

int usedCount(const std::vector<Observation>& obs) {
  return static_cast<int>(std::count_if(obs.begin(), obs.end(), [](const Observation& o) { return o.used; }));
}

FitComponents observableComponents(const std::vector<Observation>& obs) {
  FitComponents c;
  const int m = usedCount(obs);
  c.trace.resize(m);
  c.sigma.resize(m);
  c.sim.resize(m);
  int k = 0;
  for (const Observation& o : obs)
    if (o.used) {
      c.names.push_back(o.name);
      c.trace(k) = o.trace;
      c.sigma(k) = o.sigma;
      c.sim(k) = std::isfinite(o.sim) ? o.sim : 0.0;
      ++k;
    }
  c.cov = c.sigma.cwiseAbs2().asDiagonal();
  return c;
}

namespace {

// the lateral and downhill positions at fractions k / samples (k = 1 .. samples) of a polyline's length
Eigen::VectorXd shapeSamples(const Eigen::Matrix3Xd& p, int samples) {
  const Eigen::Matrix3Xd r = resampleByArcLength(p, polylineLength(p) / samples);
  Eigen::VectorXd v(2 * samples);
  for (int k = 1; k <= samples; ++k) {
    v(2 * (k - 1)) = r(0, k);
    v(2 * (k - 1) + 1) = r(1, k);
  }
  return v;
}

}  // namespace

std::vector<int> distinctPoints(const Eigen::Matrix3Xd& p) {
  std::vector<int> keep;
  for (int i = 0; i < p.cols(); ++i)
    if (keep.empty() || (p.col(i) - p.col(keep.back())).norm() > 0.0) keep.push_back(i);
  return keep;
}

Eigen::Matrix3Xd denoised(const Eigen::Matrix3Xd& p) {
  const int n = static_cast<int>(p.cols());
  Eigen::Matrix3Xd q = p;
  for (int i = 1; i + 1 < n; ++i) {
    const int w = std::min({1, i, n - 1 - i});
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double weight = 0;
    for (int j = -w; j <= w; ++j) {
      const double c = w + 1 - std::abs(j);
      sum += c * p.col(i + j);
      weight += c;
    }
    q.col(i) = sum / weight;
  }
  return q;
}

namespace {

// the polyline without a point that repeats the one before it (a tracer's doubled click: one point, one error)
Eigen::Matrix3Xd withoutRepeats(const Eigen::Matrix3Xd& p) {
  const std::vector<int> keep = distinctPoints(p);
  Eigen::Matrix3Xd q(3, static_cast<Eigen::Index>(keep.size()));
  for (std::size_t i = 0; i < keep.size(); ++i) q.col(static_cast<Eigen::Index>(i)) = p.col(keep[i]);
  return q;
}

}  // namespace

Eigen::MatrixXd shapeNoiseCovariance(const Eigen::Matrix3Xd& clean, double sigmaMm, int samples, int draws) {
  if (!(sigmaMm > 0.0) || samples < 1 || draws < 2)
    throw std::invalid_argument("shapeNoiseCovariance: needs sigma > 0, at least one sample and two draws");
  // the points' noise propagated through the sampling itself: what it does to the noise has no short
  // closed form (a point's error along the root is replaced by the error of the length up to it, a noisy
  // polyline being longer by a random amount; a sample between two points carries less than sigma across;
  // the seed's error moves every sample alike)
  const Eigen::MatrixXd y = noiseDraws(clean, sigmaMm, draws, [&](const Eigen::Matrix3Xd& t) { return shapeSamples(t, samples); });
  const Eigen::MatrixXd centred = y.rowwise() - y.colwise().mean();
  return centred.transpose() * centred / static_cast<double>(draws - 1);
}

Eigen::MatrixXd noiseDraws(const Eigen::Matrix3Xd& clean, double sigmaMm, int draws,
                           const std::function<Eigen::VectorXd(const Eigen::Matrix3Xd&)>& outputs) {
  if (!(sigmaMm > 0.0) || draws < 1) throw std::invalid_argument("noiseDraws: needs sigma > 0 and at least one draw");
  std::mt19937 gen(20260101);  // fixed: the same polyline, the same draws
  std::normal_distribution<double> noise(0.0, sigmaMm);
  Eigen::MatrixXd y;
  Eigen::Matrix3Xd t = clean;
  for (int d = 0; d < draws; ++d) {
    for (int i = 0; i < clean.cols(); ++i) {
      t(0, i) = clean(0, i) + noise(gen);
      t(1, i) = clean(1, i) + noise(gen);
    }
    const Eigen::Vector3d seed = t.col(0);
    t.colwise() -= seed;  // aligned at its own first point, as a trace is
    const Eigen::VectorXd v = outputs(t);
    if (d == 0) y.resize(draws, v.size());
    y.row(d) = v.transpose();
  }
  return y;
}

Eigen::MatrixXd shapeTraceCovariance(const Eigen::Matrix3Xd& trace, double sigmaMm, int samples, int draws) {
  return shapeNoiseCovariance(denoised(withoutRepeats(trace)), sigmaMm, samples, draws);
}

double noiseLengtheningMm(const Eigen::Matrix3Xd& trace, double sigmaMm, int draws) {
  const Eigen::Matrix3Xd clean = denoised(withoutRepeats(trace));
  if (clean.cols() < 2) return 0.0;
  const Eigen::MatrixXd y = noiseDraws(clean, sigmaMm, draws, [](const Eigen::Matrix3Xd& t) {
    return Eigen::VectorXd::Constant(1, polylineLength(t));
  });
  return y.col(0).mean() - polylineLength(clean);
}

namespace {

// the distance along p's base-to-tip chord and the offset across it of each point up to excludeTipMm
// from the tip's end of the chord
void chordCoordinates(const Eigen::Matrix3Xd& p, double excludeTipMm, std::vector<double>& u, std::vector<double>& v) {
  u.clear();
  v.clear();
  if (p.cols() < 2) return;
  const Eigen::Vector2d c = (p.col(p.cols() - 1) - p.col(0)).head<2>();
  const double span = c.norm();
  if (!(span > 0.0)) return;
  const Eigen::Vector2d along = c / span, across(-along.y(), along.x());
  for (Eigen::Index i = 0; i < p.cols(); ++i) {
    const Eigen::Vector2d d = (p.col(i) - p.col(0)).head<2>();
    if (d.dot(along) > span - excludeTipMm) continue;
    u.push_back(d.dot(along));
    v.push_back(d.dot(across));
  }
}

}  // namespace

std::pair<double, double> waveRange(const Eigen::Matrix3Xd& p, double excludeTipMm) {
  std::vector<double> u, v;
  chordCoordinates(p, excludeTipMm, u, v);
  if (u.size() < 8) return {0.0, 0.0};
  std::vector<double> gaps;
  for (std::size_t i = 1; i < u.size(); ++i) gaps.push_back(std::abs(u[i] - u[i - 1]));
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<long>(gaps.size() / 2), gaps.end());
  return {4.0 * gaps[gaps.size() / 2], *std::max_element(u.begin(), u.end()) - *std::min_element(u.begin(), u.end())};
}

WaveFit strongestWave(const Eigen::Matrix3Xd& p, double excludeTipMm, double lambdaMin, double lambdaMax) {
  WaveFit w;
  std::vector<double> u, v;
  chordCoordinates(p, excludeTipMm, u, v);
  const int n = static_cast<int>(u.size());
  if (n < 8 || !(lambdaMin > 0.0) || !(lambdaMax > lambdaMin)) return w;
  const double span = *std::max_element(u.begin(), u.end()) - *std::min_element(u.begin(), u.end());
  if (!(span > 0.0)) return w;
  Eigen::VectorXd vv = Eigen::Map<const Eigen::VectorXd>(v.data(), n);
  // the offsets' residual sum of squares after a line and the sinusoid of frequency f; its amplitude
  auto fitAt = [&](double f, double* amp) {
    Eigen::MatrixXd X(n, 4);
    for (int i = 0; i < n; ++i) {
      const double ph = 2.0 * std::numbers::pi * f * u[static_cast<std::size_t>(i)];
      X(i, 0) = 1.0;
      X(i, 1) = u[static_cast<std::size_t>(i)] / span;
      X(i, 2) = std::cos(ph);
      X(i, 3) = std::sin(ph);
    }
    const Eigen::Vector4d b = X.colPivHouseholderQr().solve(vv);
    if (amp) *amp = std::hypot(b(2), b(3));
    return (vv - X * b).squaredNorm();
  };
  // the grid in frequency, 4 points per 1 / span (the resolution of a periodogram of this span)
  const double fLo = 1.0 / lambdaMax, fHi = 1.0 / lambdaMin, df = 0.25 / span;
  const int m = std::max(3, static_cast<int>(std::ceil((fHi - fLo) / df)) + 1);
  std::vector<double> f(static_cast<std::size_t>(m)), rss(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    f[static_cast<std::size_t>(k)] = fLo + (fHi - fLo) * k / (m - 1);
    rss[static_cast<std::size_t>(k)] = fitAt(f[static_cast<std::size_t>(k)], nullptr);
  }
  const int best = static_cast<int>(std::min_element(rss.begin(), rss.end()) - rss.begin());
  double fBest = f[static_cast<std::size_t>(best)];
  if (best > 0 && best + 1 < m) {
    // the parabola through the best grid point and its neighbours
    const double a = rss[static_cast<std::size_t>(best - 1)], b = rss[static_cast<std::size_t>(best)], c = rss[static_cast<std::size_t>(best + 1)];
    const double den = a - 2.0 * b + c;
    if (den > 0.0) fBest += 0.5 * (a - c) / den * (f[1] - f[0]);
  }
  double amp = 0.0;
  fitAt(fBest, &amp);
  w.wavelengthMm = 1.0 / fBest;
  w.amplitudeMm = amp;
  return w;
}

Eigen::Matrix3Xd tracedLike(const Eigen::Matrix3Xd& root, const Eigen::Matrix3Xd& trace) {
  const int points = static_cast<int>(withoutRepeats(trace).cols());
  if (points < 2) throw std::invalid_argument("tracedLike: the trace has fewer than two distinct points");
  return resampleByArcLength(root, polylineLength(root) / (points - 1));
}

FitComponents shapeComponents(const Eigen::Matrix3Xd& trace, const Eigen::Matrix3Xd& sim, const Eigen::MatrixXd& traceCov,
                              int samples) {
  if (traceCov.rows() != 2 * samples || traceCov.cols() != 2 * samples)
    throw std::invalid_argument("shapeComponents: the trace's covariance is not (2 samples) x (2 samples)");
  FitComponents c;
  c.trace = shapeSamples(trace, samples);
  c.sim = shapeSamples(sim, samples);
  for (int k = 1; k <= samples; ++k) {
    char name[48];
    std::snprintf(name, sizeof name, "lateral_at_%d_pct", 100 * k / samples);
    c.names.push_back(name);
    std::snprintf(name, sizeof name, "downhill_at_%d_pct", 100 * k / samples);
    c.names.push_back(name);
  }
  c.cov = traceCov;
  c.sigma = c.cov.diagonal().cwiseSqrt();
  return c;
}

}  // namespace rootsim
