// `rootsim compare RUN_DIR TRACE.rsml`: a traced root beside a run's root (docs/experiments.md, "Compare").
#include "rootsim/compare_trace.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "rootsim/compare_panel.hpp"
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

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

constexpr double kDefaultSigmaMm = 0.05;   // one pixel of a 20 px/mm plate scan [mm]
constexpr double kDistanceStepMm = 0.05;   // the shape distances' sampling step (a run's element) [mm]

bool given(double v) { return v != TraceFlags::kUnset; }

}  // namespace

TraceTarget loadTarget(const TraceFlags& f, const Model& m) {
  if (given(f.sigmaMm)) checkedNumber(f.flagPrefix + "sigma-mm", f.sigmaMm, {0, 10, true, false, "mm"});
  AnalyzeOptions a;
  a.pxPerMm = f.pxPerMm;
  a.downhill = f.downhill;
  // the trace is measured as the run: its growth zone left out, the run's R for the peaks' hysteresis
  a.excludeTipMm = m.growth.zoneLength / units::mm;
  a.radiusMm = m.rod.radius / units::mm;
  a.flagPrefix = f.flagPrefix;
  checkTraceFlags(a);
  const TraceFile tf = readTraceFile(f.trace, a);
  const TracedRoot& r = pickRoot(tf, f.root, f.flagPrefix + "root");
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
  if (given(f.sigmaMm)) {
    t.sigmaMm = f.sigmaMm;
    t.sigmaSource = f.flagPrefix + "sigma-mm";
  } else if (tf.pixelMm > 0) {
    t.sigmaMm = tf.pixelMm;
    t.sigmaSource = "pixel";
  } else {
    t.sigmaMm = kDefaultSigmaMm;
    t.sigmaSource = "default";
  }
  return t;
}

SimRoot simRootOf(const Model& m, const Snapshot& s) {
  const PlateFrame pf = m.env.plane.frame();
  SimRoot r;
  r.timeH = s.timeH;
  r.step = s.step;
  r.plateMm.resize(3, s.x.cols());
  for (int i = 0; i < s.x.cols(); ++i) r.plateMm.col(i) = pf.coords(s.x.col(i) - s.x.col(0)) / units::mm;
  // the run's nodes as they are, its growth zone left out: what summary.json measures (analyseShape)
  r.traits = rootTraits(r.plateMm, 0.0, m.growth.zoneLength / units::mm, m.rod.radius / units::mm, m.analysis);
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

double tipPixelMm(const TraceTarget& t) { return t.sigmaSource == "pixel" ? t.sigmaMm : 0.0; }

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
  const Eigen::Matrix3Xd last = simRootOf(m, snaps[static_cast<std::size_t>(near(traced.back().timeH))]).plateMm;
  std::vector<double> arc(static_cast<std::size_t>(last.cols()), 0.0);
  for (Eigen::Index i = 1; i < last.cols(); ++i)
    arc[static_cast<std::size_t>(i)] = arc[static_cast<std::size_t>(i - 1)] + (last.col(i) - last.col(i - 1)).norm();
  for (const TraceAtTime& tr : traced) {
    const double at = tr.timeH;
    const Eigen::Matrix3Xd trace = polylineAtTime(t.plateMm, t.timesH, at);
    const SimRoot sim = simRootOf(m, snaps[static_cast<std::size_t>(near(at))]);
    const double length = polylineLength(sim.plateMm);
    const Eigen::Matrix3Xd run = polylineAtTime(last, arc, std::min(length, arc.back()));
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
  return rows;
}

namespace {

// b as the angle nearest a (degrees): differences of directions, not of their numbers
double angleNear(double a, double b) { return a + std::remainder(b - a, 360.0); }

// the outputs at each time, in order: length, tip lateral, tip downhill, then the tip angle where defined
Eigen::VectorXd timeLapseValues(const std::vector<TraceAtTime>& at, const std::vector<bool>& withTheta, const std::vector<double>& thetaRef) {
  std::vector<double> v;
  for (std::size_t i = 0; i < at.size(); ++i) {
    v.insert(v.end(), {at[i].lengthMm, at[i].tipLateralMm, at[i].tipDownhillMm});
    if (withTheta[i]) v.push_back(thetaRef.empty() ? at[i].thetaTipDeg : angleNear(thetaRef[i], at[i].thetaTipDeg));
  }
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace

double timeLapseNoiseMm(const TraceTarget& t) {
  const double noise = t.traits.noiseMm;
  return t.sigmaSource != "--sigma-mm" && std::isfinite(noise) && noise > 0 ? noise : t.sigmaMm;
}

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
  auto valuesOf = [&](const Eigen::Matrix3Xd& p) {
    const std::vector<TraceAtTime> at = traceAtTimes(p, times, o.timesH, pixel);
    if (at.size() != o.timesH.size()) throw SceneError(t.file + ": root " + t.rootKey + ": a noisy draw lost an observation time");
    return timeLapseValues(at, o.withTheta, thetaRef);
  };
  // the weights: the trace's uncertainty as every objective takes it; the bias: its noise as estimated
  const Eigen::MatrixXd y = noiseDraws(clean, t.sigmaMm, draws, valuesOf);
  const Eigen::MatrixXd centred = y.rowwise() - y.colwise().mean();
  o.trace.cov = centred.transpose() * centred / static_cast<double>(draws - 1);
  o.trace.sigma = o.trace.cov.diagonal().cwiseSqrt();
  const double noise = timeLapseNoiseMm(t);
  o.bias = (noise == t.sigmaMm ? y : noiseDraws(clean, noise, draws, valuesOf)).colwise().mean().transpose() - valuesOf(clean);
  o.trace.trace = timeLapseValues(raw, o.withTheta, thetaRef) - o.bias;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const std::string at = "@" + numberText(raw[i].timeH) + "h";
    for (const char* n : {"length_mm", "tip_lateral_mm", "tip_downhill_mm"}) o.trace.names.push_back(n + at);
    if (o.withTheta[i]) o.trace.names.push_back("theta_tip_deg" + at);
  }
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
  c.sim = timeLapseValues(run, o.withTheta, thetaRef);
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
  rule.inputs.push_back(workingFolder());
  claimFolder(out, compareFolder(), rule, "--out", true);

  const Scene scene = loadScene((run / "scene.toml").string());
  const Model& m = singleRootModel(scene, "compare: " + o.runDir);
  const TraceTarget target = loadTarget(o.trace, m);
  const std::vector<Snapshot> snaps = loadSnapshots(run);
  int pick = static_cast<int>(snaps.size()) - 1;
  std::string why = "the final snapshot";
  if (o.atH != CompareOptions::kUnset) {
    pick = snapshotNear(snapshotTimes(snaps), o.atH);
    why = "the snapshot nearest --at-h";
  } else {
    // the first snapshot as long as the trace
    for (int i = 0; i < static_cast<int>(snaps.size()); ++i)
      // (to a micrometre: a run's own export has its nodes' length up to rounding)
      if (polylineLength(snaps[static_cast<std::size_t>(i)].x) / units::mm >= target.traits.lengthMm - 1e-3) {
        pick = i;
        why = "the first snapshot as long as the trace";
        break;
      }
    if (why == "the final snapshot") why = "the final snapshot (the run is shorter than the trace)";
  }
  const Snapshot& snap = snaps[static_cast<std::size_t>(pick)];
  const SimRoot sim = simRootOf(m, snap);
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
