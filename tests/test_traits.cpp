// phenotyping traits of a centreline (src/analysis/traits.cpp): resampling, length, tortuosity, the skew angle's
// sign against the runs' theta, the insertion angle, the run observables of a trace equal to those
// analyseShape measures on the same shape; a trace's noise estimate, its smoothing, straightness, HGI and
// VGI, and the noise-aware measurement of roots degraded as a tracer degrades them
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "physics_support.hpp"
#include "rootsim/analysis.hpp"
#include "rootsim/rod.hpp"
#include "rootsim/traits.hpp"
#include "rootsim/units.hpp"

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
  CHECK(s.skewDeg == doctest::Approx(0.0));
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
  CHECK(std::abs(theta) == doctest::Approx(a));
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

// a root as a tracer draws it (docs/experiments.md, "Noise"): points every stepPx of arc length along the
// true curve (plate coordinates [mm]), each moved across and along by Gaussian jitter of jitterPx per
// coordinate, one point in 20 snapped snapPx across the curve (to an edge), then rounded to whole pixels
struct Tracer {
  double pxPerMm = 24, jitterPx = 1, stepPx = 4, snapPx = 3, snapEvery = 20;
  unsigned long long seed = 1;
};

// a deterministic uniform in (0, 1) and a Gaussian by Box-Muller (the same numbers on every platform)
struct Rng {
  unsigned long long s;
  double uniform() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(s >> 11) + 0.5) / 9007199254740992.0;
  }
  double normal() { return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * pi * uniform()); }
};

Eigen::Matrix3Xd traceLike(const Eigen::Matrix3Xd& truthMm, const Tracer& t) {
  const Eigen::Matrix3Xd p = resampleByArcLength(truthMm, t.stepPx / t.pxPerMm);
  Rng rng{t.seed * 0x9E3779B97F4A7C15ULL + 7};
  Eigen::Matrix3Xd q(3, p.cols());
  for (int i = 0; i < p.cols(); ++i) {
    const int a = std::max(0, i - 1), b = std::min(static_cast<int>(p.cols()) - 1, i + 1);
    const Eigen::Vector2d tan = (p.col(b) - p.col(a)).head<2>().normalized();
    const Eigen::Vector2d nrm(-tan.y(), tan.x());
    Eigen::Vector2d px = p.col(i).head<2>() * t.pxPerMm + Eigen::Vector2d(100.3, 57.6);  // an image's offset
    px += t.jitterPx * Eigen::Vector2d(rng.normal(), rng.normal());
    if (rng.uniform() < 1.0 / t.snapEvery) px += (rng.uniform() < 0.5 ? -1.0 : 1.0) * t.snapPx * nrm;
    q.col(i) = Eigen::Vector3d(std::round(px.x()), std::round(px.y()), 0.0) / t.pxPerMm;
  }
  return q;
}

// the validation shapes: 20 mm of root, straight 3 degrees off downhill, or waving with half excursion
// 0.5 mm (A = 1 mm peak to peak) and wavelength 3 mm; 4000 points
constexpr double kWaveHalfMm = 0.5, kWaveLambdaMm = 3.0, kRootMm = 20.0;
Eigen::Matrix3Xd straightRoot() {
  const double a = 3.0 * pi / 180.0;
  return plateCurve(4000, [&](double p, double& u, double& w) { u = kRootMm * p * std::sin(a); w = kRootMm * p * std::cos(a); });
}
Eigen::Matrix3Xd wavingRoot() {
  return plateCurve(4000, [](double p, double& u, double& w) {
    w = kRootMm * p;
    u = kWaveHalfMm * std::sin(2.0 * pi * w / kWaveLambdaMm);
  });
}

struct TracedCase {
  double pxPerMm, jitterPx;
  bool wave;
  double injectedMm;  // sqrt(jitter^2 + 1/12) px: the jitter and the whole-pixel rounding
  RootTraits t;
};

TracedCase traceAndMeasure(double pxPerMm, double jitterPx, bool wave, unsigned long long seed) {
  Tracer tr;
  tr.pxPerMm = pxPerMm;
  tr.jitterPx = jitterPx;
  tr.seed = seed;
  const Eigen::Matrix3Xd q = traceLike(wave ? wavingRoot() : straightRoot(), tr);
  TracedCase c{pxPerMm, jitterPx, wave, std::sqrt(jitterPx * jitterPx + 1.0 / 12.0) / pxPerMm,
               traceTraits(q, 0.05, 0.0, 0.1, AnalysisParams{})};
  return c;
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

TEST_CASE("tracer-degraded roots: a straight root stays straight, a 0.5 mm wave keeps lambda and A, sigma is found") {
  // ROOTSIM_PRINT_NOISE_TABLE=1 prints the table of docs/experiments.md ("Noise")
  const bool print = std::getenv("ROOTSIM_PRINT_NOISE_TABLE") != nullptr;
  if (print) {
    std::printf("| px/mm | jitter px | root | injected σ mm | noise_mm | noise / injected | smoothing_mm | pattern | peaks | λ mm (error) | A mm (error) |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  for (double pxPerMm : {10.0, 24.0, 50.0})
    for (double jitter : {0.5, 1.0, 2.0})
      for (bool wave : {false, true}) {
        const TracedCase c = traceAndMeasure(pxPerMm, jitter, wave, 1);
        const ShapeAnalysis& a = c.t.shape;
        const double lam = a.wavelength / units::mm, amp = a.amplitude / units::mm;
        if (print) {
          char w[64] = "–", m[64] = "–";
          if (a.peaks >= 3) std::snprintf(w, sizeof w, "%.3f (%+.1f %%)", lam, 100 * (lam / kWaveLambdaMm - 1));
          if (a.peaks >= 2) std::snprintf(m, sizeof m, "%.3f (%+.1f %%)", amp, 100 * (amp / (2 * kWaveHalfMm) - 1));
          std::printf("| %g | %g | %s | %.4f | %.4f | %.2f | %.3f | %s | %d | %s | %s |\n", pxPerMm, jitter, wave ? "wave" : "straight",
                      c.injectedMm, c.t.noiseMm, c.t.noiseMm / c.injectedMm, c.t.smoothingMm, a.pattern.c_str(), a.peaks, w, m);
        }
        CAPTURE(pxPerMm);
        CAPTURE(jitter);
        CAPTURE(wave);
        const double noiseErr = relError(c.t.noiseMm, c.injectedMm);
        report("noise_mm against the injected noise", c.t.noiseMm, c.injectedMm, noiseErr);
        CHECK(noiseErr < 0.25);
        // claimed where the trace resolves the wave: at 10 px/mm a point every 4 px is 0.4 mm (7.5 points
        // a wavelength) and jitter of 1 px or more is a fifth of the wave's half excursion (the table
        // shows those rows too: A falls by 14-18 %, and at 2 px the straight root's ends tilt it to
        // "skewing"; docs/experiments.md, "Noise")
        const bool claimed = pxPerMm >= 24 || jitter <= 0.5;
        if (!claimed) continue;
        if (!wave) {
          CHECK(a.pattern == "straight");
          CHECK(a.peaks < 2);
          CHECK(!c.t.wavesNote.empty());
        } else {
          CHECK(a.pattern == "waving");
          const double lamErr = relError(lam, kWaveLambdaMm), ampErr = relError(amp, 2 * kWaveHalfMm);
          report("wavelength of the traced wave", lam, kWaveLambdaMm, lamErr);
          report("amplitude (peak to peak) of the traced wave", amp, 2 * kWaveHalfMm, ampErr);
          CHECK(lamErr < 0.10);
          CHECK(ampErr < 0.15);
        }
      }
}
