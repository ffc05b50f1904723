// `rootsim compare RUN_DIR TRACE.rsml`: a traced root beside a run's root (docs/experiments.md, "Compare").
#include "rootsim/compare_trace.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <fstream>
#include <stdexcept>
#include <tuple>

#include "rootsim/analyze_traces.hpp"
#include "rootsim/compare_panel.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/json.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/trace_growth.hpp"
#include "rootsim/trace_match.hpp"
#include "rootsim/units.hpp"
#include "rootsim/write_rule.hpp"
#include "rootsim/run_snapshots.hpp"
#include "analysis_numbers.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

}  // namespace

TraceUncertainty traceUncertainty(const RootTraits& traits, double pixelMm, bool exact, double flagMm, const std::string& flag) {
  if (flagGiven(flagMm)) return {flagMm, flag};
  // the trace's own scatter about its smoothed curve: what its tracer's jitter, snapping and whole-pixel
  // coordinates did to this root (a pixel overstates a 0.3 px tracer three times, understates a 2 px one);
  // never below the quantisation of whole-pixel coordinates, p / sqrt(12), which every pixel trace has
  const double quantum = pixelMm > 0 ? pixelMm / std::sqrt(12.0) : 0.0;
  if (!exact && std::isfinite(traits.noiseMm) && std::max(traits.noiseMm, quantum) > 0)
    return traits.noiseMm >= quantum ? TraceUncertainty{traits.noiseMm, "noise_mm"} : TraceUncertainty{quantum, "pixel / sqrt(12)"};
  // a rootsim export (a run's nodes: no tracer's noise to estimate), or too few points to estimate it
  if (pixelMm > 0) return {pixelMm, "pixel"};
  return {kDefaultSigmaMm, exact ? "default (a rootsim export has no tracing noise)" : "default"};
}

TraceTarget loadTarget(const TraceFlags& f, const Model& m) {
  if (flagGiven(f.sigmaMm)) checkedNumber(f.flagPrefix + "sigma-mm", f.sigmaMm, {0, 10, true, false, "mm"});
  AnalyzeOptions a;
  a.pxPerMm = f.pxPerMm;
  a.downhill = f.downhill;
  // the trace is measured as the run: its growth zone left out, the run's R for the peaks' hysteresis
  a.excludeTipMm = m.growth.zoneLength / units::mm;
  a.radiusMm = m.rod.radius / units::mm;
  a.flagPrefix = f.flagPrefix;
  checkTraceFlags(a);
  const TraceFile tf = readTraceFile(f.trace, a);
  // the root as a scan of the plate shows it, as every run it is compared with (simRootOf): a rootsim
  // export's height off the plate dropped (a tracer's points have none)
  TracedRoot r = pickRoot(tf, f.root, f.flagPrefix + "root");
  r.plateMm.row(2).setZero();
  TraceTarget t;
  t.file = f.trace;
  t.rootKey = r.key;
  t.plateMm = r.plateMm;
  for (int i = 0; i < t.plateMm.cols(); ++i) t.plateMm.col(i) -= r.plateMm.col(0);
  t.dsMm = tf.dsMm;
  t.timesH = pointTimesH(tf, r);
  if (!t.timesH.empty()) t.observationTimesH = tf.observationTimesH;
  AnalysisParams set = m.analysis;
  TraceFile measured = tf;
  measured.set = set;
  t.traits = tracedTraits(measured, r, tf.dsMm, tf.excludeTipMm);
  t.pixelMm = tf.pixelMm > 0 ? tf.pixelMm : 0.0;
  const TraceUncertainty u = traceUncertainty(t.traits, t.pixelMm, tf.ours, f.sigmaMm, f.flagPrefix + "sigma-mm");
  t.sigmaMm = u.sigmaMm;
  t.sigmaSource = u.source;
  t.excludeTipMm = m.growth.zoneLength / units::mm;
  t.rootLengthMm = t.traits.lengthMm - (tf.ours ? 0.0 : noiseLengtheningMm(t.plateMm, t.sigmaMm));
  return t;
}

namespace {

// a snapshot's nodes on the plate as a scan sees them [mm]: lateral and downhill from the seed, the height
// off the plate dropped
Eigen::Matrix3Xd plateView(const Model& m, const Snapshot& s) {
  const PlateFrame pf = m.env.plane.frame();
  Eigen::Matrix3Xd p(3, s.x.cols());
  for (int i = 0; i < s.x.cols(); ++i) p.col(i) = pf.coords(s.x.col(i) - s.x.col(0)) / units::mm;
  p.row(2).setZero();
  return p;
}

}  // namespace

int snapshotOfLength(const Model& m, const std::vector<Snapshot>& snaps, double lengthMm) {
  int best = static_cast<int>(snaps.size()) - 1;
  double off = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(snaps.size()); ++i)
    if (const double d = std::abs(polylineLength(plateView(m, snaps[static_cast<std::size_t>(i)])) - lengthMm); d < off) {
      off = d;
      best = i;
    }
  return best;
}

SimRoot simRootOf(const Model& m, const Snapshot& s, const TraceTarget& as) {
  SimRoot r;
  r.timeH = s.timeH;
  r.step = s.step;
  r.plateMm = plateView(m, s);
  // the run's nodes, its growth zone left out, smoothed and resampled as the trace was (an exact trace,
  // measured as it is: what summary.json measures, analyseShape)
  r.traits = rootTraitsAs(r.plateMm, as.traits, m.growth.zoneLength / units::mm, m.rod.radius / units::mm, m.analysis);
  return r;
}

Comparison compareRoots(const TraceTarget& t, const SimRoot& s) {
  Comparison c;
  c.obs = observeBoth(t.traits, s.traits, t.sigmaMm);
  c.chi2 = chiSquare(c.obs);
  c.used = usedCount(c.obs);
  c.distanceMm = arcLengthDistanceMm(t.plateMm, s.plateMm, kDistanceStepMm);
  c.frechetMm = frechetDistanceMm(t.plateMm, s.plateMm, kDistanceStepMm);
  return c;
}

double tipPixelMm(const TraceTarget& t) { return t.pixelMm; }

std::vector<TraceAtTime> traceAtTimes(const Eigen::Matrix3Xd& p, const std::vector<double>& timesH, const std::vector<double>& observationTimesH,
                                      double pixelMm) {
  std::vector<TraceAtTime> out;
  for (double at : observationTimesH) {
    const Eigen::Matrix3Xd trace = polylineAtTime(p, timesH, at);
    if (trace.cols() < 2 || !(polylineLength(trace) > 0)) continue;
    TraceAtTime r;
    r.timeH = at;
    r.lengthMm = polylineLength(trace);
    r.tipLateralMm = trace(0, trace.cols() - 1);
    r.tipDownhillMm = trace(1, trace.cols() - 1);
    r.thetaTipDeg = tipAngleDeg(trace, pixelMm);
    r.thetaDefined = r.lengthMm >= 2.0 * tipAngleSpanMm(pixelMm);
    out.push_back(r);
  }
  return out;
}

std::vector<TimeLapseRow> compareTimeLapse(const TraceTarget& t, const Model& m, const std::vector<Snapshot>& snaps) {
  std::vector<TimeLapseRow> rows;
  if (t.timesH.empty() || snaps.empty()) return rows;
  const std::vector<double> runTimes = snapshotTimes(snaps);
  auto near = [&](double at) { return snapshotNear(runTimes, std::clamp(at, runTimes.front(), runTimes.back())); };
  const std::vector<TraceAtTime> traced = traceAtTimes(t.plateMm, t.timesH, t.observationTimesH, tipPixelMm(t));
  if (traced.empty()) return rows;
  // the run recorded as a 2D+t trace records a root (its old parts do not move): its root at the last
  // observation time up to the length it had at each earlier one; a growth zone that bends after the tip
  // passed is seen where it ended, on both sides alike
  const Eigen::Matrix3Xd last = simRootOf(m, snaps[static_cast<std::size_t>(near(traced.back().timeH))], t).plateMm;
  std::vector<double> arc(static_cast<std::size_t>(last.cols()), 0.0);
  for (Eigen::Index i = 1; i < last.cols(); ++i)
    arc[static_cast<std::size_t>(i)] = arc[static_cast<std::size_t>(i - 1)] + (last.col(i) - last.col(i - 1)).norm();
  // the tracer's points lie as far apart along the root as the trace's at the last time: it measures a
  // length along chords that long, in the plate's plane (a polyline through a bent root is shorter than
  // the root: on a waving root traced at 0.4 mm, 0.5 % of its length)
  const Eigen::Matrix3Xd traceLast = polylineAtTime(t.plateMm, t.timesH, traced.back().timeH);
  const double spacing = polylineLength(traceLast) / static_cast<double>(std::max<std::size_t>(1, distinctPoints(traceLast).size() - 1));
  for (const TraceAtTime& tr : traced) {
    const double at = tr.timeH;
    const Eigen::Matrix3Xd trace = polylineAtTime(t.plateMm, t.timesH, at);
    const SimRoot sim = simRootOf(m, snaps[static_cast<std::size_t>(near(at))], t);
    const Eigen::Matrix3Xd run = polylineAtTime(last, arc, std::min(polylineLength(sim.plateMm), arc.back()));
    Eigen::Matrix3Xd onPlate = run;
    onPlate.row(2).setZero();
    const double length = polylineLength(resampleByArcLength(onPlate, spacing));
    TimeLapseRow r;
    r.timeH = at;
    r.snapshotH = sim.timeH;
    r.traceLengthMm = tr.lengthMm;
    r.runLengthMm = length;
    r.traceTipLateralMm = tr.tipLateralMm;
    r.traceTipDownhillMm = tr.tipDownhillMm;
    r.runTipLateralMm = run(0, run.cols() - 1);
    r.runTipDownhillMm = run(1, run.cols() - 1);
    r.traceThetaTipDeg = tr.thetaTipDeg;
    r.runThetaTipDeg = tipAngleDeg(run, 0.0);
    r.distanceMm = arcLengthDistanceMm(trace, run, kDistanceStepMm);
    rows.push_back(r);
  }
  // the strongest wave of both at the last time, over the range the trace's points resolve
  const auto [lo, hi] = waveRange(traceLast, t.excludeTipMm);
  rows.back().traceWave = strongestWave(traceLast, t.excludeTipMm, lo, hi);
  // (the run sampled as the trace is, as many points along it: a wave's least-squares amplitude depends on
  // where its samples fall)
  const Eigen::Matrix3Xd runLast = polylineAtTime(last, arc, std::min(polylineLength(simRootOf(m, snaps[static_cast<std::size_t>(near(traced.back().timeH))], t).plateMm), arc.back()));
  rows.back().runWave = strongestWave(tracedLike(runLast, traceLast), t.excludeTipMm, lo, hi);
  return rows;
}

namespace {

// b as the angle nearest a (degrees): differences of directions, not of their numbers
double angleNear(double a, double b) { return a + std::remainder(b - a, 360.0); }

// the outputs at each time, in order: length, tip lateral, tip downhill, then the tip angle where defined;
// then the last time's strongest wave (wave: empty without one)
Eigen::VectorXd timeLapseValues(const std::vector<TraceAtTime>& at, const std::vector<bool>& withTheta, const std::vector<double>& thetaRef,
                                const std::vector<double>& wave) {
  std::vector<double> v;
  for (std::size_t i = 0; i < at.size(); ++i) {
    v.insert(v.end(), {at[i].lengthMm, at[i].tipLateralMm, at[i].tipDownhillMm});
    if (withTheta[i]) v.push_back(thetaRef.empty() ? at[i].thetaTipDeg : angleNear(thetaRef[i], at[i].thetaTipDeg));
  }
  v.insert(v.end(), wave.begin(), wave.end());
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace

TimeLapseObjective timeLapseObjective(const TraceTarget& t, int draws) {
  if (t.timesH.empty()) throw SceneError(t.file + ": root " + t.rootKey + " has no observation times (a trace of one time)");
  const double pixel = tipPixelMm(t);
  const std::vector<TraceAtTime> raw = traceAtTimes(t.plateMm, t.timesH, t.observationTimesH, pixel);
  if (raw.size() < 2)
    throw SceneError(t.file + ": root " + t.rootKey + " has a length at " + std::to_string(raw.size()) +
                     " observation time(s); a time-lapse needs at least 2");
  TimeLapseObjective o;
  std::vector<double> thetaRef;
  for (const TraceAtTime& r : raw) {
    o.timesH.push_back(r.timeH);
    o.withTheta.push_back(r.thetaDefined);
    thetaRef.push_back(r.thetaTipDeg);
  }
  // the clean side of the draws: the trace's distinct points, denoised, with their times
  const std::vector<int> keep = distinctPoints(t.plateMm);
  Eigen::Matrix3Xd pts(3, static_cast<Eigen::Index>(keep.size()));
  std::vector<double> times;
  for (std::size_t i = 0; i < keep.size(); ++i) {
    pts.col(static_cast<Eigen::Index>(i)) = t.plateMm.col(keep[i]);
    times.push_back(t.timesH[static_cast<std::size_t>(keep[i])]);
  }
  const Eigen::Matrix3Xd clean = denoised(pts);
  // the strongest wave at the last time, over the range the trace's own points resolve
  const Eigen::Matrix3Xd lastTrace = polylineAtTime(t.plateMm, t.timesH, o.timesH.back());
  const std::pair<double, double> range = waveRange(lastTrace, t.excludeTipMm);
  o.withWave = std::isfinite(strongestWave(lastTrace, t.excludeTipMm, range.first, range.second).wavelengthMm);
  auto waveOf = [&](const Eigen::Matrix3Xd& p, const std::vector<double>& at) {
    if (!o.withWave) return std::vector<double>{};
    const WaveFit w = strongestWave(polylineAtTime(p, at, o.timesH.back()), t.excludeTipMm, range.first, range.second);
    return std::vector<double>{w.wavelengthMm, w.amplitudeMm};
  };
  auto valuesOf = [&](const Eigen::Matrix3Xd& p) {
    const std::vector<TraceAtTime> at = traceAtTimes(p, times, o.timesH, pixel);
    if (at.size() != o.timesH.size()) throw SceneError(t.file + ": root " + t.rootKey + ": a noisy draw lost an observation time");
    return timeLapseValues(at, o.withTheta, thetaRef, waveOf(p, times));
  };
  // the trace's uncertainty as every objective takes it (traceUncertainty): the covariance of the values
  // and their mean shift (a noisy polyline is longer), taken off the trace's values
  const Eigen::MatrixXd y = noiseDraws(clean, t.sigmaMm, draws, valuesOf);
  const Eigen::MatrixXd centred = y.rowwise() - y.colwise().mean();
  o.trace.cov = centred.transpose() * centred / static_cast<double>(draws - 1);
  // a tracer dates every point of a root it first sees with that time: its tip then lies somewhere between
  // the last point so dated and the next point, which the trace's own writer may or may not have put at
  // the tip. Length and tip at that time carry that point gap h as an error along the root, uniform on
  // [0, h]: h^2 / 3 about the last dated point (the synthetic 2D+t plate's 0 h root ends 0.24 mm short)
  for (std::size_t k = 0, at = 0; k < o.timesH.size(); at += 3 + (o.withTheta[k] ? 1 : 0), ++k) {
    const auto after = std::upper_bound(t.timesH.begin(), t.timesH.end(), o.timesH[k]);
    const long i = static_cast<long>(after - t.timesH.begin()) - 1;
    if (i < 1 || i + 1 >= static_cast<long>(t.timesH.size()) || t.timesH[static_cast<std::size_t>(i - 1)] != o.timesH[k]) continue;
    const Eigen::Vector2d gap = (t.plateMm.col(i + 1) - t.plateMm.col(i)).head<2>();
    const double h = gap.norm();
    if (!(h > 0)) continue;
    Eigen::Vector3d d(1.0, gap.x() / h, gap.y() / h);  // length, tip lateral, tip downhill per unit along the root
    o.trace.cov.block(static_cast<Eigen::Index>(at), static_cast<Eigen::Index>(at), 3, 3) += d * d.transpose() * (h * h / 3.0);
  }
  o.trace.sigma = o.trace.cov.diagonal().cwiseSqrt();
  o.bias = y.colwise().mean().transpose() - valuesOf(clean);
  o.trace.trace = timeLapseValues(raw, o.withTheta, thetaRef, waveOf(t.plateMm, t.timesH)) - o.bias;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const std::string at = "@" + numberText(raw[i].timeH) + "h";
    for (const char* n : {"length_mm", "tip_lateral_mm", "tip_downhill_mm"}) o.trace.names.push_back(n + at);
    if (o.withTheta[i]) o.trace.names.push_back("theta_tip_deg" + at);
  }
  if (o.withWave)
    for (const char* n : {"wave_lambda_mm", "wave_amplitude_mm"}) o.trace.names.push_back(n + ("@" + numberText(raw.back().timeH) + "h"));
  // dL/dt: the generalised least-squares slope of the lengths over time, with the lengths' covariance
  std::vector<int> li;
  for (int c = 0; c < static_cast<int>(o.trace.names.size()); ++c)
    if (o.trace.names[static_cast<std::size_t>(c)].rfind("length_mm@", 0) == 0) li.push_back(c);
  const int m = static_cast<int>(li.size());
  Eigen::MatrixXd X(m, 2), C(m, m);
  Eigen::VectorXd L(m);
  for (int a = 0; a < m; ++a) {
    X(a, 0) = 1;
    X(a, 1) = o.timesH[static_cast<std::size_t>(a)];
    L(a) = o.trace.trace(li[static_cast<std::size_t>(a)]);
    for (int b = 0; b < m; ++b) C(a, b) = o.trace.cov(li[static_cast<std::size_t>(a)], li[static_cast<std::size_t>(b)]);
  }
  const Eigen::MatrixXd Ci = C.ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  const Eigen::Matrix2d F = X.transpose() * Ci * X;
  const Eigen::Vector2d beta = F.ldlt().solve(X.transpose() * Ci * L);
  o.growthMmPerH = beta(1);
  o.growthSigma = std::sqrt(F.inverse()(1, 1));
  return o;
}

FitComponents timeLapseComponents(const TimeLapseObjective& o, const std::vector<TimeLapseRow>& rows) {
  if (rows.size() != o.timesH.size())
    throw std::invalid_argument("the run has " + std::to_string(rows.size()) + " of the trace's " + std::to_string(o.timesH.size()) + " observation times");
  FitComponents c = o.trace;
  std::vector<TraceAtTime> run;
  std::vector<double> thetaRef;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].timeH != o.timesH[i]) throw std::invalid_argument("the run's rows are not at the trace's observation times");
    TraceAtTime r;
    r.timeH = rows[i].timeH;
    r.lengthMm = rows[i].runLengthMm;
    r.tipLateralMm = rows[i].runTipLateralMm;
    r.tipDownhillMm = rows[i].runTipDownhillMm;
    r.thetaTipDeg = rows[i].runThetaTipDeg;
    run.push_back(r);
    thetaRef.push_back(rows[i].traceThetaTipDeg);
  }
  std::vector<double> wave;
  if (o.withWave) wave = {rows.back().runWave.wavelengthMm, rows.back().runWave.amplitudeMm};
  c.sim = timeLapseValues(run, o.withTheta, thetaRef, wave);
  return c;
}

std::string comparisonCaption(const Comparison& c) {
  char b[256];
  std::snprintf(b, sizeof b, "distance %.3g mm (RMS at equal arc length), Fréchet %.3g mm, χ² %.3g (%d observable%s)",
                c.distanceMm, c.frechetMm, c.chi2, c.used, c.used == 1 ? "" : "s");
  return b;
}

std::string observablesCsv(const Comparison& c) {
  std::string out = "observable,unit,trace,sim,sigma,residual,used,how\n";
  auto cell = [](double v) { return std::isfinite(v) ? numberText(v) : std::string(); };
  for (const Observation& o : c.obs)
    out += o.name + "," + o.unit + "," + cell(o.trace) + "," + cell(o.sim) + "," + cell(o.used ? o.sigma : std::numeric_limits<double>::quiet_NaN()) + "," +
           cell(o.used ? o.residual() : std::numeric_limits<double>::quiet_NaN()) + "," + (o.used ? "1" : "0") + ",\"" + o.why + "\"\n";
  return out;
}

namespace {

Json observablesJson(const Comparison& c) {
  Json j;
  for (const Observation& o : c.obs) {
    Json e;
    e.str("unit", o.unit).num("trace", o.trace).num("sim", o.sim).boolean("used", o.used);
    if (o.used) e.num("sigma", o.sigma).num("residual", o.residual());
    e.str("how", o.why);
    j.object(o.name, e);
  }
  return j;
}

std::string timeLapseCsv(const std::vector<TimeLapseRow>& rows) {
  std::string out = "time_h,snapshot_h,trace_length_mm,run_length_mm,trace_tip_lateral_mm,trace_tip_downhill_mm,run_tip_lateral_mm,"
                    "run_tip_downhill_mm,trace_theta_tip_deg,run_theta_tip_deg,distance_mm\n";
  auto cell = [](double v) { return std::isfinite(v) ? numberText(v) : std::string(); };
  for (const TimeLapseRow& r : rows)
    out += cell(r.timeH) + "," + cell(r.snapshotH) + "," + cell(r.traceLengthMm) + "," + cell(r.runLengthMm) + "," + cell(r.traceTipLateralMm) + "," +
           cell(r.traceTipDownhillMm) + "," + cell(r.runTipLateralMm) + "," + cell(r.runTipDownhillMm) + "," + cell(r.traceThetaTipDeg) + "," +
           cell(r.runThetaTipDeg) + "," + cell(r.distanceMm) + "\n";
  return out;
}

// the run's snapshot a trace is compared with: the one nearest --at-h, else the first as long as the trace
// (the final one when none is); why says which
int pickSnapshot(const Model& m, const std::vector<Snapshot>& snaps, const TraceTarget& target, double atH, std::string& why) {
  int pick = static_cast<int>(snaps.size()) - 1;
  why = "the final snapshot";
  if (atH != CompareOptions::kUnset) {
    why = "the snapshot nearest --at-h";
    return snapshotNear(snapshotTimes(snaps), atH);
  }
  // (to a micrometre: a run's own export has its nodes' length up to rounding)
  if (polylineLength(plateView(m, snaps.back())) >= target.rootLengthMm - 1e-3) {
    why = "the snapshot as long as the trace on the plate (the nearest)";
    return snapshotOfLength(m, snaps, target.rootLengthMm);
  }
  why = "the final snapshot (the run is shorter than the trace)";
  return pick;
}

void printTable(const Comparison& c) {
  std::printf("%-18s %12s %12s %10s %9s\n", "observable", "trace", "simulation", "sigma", "residual");
  for (const Observation& o : c.obs) {
    if (o.used)
      std::printf("%-18s %12.4g %12.4g %10.3g %9.3g\n", (o.name).c_str(), o.trace, o.sim, o.sigma, o.residual());
    else
      std::printf("%-18s %12.4g %12.4g %10s %9s\n", (o.name).c_str(), o.trace, o.sim, "-", "(shown)");
  }
  std::printf("%s\n", comparisonCaption(c).c_str());
}

// ---- a plate's run against a traced plate ----

}  // namespace

std::vector<TracedPlant> tracedPlants(const TraceFile& tf, const std::string& file) {
  std::vector<TracedPlant> plants;
  for (int k = 0; k < static_cast<int>(tf.roots.size()); ++k) {
    const TracedRoot& r = tf.roots[static_cast<std::size_t>(k)];
    if (r.parentIndex >= 0) continue;
    const std::string id = r.key.substr(0, r.key.find('/'));
    if (std::any_of(plants.begin(), plants.end(), [&](const TracedPlant& p) { return p.id == id; })) continue;
    TracedPlant p;
    p.id = id;
    p.label = r.plantLabel;
    p.file = file;
    p.root = k;
    p.seedMm = (r.originMm + r.plateMm.col(0)).head<2>();
    plants.push_back(p);
  }
  return plants;
}

std::vector<SheetRow> readSampleSheet(const std::string& sheet, const std::string& column, const std::vector<TracedPlant>& plants,
                                      const std::string& optionalColumn) {
  std::ifstream in(sheet);
  if (!in) throw SceneError("--groups " + sheet + ": cannot be read (not found?)");
  std::string line;
  const std::string expected = "plant," + column;
  if (!std::getline(in, line)) throw SceneError(sheet + ":1: empty; expected a header with the columns " + expected);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> head = splitCommas(line);
  const auto col = [&](const std::string& name) {
    const auto it = std::find(head.begin(), head.end(), name);
    if (it == head.end()) throw SceneError(sheet + ":1: no column " + name + " (the header: " + line + "; expected " + expected + ")");
    return static_cast<std::size_t>(it - head.begin());
  };
  const std::size_t cp = col("plant"), cv = col(column);
  const auto oi = optionalColumn.empty() ? head.end() : std::find(head.begin(), head.end(), optionalColumn);
  const std::size_t co = oi == head.end() ? std::string::npos : static_cast<std::size_t>(oi - head.begin());
  std::vector<SheetRow> rows;
  std::vector<int> plantLine(plants.size(), 0);
  for (int n = 2; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> cells = splitCommas(line);
    const std::string at = sheet + ":" + std::to_string(n);
    if (cells.size() <= std::max(cp, cv)) throw SceneError(at + ": " + std::to_string(cells.size()) + " cell(s); expected " + std::to_string(head.size()));
    const std::string& pn = cells[cp];
    if (cells[cv].empty()) throw SceneError(at + ": plant " + pn + ": no " + column + " (the " + column + " column is empty)");
    int p = -1;
    for (int k = 0; k < static_cast<int>(plants.size()); ++k) {
      const TracedPlant& q = plants[static_cast<std::size_t>(k)];
      if (q.id != pn && (q.label.empty() || q.label != pn)) continue;
      if (p >= 0)
        throw SceneError(at + ": plant " + pn + " names two plants (" + plants[static_cast<std::size_t>(p)].file + " and " + q.file +
                         "); name it by a label or id only one of them has");
      p = k;
    }
    if (p < 0) {
      std::string names;
      for (const TracedPlant& q : plants) names += (names.empty() ? "" : ", ") + q.id + (q.label.empty() ? "" : " (" + q.label + ")");
      throw SceneError(at + ": plant " + pn + ": not a plant of the trace (its plants: " + names + "); correct the name or remove the line");
    }
    if (const int first = plantLine[static_cast<std::size_t>(p)])
      throw SceneError(at + ": plant " + pn + " named twice (first on line " + std::to_string(first) + ")");
    plantLine[static_cast<std::size_t>(p)] = n;
    rows.push_back(SheetRow{p, cells[cv], n, co < cells.size() ? cells[co] : std::string()});
  }
  if (rows.empty()) throw SceneError(sheet + ": no rows; expected one " + expected + " row per line after the header");
  return rows;
}

namespace {

// --groups SHEET.csv pairing plants with seedlings: readSampleSheet's rows, each seedling named once
std::vector<std::pair<int, int>> sheetPairs(const std::string& sheet, const std::vector<PlateRoot>& seedlings,
                                            const std::vector<TracedPlant>& plants) {
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> seedlingLine(seedlings.size(), 0);
  for (const SheetRow& row : readSampleSheet(sheet, "seedling", plants)) {
    const std::string at = sheet + ":" + std::to_string(row.line);
    int sd = -1;
    for (int k = 0; k < static_cast<int>(seedlings.size()); ++k)
      if (seedlings[static_cast<std::size_t>(k)].name == row.value) sd = k;
    if (sd < 0) {
      std::string names;
      for (const PlateRoot& q : seedlings) names += (names.empty() ? "" : ", ") + q.name;
      throw SceneError(at + ": seedling " + row.value + ": not a seedling of the run (its seedlings: " + names + ")");
    }
    if (const int first = seedlingLine[static_cast<std::size_t>(sd)])
      throw SceneError(at + ": seedling " + row.value + " named twice (first on line " + std::to_string(first) + ")");
    seedlingLine[static_cast<std::size_t>(sd)] = row.line;
    pairs.emplace_back(sd, row.plant);
  }
  return pairs;
}

// the nearest seeds: the traced seeds moved by the difference of the two plates' mean seeds (a trace's
// origin is its image's corner, not the plate's), then the closest (seedling, plant) pairs first, each
// seedling and each plant in one pair at most
std::vector<std::pair<int, int>> nearestPairs(const std::vector<PlateRoot>& seedlings, const std::vector<TracedPlant>& plants,
                                              Eigen::Vector2d& shift) {
  Eigen::Vector2d ms = Eigen::Vector2d::Zero(), mp = Eigen::Vector2d::Zero();
  for (const PlateRoot& r : seedlings) ms += r.seedling.position / units::mm;
  for (const TracedPlant& p : plants) mp += p.seedMm;
  shift = ms / static_cast<double>(seedlings.size()) - mp / static_cast<double>(plants.size());
  std::vector<std::tuple<double, int, int>> all;
  for (int a = 0; a < static_cast<int>(seedlings.size()); ++a)
    for (int b = 0; b < static_cast<int>(plants.size()); ++b)
      all.emplace_back((seedlings[static_cast<std::size_t>(a)].seedling.position / units::mm - plants[static_cast<std::size_t>(b)].seedMm - shift).norm(), a, b);
  std::sort(all.begin(), all.end());
  std::vector<bool> usedS(seedlings.size()), usedP(plants.size());
  std::vector<std::pair<int, int>> pairs;
  for (const auto& [d, a, b] : all) {
    if (usedS[static_cast<std::size_t>(a)] || usedP[static_cast<std::size_t>(b)]) continue;
    usedS[static_cast<std::size_t>(a)] = usedP[static_cast<std::size_t>(b)] = true;
    pairs.emplace_back(a, b);
  }
  std::sort(pairs.begin(), pairs.end());  // in the seedlings' order
  return pairs;
}

int comparePlate(const CompareOptions& o, const fs::path& run, const fs::path& out, const WriteRule& rule,
                 const std::string& runName, std::string* outDir) {
  const Scene plate = loadScene((run / "scene.toml").string());
  std::vector<PlateRoot> seedlings;
  for (const PlateRoot& r : plateRoots(run))
    if (r.parent.empty()) seedlings.push_back(r);
  if (!o.trace.root.empty()) throw SceneError("--root " + o.trace.root + ": " + o.runDir + " is a plate's run; its plants are paired by seed or --groups");
  // the traced plants, read once as the plate's model measures them
  AnalyzeOptions a;
  a.pxPerMm = o.trace.pxPerMm;
  a.downhill = o.trace.downhill;
  a.excludeTipMm = plate.model.growth.zoneLength / units::mm;
  a.radiusMm = plate.model.rod.radius / units::mm;
  a.flagPrefix = o.trace.flagPrefix;
  checkTraceFlags(a);
  const TraceFile tf = readTraceFile(o.trace.trace, a);
  const std::vector<TracedPlant> plants = tracedPlants(tf);
  if (plants.empty()) throw SceneError(o.trace.trace + ": no primary root (order 0) to pair with a seedling");
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  const bool bySheet = !o.groups.empty();
  const std::vector<std::pair<int, int>> pairs = bySheet ? sheetPairs(o.groups, seedlings, plants) : nearestPairs(seedlings, plants, shift);

  // one loop over the pairs: each compared as one root is (compareRoots), its seedling's own model
  struct Pair {
    std::string seedling, plant, why;
    TraceTarget target;
    SimRoot sim;
    Comparison c;
  };
  std::vector<Pair> done;
  std::vector<Snapshot> simPlate;
  std::vector<std::string> names;
  const PlateFrame pf = plate.model.env.plane.frame();
  for (const auto& [sd, pl] : pairs) {
    const PlateRoot& root = seedlings[static_cast<std::size_t>(sd)];
    const TracedPlant& plant = plants[static_cast<std::size_t>(pl)];
    const Scene own = loadScene((root.dir / "scene.toml").string());
    const Model& m = singleRootModel(own, "compare: " + root.dir.string());
    TraceFlags f = o.trace;
    f.root = tf.roots[static_cast<std::size_t>(plant.root)].key;
    Pair p;
    p.seedling = root.name;
    p.plant = plant.id + (plant.label.empty() ? "" : " (" + plant.label + ")");
    p.target = loadTarget(f, m);
    const std::vector<Snapshot> snaps = loadSnapshots(root.dir);
    const int pick = pickSnapshot(m, snaps, p.target, o.atH, p.why);
    p.sim = simRootOf(m, snaps[static_cast<std::size_t>(pick)], p.target);
    p.c = compareRoots(p.target, p.sim);
    done.push_back(std::move(p));
  }
  // the pictures: every root of the run at the first pair's snapshot time, every traced root moved onto
  // the plate (a paired plant's seed onto its seedling's, an unpaired one by the mean shift)
  const double atH = done.front().sim.timeH;
  for (const PlateRoot& r : plateRoots(run)) {
    const std::vector<Snapshot> snaps = loadSnapshots(r.dir);
    if (snaps.front().timeH > atH + 1e-9) continue;  // a lateral root not emerged by then
    Snapshot s = snaps[static_cast<std::size_t>(nearestSnapshot(snapshotTimes(snaps), atH))];
    s.x.colwise() += plateOffset(pf, r);
    simPlate.push_back(std::move(s));
    names.push_back(r.parent.empty() ? r.name : "");
  }
  std::vector<Eigen::Vector2d> plantShift(plants.size(), shift);
  if (bySheet) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (const auto& [sd, pl] : pairs)
      sum += seedlings[static_cast<std::size_t>(sd)].seedling.position / units::mm - plants[static_cast<std::size_t>(pl)].seedMm;
    plantShift.assign(plants.size(), sum / static_cast<double>(pairs.size()));
  }
  for (const auto& [sd, pl] : pairs)
    plantShift[static_cast<std::size_t>(pl)] = seedlings[static_cast<std::size_t>(sd)].seedling.position / units::mm - plants[static_cast<std::size_t>(pl)].seedMm;
  std::vector<Eigen::Matrix3Xd> traces;
  std::vector<std::string> traceNames;  // each plant's id at its primary root's seed
  for (const TracedRoot& r : tf.roots) {
    std::size_t p = 0;
    while (p < plants.size() && r.key.substr(0, r.key.find('/')) != plants[p].id) ++p;
    Eigen::Matrix3Xd t = r.plateMm;
    for (int i = 0; i < t.cols(); ++i) {
      t.col(i) += r.originMm;
      if (p < plants.size()) t.col(i).head<2>() += plantShift[p];
    }
    traces.push_back(std::move(t));
    const bool primary = p < plants.size() && &tf.roots[static_cast<std::size_t>(plants[p].root)] == &r;
    traceNames.push_back(primary ? "plant " + plants[p].id : "");
  }

  StagedFolder folder(out, compareFolder(), rule, "--out");
  std::string pairsCsv = "seedling,plant,root,time_h,step,snapshot,distance_mm,frechet_mm,chi2,observables_used\n";
  std::string obsCsv;
  std::vector<Json> items;
  for (const Pair& p : done) {
    pairsCsv += csvField(p.seedling) + "," + csvField(p.plant) + "," + csvField(p.target.rootKey) + "," + numberText(p.sim.timeH) + "," +
                std::to_string(p.sim.step) + "," + csvField(p.why) + "," + numberText(p.c.distanceMm) + "," + numberText(p.c.frechetMm) + "," +
                numberText(p.c.chi2) + "," + std::to_string(p.c.used) + "\n";
    const std::string rows = observablesCsv(p.c);
    const auto nl = rows.find('\n');
    if (obsCsv.empty()) obsCsv = "seedling,plant," + rows.substr(0, nl + 1);
    for (std::size_t at = nl + 1; at < rows.size();) {
      const auto end = rows.find('\n', at);
      obsCsv += csvField(p.seedling) + "," + csvField(p.plant) + "," + rows.substr(at, end - at + 1);
      at = end + 1;
    }
    Json e;
    e.str("seedling", p.seedling).str("plant", p.plant).str("root", p.target.rootKey).num("time_h", p.sim.timeH).integer("step", p.sim.step);
    e.str("snapshot", p.why).num("sigma_mm", p.target.sigmaMm).str("sigma_source", p.target.sigmaSource).num("smoothing_mm", p.target.traits.smoothingMm);
    e.num("distance_mm", p.c.distanceMm).num("frechet_mm", p.c.frechetMm).num("chi2", p.c.chi2).integer("observables_used", p.c.used);
    e.object("observables", observablesJson(p.c));
    items.push_back(e);
  }
  std::vector<std::string> lonelySeedlings, lonelyPlants;
  for (std::size_t k = 0; k < seedlings.size(); ++k)
    if (std::none_of(pairs.begin(), pairs.end(), [&](const auto& q) { return q.first == static_cast<int>(k); })) lonelySeedlings.push_back(seedlings[k].name);
  for (std::size_t k = 0; k < plants.size(); ++k)
    if (std::none_of(pairs.begin(), pairs.end(), [&](const auto& q) { return q.second == static_cast<int>(k); })) lonelyPlants.push_back(plants[k].id);
  auto joined = [](const std::vector<std::string>& v) {
    std::string t;
    for (const std::string& x : v) t += (t.empty() ? "" : ", ") + x;
    return t;
  };
  Json j;
  j.str("software", outputSignatureText()).str("run", o.runDir).str("trace", o.trace.trace).str("kind", "plate");
  j.str("paired_by", bySheet ? "sample sheet " + o.groups : "nearest seed (the traced seeds moved by the difference of the mean seeds)");
  j.str("distance", "root-mean-square distance between the roots' points at equal arc length from the seed, over the shorter root");
  j.array("pairs", items);
  j.str("unpaired_seedlings", joined(lonelySeedlings)).str("unpaired_plants", joined(lonelyPlants));
  writeFileAtomic(folder.work() / "compare.json", j.dump() + "\n");
  writeFileAtomic(folder.work() / "pairs.csv", pairsCsv);
  writeFileAtomic(folder.work() / "compare.csv", obsCsv);
  double meanD = 0;
  for (const Pair& p : done) meanD += p.c.distanceMm / static_cast<double>(done.size());
  char caption[160];
  std::snprintf(caption, sizeof caption, "%zu pair%s, mean distance %.3g mm", done.size(), done.size() == 1 ? "" : "s", meanD);
  savePlateComparePanel(plate.model, simPlate, names, traces, traceNames,
                        "traced plate " + literalLabel(fs::path(o.trace.trace).filename().string()) + " beside plate run " + literalLabel(runName) +
                            " at " + numberText(std::round(atH * 100) / 100) + " h",
                        caption, (folder.work() / "compare").string());
  folder.commit();
  if (outDir) *outDir = out.string();
  if (o.printTable)
    for (const Pair& p : done) {
      std::printf("seedling %s - plant %s (%s)\n", p.seedling.c_str(), p.plant.c_str(), p.why.c_str());
      printTable(p.c);
    }
  if (!o.quiet)
    std::fprintf(stderr, "wrote %s (compare.json, pairs.csv, compare.csv, compare.pdf/.svg/.png; %zu pairs%s%s)\n", out.c_str(), done.size(),
                 lonelySeedlings.empty() ? "" : ("; unpaired seedlings: " + joined(lonelySeedlings)).c_str(),
                 lonelyPlants.empty() ? "" : ("; unpaired plants: " + joined(lonelyPlants)).c_str());
  return 0;
}

}  // namespace

int compareCommand(const CompareOptions& o, std::string* outDir) {
  if (o.atH != CompareOptions::kUnset) checkedNumber("--at-h", o.atH, kGrowthHours);
  const fs::path run = o.runDir;
  const std::string runName = fs::absolute(run).lexically_normal().filename().string();
  const std::string outText =
      o.out.empty() ? (fs::path("compare") / (runName + "_vs_" + fs::path(o.trace.trace).stem().string())).string() : o.out;
  const fs::path out = checkOutputName(outText, "--out");
  if (const std::string why = whyUnfinished(run); !why.empty()) throw SceneError(o.runDir + ": " + why);
  // locked before any work (the StagedFolder below takes it again)
  const OutputLock lock = lockOutput(out, "--out");
  if (!fs::is_directory(run) || !whyNotOurs(run, runFolder()).empty())
    throw SceneError(o.runDir + ": not a run directory (" + (fs::is_directory(run) ? whyNotOurs(run, runFolder()) : "not found") + ")");
  WriteRule rule;
  rule.force = o.force;
  rule.inputs.push_back(WriteInput{run, {}, true});
  rule.inputs.push_back(WriteInput{o.trace.trace, {}, true});
  if (!o.groups.empty()) rule.inputs.push_back(WriteInput{o.groups, {}, true});
  rule.inputs.push_back(workingFolder());
  claimFolder(out, compareFolder(), rule, "--out", true);
  if (isPlateRun(run)) return comparePlate(o, run, out, rule, runName, outDir);
  if (!o.groups.empty()) throw SceneError("--groups " + o.groups + ": " + o.runDir + " is a run of one root (--groups pairs a plate's plants)");

  const Scene scene = loadScene((run / "scene.toml").string());
  const Model& m = singleRootModel(scene, "compare: " + o.runDir);
  const TraceTarget target = loadTarget(o.trace, m);
  const std::vector<Snapshot> snaps = loadSnapshots(run);
  std::string why;
  const int pick = pickSnapshot(m, snaps, target, o.atH, why);
  const Snapshot& snap = snaps[static_cast<std::size_t>(pick)];
  const SimRoot sim = simRootOf(m, snap, target);
  const Comparison c = compareRoots(target, sim);

  StagedFolder folder(out, compareFolder(), rule, "--out");
  Json j;
  j.str("software", outputSignatureText())
      .str("run", o.runDir)
      .str("trace", o.trace.trace)
      .str("root", target.rootKey)
      .num("time_h", sim.timeH)
      .integer("step", sim.step)
      .str("snapshot", why)
      .num("sigma_mm", target.sigmaMm)
      .str("sigma_source", target.sigmaSource)
      .num("smoothing_mm", target.traits.smoothingMm)
      .num("trace_ds_mm", target.dsMm)
      .num("distance_mm", c.distanceMm)
      .str("distance", "root-mean-square distance between the roots' points at equal arc length from the seed, over the shorter root")
      .num("frechet_mm", c.frechetMm)
      .num("chi2", c.chi2)
      .integer("observables_used", c.used)
      .object("observables", observablesJson(c));
  // a time-lapse trace: the run at every observation time
  const std::vector<TimeLapseRow> lapse = compareTimeLapse(target, m, snaps);
  if (!lapse.empty()) {
    std::vector<Json> items;
    for (const TimeLapseRow& r : lapse) {
      Json e;
      e.num("time_h", r.timeH).num("snapshot_h", r.snapshotH).num("trace_length_mm", r.traceLengthMm).num("run_length_mm", r.runLengthMm);
      e.num("trace_tip_lateral_mm", r.traceTipLateralMm).num("trace_tip_downhill_mm", r.traceTipDownhillMm);
      e.num("run_tip_lateral_mm", r.runTipLateralMm).num("run_tip_downhill_mm", r.runTipDownhillMm);
      e.num("trace_theta_tip_deg", r.traceThetaTipDeg).num("run_theta_tip_deg", r.runThetaTipDeg).num("distance_mm", r.distanceMm);
      items.push_back(e);
    }
    j.array("time_lapse", items);
    writeFileAtomic(folder.work() / "timelapse.csv", timeLapseCsv(lapse));
  }
  writeFileAtomic(folder.work() / "compare.json", j.dump() + "\n");
  writeFileAtomic(folder.work() / "compare.csv", observablesCsv(c));
  saveComparePanel(m, snap, target.plateMm,
                   "trace " + literalLabel(fs::path(o.trace.trace).filename().string() + " (" + target.rootKey + ")") + " over run " + literalLabel(runName) +
                       " at " + numberText(std::round(sim.timeH * 100) / 100) + " h",
                   comparisonCaption(c), (folder.work() / "compare").string());
  folder.commit();
  if (outDir) *outDir = out.string();
  if (o.printTable) printTable(c);
  if (!o.quiet) std::fprintf(stderr, "wrote %s (compare.json, compare.csv, compare.pdf/.svg/.png; %s)\n", out.c_str(), why.c_str());
  return 0;
}

}  // namespace rootsim::app
