// phenotyping traits of a centreline (src/analysis/traits.cpp): resampling, length, tortuosity, the skew angle's
// sign against the runs' theta, the insertion angle, the run observables of a trace equal to those
// analyseShape measures on the same shape; a trace's noise estimate, its smoothing, straightness, HGI and
// VGI, and the noise-aware measurement of roots degraded as a tracer degrades them
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "physics_support.hpp"
#include "tracer_model.hpp"
#include "rootsim/analysis.hpp"
#include "rootsim/rod.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/trace_match.hpp"
#include "rootsim/traits.hpp"
#include "rootsim/units.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
using rootsim::test::relError;
using rootsim::test::report;

namespace {
constexpr double pi = std::numbers::pi;

// a planar curve in plate coordinates [mm]: (lateral u(p), downhill w(p), 0), p in [0, 1], n + 1 points
template <class F>
Eigen::Matrix3Xd plateCurve(int n, F f) {
  Eigen::Matrix3Xd c(3, n + 1);
  for (int i = 0; i <= n; ++i) {
    double u = 0, w = 0;
    f(static_cast<double>(i) / n, u, w);
    c.col(i) = Eigen::Vector3d(u, w, 0.0);
  }
  return c;
}
}  // namespace

TEST_CASE("resampling keeps the ends, spaces the points equally and drops repeated points") {
  Eigen::Matrix3Xd p(3, 4);
  p << 0, 0, 3, 3,   //
      0, 0, 4, 4,    //
      0, 0, 0, 0;    // a 5 mm segment with its two ends doubled
  const Eigen::Matrix3Xd r = resampleByArcLength(p, 0.5);
  REQUIRE(r.cols() == 11);
  for (int i = 1; i < r.cols(); ++i) CHECK((r.col(i) - r.col(i - 1)).norm() == doctest::Approx(0.5).epsilon(1e-12));
  CHECK(r.col(10).isApprox(Eigen::Vector3d(3, 4, 0)));
  CHECK(polylineLength(r) == doctest::Approx(5.0).epsilon(1e-14));
  CHECK_THROWS(resampleByArcLength(p, 0.0));
  CHECK_THROWS(resampleByArcLength(Eigen::Matrix3Xd::Zero(3, 3), 0.1));
}

TEST_CASE("length and chord and tortuosity of a half circle - a straight root has tortuosity 1") {
  const double R = 2.0;  // [mm]
  const Eigen::Matrix3Xd half = plateCurve(2000, [&](double p, double& u, double& w) {
    u = R - R * std::cos(pi * p);
    w = R * std::sin(pi * p);
  });
  const RootTraits t = rootTraits(half, 0.05, 0.0, 0.1, AnalysisParams{});
  CHECK(t.lengthMm == doctest::Approx(pi * R).epsilon(1e-6));
  CHECK(t.chordMm == doctest::Approx(2 * R).epsilon(1e-12));
  CHECK(t.tortuosity == doctest::Approx(pi / 2).epsilon(1e-6));
  const Eigen::Matrix3Xd line = plateCurve(7, [](double p, double& u, double& w) { u = 0; w = 10 * p; });
  const RootTraits s = rootTraits(line, 0.05, 0.0, 0.1, AnalysisParams{});
  CHECK(s.tortuosity == doctest::Approx(1.0).epsilon(1e-14));
  ROOTSIM_CHECK_CLOSE(s.skewDeg, 0.0, kRoundoff);
  CHECK(s.shape.pattern == "straight");
  CHECK_THROWS(rootTraits(Eigen::Matrix3Xd::Zero(3, 2), 0.05, 0.0, 0.1, AnalysisParams{}));
}

TEST_CASE("the skew angle has the sign of the runs' theta on a tilted plate") {
  // a rod on the 40 degree plate heading downhill and 10 degrees towards +lateral: its planar angle by the
  // runs' code, and the trace of the same points in plate coordinates
  Plane pl;
  pl.alpha = 40 * units::deg;
  const PlateFrame f = pl.frame();
  const double a = 10 * units::deg;
  const Vec3 dir = std::cos(a) * f.downhill + std::sin(a) * f.lateral;
  const double theta = planarAngle(pl, dir);
  Eigen::Matrix3Xd trace(3, 2);
  trace.col(0) = f.coords(Vec3::Zero()) / units::mm;
  trace.col(1) = f.coords(5 * units::mm * dir) / units::mm;
  const RootTraits t = rootTraits(trace, 0.0, 0.0, 0.1, AnalysisParams{});
  ROOTSIM_CHECK_CLOSE(std::abs(theta), a, kRoundoff);
  CHECK(t.skewDeg == doctest::Approx(theta / units::deg).epsilon(1e-12));
}

TEST_CASE("a traced sine gives the lambda, A and pattern analyseShape gives the same shape as a run") {
  // 6 waves of wavelength 2.5 mm and half excursion 0.3 mm, 80 points a wave, on a 40 degree plate
  const double lam = 2.5, amp = 0.3;
  const int n = 480;
  const Eigen::Matrix3Xd trace = plateCurve(n, [&](double p, double& u, double& w) {
    w = 6 * lam * p;
    u = amp * std::sin(2 * pi * w / lam);
  });
  Model m;
  m.growth.enabled = false;
  m.env.plane.alpha = 40 * units::deg;
  RodState s;
  s.resize(n);
  s.x = plateMmToLab(trace, m.env.plane.frame());
  const ShapeAnalysis run = analyseShape(m, s);
  const RootTraits t = rootTraits(trace, 0.0, 0.0, m.rod.radius / units::mm, m.analysis);
  CHECK(run.pattern == "waving");
  CHECK(t.shape.pattern == run.pattern);
  CHECK(t.shape.peaks == run.peaks);
  CHECK(t.shape.wavelength == doctest::Approx(run.wavelength).epsilon(1e-12));
  CHECK(t.shape.amplitude == doctest::Approx(run.amplitude).epsilon(1e-12));
  CHECK(t.shape.skew == doctest::Approx(run.skew).scale(1.0).epsilon(1e-12));
  CHECK(t.shape.maxKappa == doctest::Approx(run.maxKappa).epsilon(1e-9));
  CHECK(t.shape.wavelength == doctest::Approx(lam * units::mm).epsilon(0.01));
  CHECK(t.shape.amplitude == doctest::Approx(2 * amp * units::mm).epsilon(0.01));
  // the growth zone left out: the mature part ends at the last point at least 2.5 mm of arc length
  // before the tip, and the peaks of that stretch are not counted
  const RootTraits z = rootTraits(trace, 0.0, lam, m.rod.radius / units::mm, m.analysis);
  const int last = z.matureLast;
  CHECK(polylineLength(trace.rightCols(n + 1 - last)) >= lam);
  CHECK(polylineLength(trace.rightCols(n - last)) < lam);
  CHECK(z.shape.peaks < run.peaks);
  CHECK(z.shape.peaks >= run.peaks - 2);
}

TEST_CASE("the insertion angle of a lateral on its parent") {
  const Eigen::Matrix3Xd parent = plateCurve(100, [](double p, double& u, double& w) { u = 0; w = 20 * p; });
  for (double ang : {30.0, 60.0, 90.0, 120.0}) {
    const double a = ang * units::deg;
    // a lateral from the parent's point at 8 mm, heading 'ang' from the parent's direction (downhill)
    const Eigen::Matrix3Xd lat = plateCurve(50, [&](double p, double& u, double& w) {
      u = 5 * p * std::sin(a);
      w = 8 + 5 * p * std::cos(a);
    });
    CHECK(insertionAngleDeg(parent, lat, 1.0) == doctest::Approx(ang).epsilon(1e-9));
  }
}

// ---- noise-aware measurement of traced roots (docs/experiments.md, "Noise") ----

namespace {

using rootsim::test::TracerModel;
using rootsim::test::TracerRng;
using rootsim::test::traceLikeTracer;
using Rng = TracerRng;

// the validation shapes (docs/experiments.md, "Validation on roots degraded as a tracer degrades them"):
// 20 mm of root, straight 3 degrees off downhill, or waving with peak-to-peak excursion A (the runs' A)
// and wavelength lambda; 4000 points
constexpr double kRootMm = 20.0;
Eigen::Matrix3Xd straightRoot() {
  const double a = 3.0 * pi / 180.0;
  return plateCurve(4000, [&](double p, double& u, double& w) { u = kRootMm * p * std::sin(a); w = kRootMm * p * std::cos(a); });
}
Eigen::Matrix3Xd wavingRoot(double ampMm, double lambdaMm) {
  return plateCurve(4000, [&](double p, double& u, double& w) {
    w = kRootMm * p;
    u = 0.5 * ampMm * std::sin(2.0 * pi * w / lambdaMm);
  });
}

// the placement offset's correlation length drawn per seed in [0.5, 2] mm: a tracer's drift is not one
// number
double corrLengthOf(unsigned long long seed) {
  Rng r{seed * 7919 + 3};
  return 0.5 + 1.5 * r.uniform();
}

// the validation plate's scan (bench/fit_groups.sh's tracing): 20 px/mm, a point every 4 px, whole pixels,
// 0.5 px of jitter, and no drift across the root's width, whose correlated error the wave's sigma does not hold
TracerModel plateScan(unsigned long long seed) {
  TracerModel tr;
  tr.pxPerMm = 20;
  tr.jitterPx = 0.5;
  tr.seed = seed;
  tr.radiusMm = 0.0;
  return tr;
}

RootTraits traceAndMeasure(const Eigen::Matrix3Xd& truth, double pxPerMm, double jitterPx, unsigned long long seed) {
  TracerModel tr;
  tr.pxPerMm = pxPerMm;
  tr.jitterPx = jitterPx;
  tr.seed = seed;
  tr.offsetCorrMm = corrLengthOf(seed);
  return traceTraits(traceLikeTracer(truth, tr), 0.05, 0.0, 0.1, AnalysisParams{});
}

}  // namespace

TEST_CASE("the noise estimate of a clean curve is nil, and snapping steps do not inflate it") {
  // a noise-free half circle sampled every 0.2 mm: the cubic through the neighbours follows the bend
  const Eigen::Matrix3Xd arc = plateCurve(80, [](double p, double& u, double& w) {
    u = 5.0 - 5.0 * std::cos(pi * p);
    w = 5.0 * std::sin(pi * p);
  });
  const TraceNoise clean = estimateTraceNoise(arc);
  CHECK(clean.sigma < 1e-4);
  CHECK(clean.spacing == doctest::Approx(5.0 * pi / 80).epsilon(1e-3));
  // Gaussian noise of 0.02 mm on a straight line, with one point in 10 thrown 0.2 mm sideways
  Rng rng{42};
  Eigen::Matrix3Xd line(3, 2001);
  for (int i = 0; i <= 2000; ++i) line.col(i) = Eigen::Vector3d(0.02 * rng.normal() + (i % 10 == 5 ? 0.2 : 0.0), 0.1 * i, 0.0);
  const TraceNoise noisy = estimateTraceNoise(line);
  const double err = relError(noisy.sigma, 0.02);
  report("sigma of 0.02 mm noise with 10 % snaps", noisy.sigma, 0.02, err);
  CHECK(err < 0.08);
  // fewer than 9 points (5 residuals): no estimate
  CHECK(std::isnan(estimateTraceNoise(line.leftCols(8)).sigma));
  CHECK(std::isfinite(estimateTraceNoise(line.leftCols(9)).sigma));
}

TEST_CASE("the smoothing keeps a clean curve and averages noise away, its window chosen by GCV") {
  // a clean sine sampled every 0.1 mm: the smoothed curve stays within 1 % of its half excursion
  const Eigen::Matrix3Xd wave = plateCurve(200, [](double p, double& u, double& w) {
    w = 20 * p;
    u = 0.5 * std::sin(2 * pi * w / 3.0);
  });
  const TraceSmoothing sw = smoothTrace(wave, 0.0);
  REQUIRE(sw.points.cols() == wave.cols());
  CHECK((sw.points - wave).cwiseAbs().maxCoeff() < 0.005);
  // a noisy straight line: GCV takes a wide window and the smoothed points lie much closer to the line
  Rng rng{7};
  Eigen::Matrix3Xd line(3, 401);
  for (int i = 0; i <= 400; ++i) line.col(i) = Eigen::Vector3d(0.05 * rng.normal(), 0.1 * i, 0.0);
  const TraceSmoothing sl = smoothTrace(line, 0.0);
    CHECK(sl.points.row(0).cwiseAbs().maxCoeff() < 0.05);
  CHECK(sl.halfWidth > 1.0);  // wider than 10 point spacings
  // too few points: resampled, not smoothed
  const TraceSmoothing few = smoothTrace(line.leftCols(6), 0.0);
    CHECK(few.halfWidth == 0.0);
  CHECK(few.points.cols() == 6);
}

TEST_CASE("a run measured as its trace was reads the trace's amplitude: the smoothing flattens both alike") {
  // the validation plate's wavelength (2.39 mm; A 0.6 mm, clear of the tracing limit on every seed) traced
  // as its scan is: 20 px/mm, a point every 4 px, whole pixels, 0.5 px of jitter. The trace is smoothed at a window GCV picks from its noise
  // (about 1 mm, 0.4 of the wavelength), which flattens its peaks; the root itself measured as it is reads
  // 5-9 % more, measured as its trace was (rootTraitsAs) the trace's amplitude within its tracing sigma
  const Eigen::Matrix3Xd truth = wavingRoot(0.6, 2.39);
  const AnalysisParams set;
  double biasAs = 0.0, biasPlain = 0.0, chi2 = 0.0;
  int n = 0;
  for (unsigned long long seed = 1; seed <= 8; ++seed) {
    const RootTraits t = traceTraits(traceLikeTracer(truth, plateScan(seed)), 0.05, 0.0, 0.1, set);
    CAPTURE(t.wavesNote);
    CAPTURE(t.noiseMm);
    REQUIRE(t.shape.peaks >= 3);
    REQUIRE(t.smoothingMm > 0.5);
    const RootTraits as = rootTraitsAs(truth, t, 0.0, 0.1, set);
    const RootTraits plain = rootTraits(truth, 0.05, 0.0, 0.1, set);
    CHECK(as.smoothingMm == t.smoothingMm);
    CHECK(as.dsMm == t.dsMm);
    // the amplitude's sigma as a fit takes it (observeBoth): sqrt(2) sigma / sqrt(peaks - 1)
    const double sigma = std::sqrt(2.0) * std::max(t.noiseMm, 0.05 / std::sqrt(12.0)) / std::sqrt(t.shape.peaks - 1.0);
    const double ta = t.shape.amplitude / units::mm, aa = as.shape.amplitude / units::mm, pa = plain.shape.amplitude / units::mm;
    CAPTURE(seed);
    CAPTURE(t.smoothingMm);
    CAPTURE(sigma);
    CAPTURE(pa);
    CAPTURE(aa);
    CAPTURE(ta);
    // each seed within three of its sigma; over the seeds, the sum of squares of (aa - ta) / sigma below
    // chi-square's 0.999 quantile for 8 degrees of freedom (26.1): a sigma that is right leaves about a
    // third of the seeds beyond one sigma, so one sigma on every seed would refuse a correct sigma
    const double z = (aa - ta) / sigma;
    CAPTURE(z);
    report("root measured as its trace less the trace, in the amplitude's sigma", z, 0.0, std::abs(z));
    CHECK(std::abs(z) < 3.0);
    chi2 += z * z;
    biasAs += aa / ta - 1.0;
    biasPlain += pa / ta - 1.0;
    ++n;
  }
  biasAs /= n;
  biasPlain /= n;
  report("mean amplitude of the root measured as its trace, relative to the trace's", 1.0 + biasAs, 1.0, std::abs(biasAs));
  report("mean amplitude of the root measured as it is, relative to the trace's", 1.0 + biasPlain, 1.0, std::abs(biasPlain));
  CHECK(chi2 < 26.1);
  CHECK(std::abs(biasAs) < 0.015);
  CHECK(biasPlain > 0.04);  // what a run measured as it is reads: the bias this rule removes
}

namespace {
// a wave train kRootMm long of half excursion half [mm] (negative: towards -lateral first) and wavelength
// lambda [mm] along an axis tiltDeg from downhill, its excursion growing as 1 - exp(-a / growMm) from the
// base (growMm 0: whole from the start)
Eigen::Matrix3Xd skewingTrain(double lambda, double half, double tiltDeg, double growMm) {
  const double tilt = tiltDeg * pi / 180.0;
  return plateCurve(4000, [&](double p, double& u, double& w) {
    const double a = kRootMm * p, grown = growMm > 0.0 ? 1.0 - std::exp(-a / growMm) : 1.0;
    const double across = half * grown * std::sin(2.0 * pi * a / lambda);
    u = a * std::sin(tilt) + across * std::cos(tilt);
    w = a * std::cos(tilt) - across * std::sin(tilt);
  });
}

// a skewing root traced as the plate's scans are (plateScan(seed)), measured; it must read "skewing"
RootTraits tracedSkewing(const Eigen::Matrix3Xd& truth, unsigned long long seed, const AnalysisParams& set) {
  const RootTraits t = traceTraits(traceLikeTracer(truth, plateScan(seed)), 0.05, 0.0, 0.1, set);
  CAPTURE(t.wavesNote);
  CAPTURE(t.noiseThresholdMm);
  REQUIRE(t.shape.pattern == "skewing");
  return t;
}
}  // namespace

TEST_CASE("a skewing root's waves are measured about its own axis: its trace loses no peak to the skew's drift") {
  // a wave train 0.64 mm peak to peak, lambda 2.33 mm, along an axis 16 deg from downhill, traced as a scan is
  // (20 px/mm, a point every 4 px, whole pixels, 0.5 px of jitter). Across downhill its half-waves' swings
  // alternate 0.62 +- 0.33 mm: the smaller ones lie at the tracing limit (about 0.27 mm), and measured there
  // some traces lose them and read a longer wavelength. About the root's axis every swing is 0.64 mm: every
  // trace reads the root's wavelength and its peaks
  const double lambda = 2.33, half = 0.32;
  const Eigen::Matrix3Xd truth = skewingTrain(lambda, half, 16.0, 0.0);
  const AnalysisParams set;
  const RootTraits exact = rootTraits(truth, 0.05, 0.0, 0.1, set);
  REQUIRE(exact.shape.pattern == "skewing");
  CHECK(relError(exact.shape.wavelength / units::mm, lambda) < 0.02);
  CHECK(relError(exact.shape.amplitude / units::mm, 2.0 * half) < 0.02);
  int lostAcrossDownhill = 0;
  for (unsigned long long seed = 1; seed <= 8; ++seed) {
    CAPTURE(seed);
    const RootTraits t = tracedSkewing(truth, seed, set);
    CHECK(relError(t.shape.wavelength / units::mm, lambda) < 0.05);
    CHECK(std::abs(t.shape.peaks - exact.shape.peaks) <= 1);
    CHECK(t.shape.skew / units::deg == doctest::Approx(16.0).epsilon(0.05));
    // the same smoothed curve measured across downhill (analyseCentreline as it is): what the axis avoids
    const ShapeAnalysis across = analyseCentreline(plateMmToLab(t.curveMm, PlateFrame::tilted(90.0 * units::deg)), t.matureLast,
                                                   [] { Plane pl; pl.alpha = 90.0 * units::deg; return pl; }(), set, 0.1 * units::mm,
                                                   t.noiseThresholdMm * units::mm);
    CAPTURE(across.peaks);
    CAPTURE(across.wavelength);
    lostAcrossDownhill += across.peaks < t.shape.peaks - 1;
  }
  // the case the rule is for: across downhill, some of these traces lose peaks
  CHECK(lostAcrossDownhill >= 1);
}

TEST_CASE("a run measured as its trace starts its wave train where the trace does: a first swing under the tracing limit is no peak of either") {
  // a skewing root whose first wave grows from its sowing, as a run's does: 0.6 mm peak to peak, lambda
  // 2.33 mm, along an axis 7 deg from downhill, the excursion growing as 1 - exp(-a / 1 mm) from the base.
  // Its first trough departs from the base by about 0.1 mm, above a run's hysteresis (0.05 mm) and below a
  // scan's tracing limit (about 0.27 mm): the exact root counts it, its traces do not, and it lies off the
  // axis, so the skew over whole waves from it (first peak to the last on its side) reads about 0.4 deg
  // less than from the first full crest. Measured as its trace was (rootTraitsAs), the root's train starts and
  // ends at the trace's limit and reads the trace's skew within its sigma
  const Eigen::Matrix3Xd truth = skewingTrain(2.33, -0.3, 7.0, 1.0);
  const AnalysisParams set;
  const RootTraits exact = rootTraits(truth, 0.05, 0.0, 0.1, set);
  REQUIRE(exact.shape.pattern == "skewing");
  double chi2 = 0.0, zPlain = 0.0;
  int n = 0;
  for (unsigned long long seed = 1; seed <= 8; ++seed) {
    CAPTURE(seed);
    const RootTraits t = tracedSkewing(truth, seed, set);
    const RootTraits as = rootTraitsAs(truth, t, 0.0, 0.1, set);
    CAPTURE(exact.shape.peaks);
    CAPTURE(t.shape.peaks);
    CAPTURE(as.shape.peaks);
    // the trace loses the shallow first trough, and so does the root measured as the trace: both start
    // their train at least a quarter wave past the exact root's first peak (how many later swings near the
    // limit a trace keeps, its noise decides)
    const auto firstPeakDownhill = [](const RootTraits& r) { return r.curveMm(1, r.shape.peakNodes.front()); };
    REQUIRE(!t.shape.peakNodes.empty());
    REQUIRE(!as.shape.peakNodes.empty());
    CHECK(firstPeakDownhill(t) > firstPeakDownhill(exact) + 0.25 * 2.33);
    CHECK(firstPeakDownhill(as) > firstPeakDownhill(exact) + 0.25 * 2.33);
    CHECK(t.shape.peaks < exact.shape.peaks);
    CHECK(as.shape.peaks < exact.shape.peaks);
    // the skew's residual as a fit takes it (observeBoth: its sigma from the trace's noise and span)
    const double sigmaPos = std::max(t.noiseMm, 0.05 / std::sqrt(12.0));
    const auto skewOf = [&](const RootTraits& sim) {
      for (const Observation& o : observeBoth(t, sim, sigmaPos))
        if (o.name == "skew_deg") return o;
      return Observation{};
    };
    const Observation o = skewOf(as), plain = skewOf(exact);
    REQUIRE(o.used);
    CAPTURE(o.trace);
    CAPTURE(o.sim);
    CAPTURE(o.sigma);
    CAPTURE(plain.sim);
    report("skew of the root measured as its trace less the trace's, in its sigma", o.residual(), 0.0, std::abs(o.residual()));
    // each seed within three sigma; over the seeds chi-square below its 0.999 quantile for 8 dof (26.1)
    CHECK(std::abs(o.residual()) < 3.0);
    chi2 += o.residual() * o.residual();
    zPlain += plain.residual();
    ++n;
  }
  CHECK(chi2 < 26.1);
  // the root measured as it is starts its train at the shallow trough: its skew off the traces' by
  // several sigma on average (what this rule removes)
  report("mean residual of the skew of the root measured as it is, in sigma", zPlain / n, 0.0, std::abs(zPlain / n));
  CHECK(std::abs(zPlain / n) > 2.0);
}

TEST_CASE("straightness, HGI and VGI of closed-form shapes, signed as the skew angle") {
  for (double deg : {-30.0, 0.0, 20.0}) {
    const double a = deg * pi / 180.0;
    const Eigen::Matrix3Xd line = plateCurve(50, [&](double p, double& u, double& w) { u = 10 * p * std::sin(a); w = 10 * p * std::cos(a); });
    const RootTraits t = rootTraits(line, 0.05, 0.0, 0.1, AnalysisParams{});
    CHECK(t.straightness == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(t.hgi == doctest::Approx(std::sin(a)).scale(1.0).epsilon(1e-12));
    CHECK(t.vgi == doctest::Approx(std::cos(a)).epsilon(1e-12));
    CHECK(t.skewDeg == doctest::Approx(deg).scale(1.0).epsilon(1e-9));
    CHECK(t.thetaTipDeg == doctest::Approx(deg).scale(1.0).epsilon(1e-9));
  }
  // a half circle bending towards +lateral and back: chord 2R along downhill over length pi R
  const Eigen::Matrix3Xd half = plateCurve(2000, [](double p, double& u, double& w) {
    u = 2 * std::sin(pi * p);
    w = 2 - 2 * std::cos(pi * p);
  });
  const RootTraits h = rootTraits(half, 0.0, 0.0, 0.1, AnalysisParams{});
  CHECK(h.straightness == doctest::Approx(2.0 / pi).epsilon(1e-6));
  CHECK(h.hgi == doctest::Approx(0.0).scale(1.0).epsilon(1e-12));
  CHECK(h.vgi == doctest::Approx(2.0 / pi).epsilon(1e-6));
  CHECK(h.thetaTipDeg == doctest::Approx(-90.0).epsilon(1e-3));  // heading towards -lateral at the end
}


// ---- roots degraded as a tracer degrades them (docs/experiments.md, "Validation on roots degraded as a
// tracer degrades them"); ROOTSIM_PRINT_NOISE_TABLE=1 prints its tables ----

namespace {

struct Tally {
  int n = 0, straight = 0, waving = 0, kept = 0;  // kept: waving with lambda within 10 % and A within 15 %
  std::vector<double> lamErr, ampErr, noiseRatio;
  void add(const RootTraits& t, double lam, double amp, double injected) {
    ++n;
    const ShapeAnalysis& a = t.shape;
    straight += a.pattern == "straight";
    noiseRatio.push_back(t.noiseMm / injected);
    if (a.pattern != "waving") return;
    ++waving;
    if (!(lam > 0)) return;
    const double le = a.peaks >= 3 ? a.wavelength / units::mm / lam - 1 : std::nan("");
    const double ae = a.amplitude / units::mm / amp - 1;
    lamErr.push_back(le);
    ampErr.push_back(ae);
    kept += std::abs(le) <= 0.10 && std::abs(ae) <= 0.15;
  }
};

double medianOf(std::vector<double> v) {
  std::vector<double> f;
  for (double x : v)
    if (std::isfinite(x)) f.push_back(x);
  if (f.empty()) return std::nan("");
  std::sort(f.begin(), f.end());
  return f.size() % 2 ? f[f.size() / 2] : 0.5 * (f[f.size() / 2 - 1] + f[f.size() / 2]);
}

std::string pct(double x) {
  char b[32];
  if (!std::isfinite(x)) return "–";
  std::snprintf(b, sizeof b, "%+.1f %%", 100 * x);
  return b;
}

}  // namespace

TEST_CASE("tracer-degraded roots: straight ones stay straight and 0.5 mm waves keep lambda and A over scales jitters and seeds") {
  const bool print = std::getenv("ROOTSIM_PRINT_NOISE_TABLE") != nullptr;
  struct Shape {
    const char* name;
    double amp, lam;
  };
  const Shape shapes[] = {{"straight", 0, 0}, {"A 0.5 λ 2", 0.5, 2}, {"A 0.5 λ 4", 0.5, 4}, {"A 0.5 λ 6", 0.5, 6}, {"A 1 λ 3", 1.0, 3}};
  constexpr int kSeeds = 20;
  if (print) {
    std::printf("| px/mm | jitter px | root | straight | waving | λ and A kept | median λ error | median A error | median noise / white |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
  }
  for (double pxPerMm : {10.0, 16.0, 24.0, 40.0})
    for (double jitter : {0.5, 1.0, 2.0})
      for (const Shape& sh : shapes) {
        const Eigen::Matrix3Xd truth = sh.amp > 0 ? wavingRoot(sh.amp, sh.lam) : straightRoot();
        // the white part the tracer adds: jitter and whole-pixel rounding
        const double white = std::sqrt(jitter * jitter + 1.0 / 12.0) / pxPerMm;
        Tally tl;
        for (unsigned long long seed = 1; seed <= kSeeds; ++seed)
          tl.add(traceAndMeasure(truth, pxPerMm, jitter, seed), sh.lam, sh.amp, white);
        if (print)
          std::printf("| %g | %g | %s | %d/%d | %d/%d | %d/%d | %s | %s | %.2f |\n", pxPerMm, jitter, sh.name, tl.straight, tl.n, tl.waving,
                      tl.n, tl.kept, tl.n, pct(medianOf(tl.lamErr)).c_str(), pct(medianOf(tl.ampErr)).c_str(), medianOf(tl.noiseRatio));
        CAPTURE(pxPerMm);
        CAPTURE(jitter);
        CAPTURE(sh.name);
        if (sh.amp == 0) {
          CHECK(tl.straight >= 0.95 * tl.n);
          continue;
        }
        // claimed where the trace resolves the wave above the tracing limit (the table shows the rest):
        // A = 0.5 mm at 24 px/mm and up with up to 1 px of jitter, at 40 px/mm with any; A = 1 mm from 16
        // px/mm with up to 1 px, from 24 px/mm with any
        const bool claimed = sh.amp < 1 ? (pxPerMm >= 24 && jitter <= 1) || pxPerMm >= 40 : (pxPerMm >= 16 && jitter <= 1) || pxPerMm >= 24;
        if (!claimed) continue;
        // 85 %: a 20 mm root has 3 waves of 6 mm, so one excursion merged under the limit leaves fewer
        // than the 3 regular half-waves a wave train needs (the table: 17-18 of 20 for lambda 6 mm)
        CHECK(tl.waving >= 0.85 * tl.n);
        CHECK(std::abs(medianOf(tl.lamErr)) < 0.10);
        CHECK(std::abs(medianOf(tl.ampErr)) < 0.15);
        CHECK(tl.kept >= tl.n / 2);
      }
  // the detection limit: waves of lambda 3 mm and smaller A at 24 px/mm with 1 px of jitter
  if (print) std::printf("\n| A mm | waving | λ and A kept | median λ error | median A error |\n|---|---|---|---|---|\n");
  for (double amp : {0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5}) {
    Tally tl;
    for (unsigned long long seed = 1; seed <= kSeeds; ++seed) tl.add(traceAndMeasure(wavingRoot(amp, 3.0), 24.0, 1.0, seed), 3.0, amp, 1.0);
    if (print)
      std::printf("| %g | %d/%d | %d/%d | %s | %s |\n", amp, tl.waving, tl.n, tl.kept, tl.n, pct(medianOf(tl.lamErr)).c_str(),
                  pct(medianOf(tl.ampErr)).c_str());
    CAPTURE(amp);
    // a wave of one root diameter is what the tracing alone can draw: not called
    if (amp <= 0.2) CHECK(tl.waving <= tl.n / 20);
  }
}

TEST_CASE("the paper's fig2b waving run traced as a tracer traces it is still waving with its lambda and A") {
  // scenes/fig2b_waving.toml: the default root on a plate tilted 40 degrees, beta 0.2, 3000 steps of 0.05 h
  Model m = defaultModel();
  m.env.plane.alpha = 40 * units::deg;
  m.tropism.beta = 0.2;
  completeModel(m);
  Simulation sim(m);
  for (int k = 0; k < m.growth.steps; ++k) sim.growthStep();
  const ShapeAnalysis run = analyseShape(m, sim.state());
  REQUIRE(run.pattern == "waving");
  const PlateFrame f = m.env.plane.frame();
  const RodState& s = sim.state();
  Eigen::Matrix3Xd plate(3, s.nodes());
  for (int i = 0; i < s.nodes(); ++i) plate.col(i) = f.coords(s.x.col(i) - s.x.col(0)) / units::mm;
  const double gzMm = m.growth.zoneLength / units::mm, lam = run.wavelength / units::mm, amp = run.amplitude / units::mm;
  const bool print = std::getenv("ROOTSIM_PRINT_NOISE_TABLE") != nullptr;
  if (print) {
    std::printf("fig2b run: lambda %.3f mm, A %.3f mm, %d peaks\n", lam, amp, run.peaks);
    std::printf("| px/mm | jitter px | waving | λ and A kept | median λ error | median A error |\n|---|---|---|---|---|---|\n");
  }
  for (double pxPerMm : {10.0, 16.0, 24.0, 40.0})
    for (double jitter : {0.5, 1.0, 2.0}) {
      Tally tl;
      for (unsigned long long seed = 1; seed <= 10; ++seed) {
        TracerModel tr;
        tr.pxPerMm = pxPerMm;
        tr.jitterPx = jitter;
        tr.seed = seed;
        tr.offsetCorrMm = corrLengthOf(seed);
        tl.add(traceTraits(traceLikeTracer(plate, tr), 0.05, gzMm, 0.1, m.analysis), lam, amp, 1.0);
      }
      if (print)
        std::printf("| %g | %g | %d/%d | %d/%d | %s | %s |\n", pxPerMm, jitter, tl.waving, tl.n, tl.kept, tl.n, pct(medianOf(tl.lamErr)).c_str(),
                    pct(medianOf(tl.ampErr)).c_str());
      CAPTURE(pxPerMm);
      CAPTURE(jitter);
      // still waving from 24 px/mm; lambda and A kept from 24 px/mm with up to 1 px of jitter, 40 with 2 px
      if (pxPerMm >= 24) CHECK(tl.waving == tl.n);
      if ((pxPerMm >= 24 && jitter <= 1) || pxPerMm >= 40) {
        CHECK(tl.waving == tl.n);
        CHECK(std::abs(medianOf(tl.lamErr)) < 0.10);
        CHECK(std::abs(medianOf(tl.ampErr)) < 0.15);
      }
    }
}

// ---- one bend: a root that turned once is "curved", a straight one traced with drift is not ----

namespace {

// a C: one half-wave of lateral bow b over the root
Eigen::Matrix3Xd cBend(double bowMm) {
  return plateCurve(4000, [&](double p, double& u, double& w) {
    w = kRootMm * p;
    u = bowMm * std::sin(pi * p);
  });
}
// a root that turns by deg over 2 mm at its middle, from -deg/2 to +deg/2 off downhill (its base-to-tip
// direction downhill: not skewing)
Eigen::Matrix3Xd turnOnce(double deg) {
  const double h = 0.5 * deg * pi / 180.0;
  constexpr int n = 4000;
  Eigen::Matrix3Xd c(3, n + 1);
  c.col(0).setZero();
  for (int i = 1; i <= n; ++i) {
    const double s = kRootMm * (i - 0.5) / n;
    const double a = -h + 2.0 * h * std::clamp((s - 0.5 * kRootMm + 1.0) / 2.0, 0.0, 1.0);
    c.col(i) = c.col(i - 1) + kRootMm / n * Eigen::Vector3d(std::sin(a), std::cos(a), 0.0);
  }
  return c;
}

}  // namespace

TEST_CASE("bow and turning angle of closed-form bends") {
  // (bows small against the length: the thirds are of the arc length, which w then is to 1e-3)
  for (double b : {0.1, 0.25, 1.0}) {
    const RootTraits t = rootTraits(cBend(b), 0.05, 0.0, 0.1, AnalysisParams{});
    CHECK(t.bowMm == doctest::Approx(b).epsilon(1e-4));
    // the thirds' chords: from (0, 0) to (b sin(pi/3), L/3), and from (b sin(2 pi/3), 2L/3) to (0, L)
    const double expect = -2.0 * std::atan(b * std::sin(pi / 3.0) / (kRootMm / 3.0)) * 180.0 / pi;
    CHECK(t.bendDeg == doctest::Approx(expect).epsilon(1e-3));
  }
  // a straight line at any angle neither bows nor turns
  const Eigen::Matrix3Xd line = plateCurve(100, [](double p, double& u, double& w) { u = 3 * p; w = 10 * p; });
  const RootTraits l = rootTraits(line, 0.05, 0.0, 0.1, AnalysisParams{});
  CHECK(l.bowMm == doctest::Approx(0.0).scale(1.0).epsilon(1e-9));
  CHECK(l.bendDeg == doctest::Approx(0.0).scale(1.0).epsilon(1e-9));
  // the turn: the thirds lie on either side of the 2 mm turn, so their chords have the two directions
  CHECK(rootTraits(turnOnce(20), 0.05, 0.0, 0.1, AnalysisParams{}).bendDeg == doctest::Approx(20.0).epsilon(1e-3));
}

TEST_CASE("tracer-degraded bends: a root that turned once is curved and a straight one is not, over scales jitters and seeds") {
  const bool print = std::getenv("ROOTSIM_PRINT_NOISE_TABLE") != nullptr;
  struct Shape {
    const char* name;
    Eigen::Matrix3Xd truth;
    int strength;  // 0: straight; 1: at the threshold (shown, not claimed); 2: a clear bend; 3: a large one
  };
  const Shape shapes[] = {{"straight", straightRoot(), 0},   {"C bow 0.25", cBend(0.25), 1}, {"C bow 0.5", cBend(0.5), 2},
                          {"C bow 1", cBend(1.0), 3},         {"turn 5°", turnOnce(5), 1},    {"turn 10°", turnOnce(10), 2},
                          {"turn 20°", turnOnce(20), 3}};
  constexpr int kSeeds = 20;
  if (print) {
    std::printf("\n| px/mm | jitter px | root | true bow mm, turn ° | curved | straight | waving | median bow error | median turn error |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
  }
  for (double pxPerMm : {10.0, 16.0, 24.0, 40.0})
    for (double jitter : {0.5, 1.0, 2.0})
      for (const Shape& sh : shapes) {
        const RootTraits truth = rootTraits(sh.truth, 0.05, 0.0, 0.1, AnalysisParams{});
        int curved = 0, straight = 0, waving = 0;
        std::vector<double> bowErr, turnErr;
        for (unsigned long long seed = 1; seed <= kSeeds; ++seed) {
          const RootTraits t = traceAndMeasure(sh.truth, pxPerMm, jitter, seed);
          curved += t.shape.pattern == "curved";
          straight += t.shape.pattern == "straight";
          waving += t.shape.pattern == "waving";
          if (t.shape.pattern != "curved") continue;
          bowErr.push_back(t.bowMm / truth.bowMm - 1.0);
          turnErr.push_back(t.bendDeg / truth.bendDeg - 1.0);
        }
        if (print)
          std::printf("| %g | %g | %s | %.3g, %.3g | %d/%d | %d/%d | %d/%d | %s | %s |\n", pxPerMm, jitter, sh.name, truth.bowMm, truth.bendDeg, curved,
                      kSeeds, straight, kSeeds, waving, kSeeds, pct(medianOf(bowErr)).c_str(), pct(medianOf(turnErr)).c_str());
        CAPTURE(pxPerMm);
        CAPTURE(jitter);
        CAPTURE(sh.name);
        CHECK(waving == 0);
        if (sh.strength == 0) {
          CHECK(curved == 0);  // the tracer's drift bows a straight root but does not turn it
          continue;
        }
        if (sh.strength == 1) continue;  // at the threshold: the table shows how often
        // claimed: a large bend everywhere; a clear one where the trace resolves half a millimetre
        const bool claimed = sh.strength == 3 ? !(pxPerMm < 16 && jitter > 1) : (pxPerMm >= 16 && jitter <= 1) || pxPerMm >= 24;
        if (!claimed) continue;
        CHECK(curved >= 0.85 * kSeeds);
        CHECK(std::abs(medianOf(turnErr)) < 0.15);
      }
}
