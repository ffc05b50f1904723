#pragma once
// `rootsim compare RUN_DIR TRACE.rsml` (docs/experiments.md, "Compare"): a traced root beside a simulated
// one, both in plate coordinates and aligned at the seed: the picture, the observables side by side with
// the trace's uncertainties, chi-square, and two shape distances. Its pieces are what every evaluation of
// `rootsim fit` does.
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/analyze_traces.hpp"
#include "rootsim/model.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/trace_match.hpp"

namespace rootsim::app {

// a traced plant: its first primary root (order 0) and where its seed lies in the file's plate frame [mm]
struct TracedPlant {
  std::string id, label;
  std::string file;          // the RSML file it is in
  int root = -1;             // index in TraceFile::roots
  Eigen::Vector2d seedMm = Eigen::Vector2d::Zero();
};
// the plants of a traced file, in its order (file: TracedPlant::file)
std::vector<TracedPlant> tracedPlants(const TraceFile& tf, const std::string& file = "");

// a sample sheet (compare --groups, fit --groups): a CSV whose header names the columns plant and
// `column` (others ignored), then one row per plant, named by its id or its label. SceneError naming
// SHEET:LINE for a plant absent from plants, named twice, naming two plants, or an empty value
struct SheetRow {
  int plant = -1;            // index into plants
  std::string value;         // its cell in `column`
  int line = 0;              // the sheet's line
  std::string optional;      // its cell in the optional column ("" when the sheet has none, or the cell is empty)
};
// optionalColumn: a column the sheet may have (its cells may be empty)
std::vector<SheetRow> readSampleSheet(const std::string& sheet, const std::string& column, const std::vector<TracedPlant>& plants,
                                      const std::string& optionalColumn = "");

// how to read the traced root (the flags compare and fit share)
struct TraceFlags {
  static constexpr double kUnset = AnalyzeOptions::kUnset;
  std::string trace;              // the RSML file
  std::string root;               // --root ID (default: the file's one primary root)
  double pxPerMm = kUnset;        // --px-per-mm for a pixel file
  std::string downhill = "+y";    // --downhill +y | -y | DEG
  double sigmaMm = kUnset;        // --sigma-mm: a traced point's position uncertainty [mm]; default: one
                                  // pixel of a pixel file, else 0.05 mm (one pixel of a 20 px/mm scan)
  std::string flagPrefix = "--";  // how messages name these flags (render's are --trace-root, ...)
};

// a traced root made ready for comparison with runs of model m: in plate coordinates [mm] with its base
// at the origin, measured with m's analysis (its growth zone left out, its R for the peaks' hysteresis)
struct TraceTarget {
  std::string file, rootKey;
  Eigen::Matrix3Xd plateMm;
  RootTraits traits;
  double sigmaMm = 0;             // a traced point's position uncertainty (traceUncertainty)
  std::string sigmaSource;        // "--sigma-mm", "noise_mm", "pixel / sqrt(12)", "pixel", "default"
  double pixelMm = 0;             // the file's pixel [mm] (0: a file in lengths)
  double excludeTipMm = 0;        // the model's growth zone [mm], left out of the measurements of shape
  double rootLengthMm = 0;        // the root's length: the trace's less the lengthening its points' noise
                                  // (sigmaMm) gives a polyline (noiseLengtheningMm)
  double dsMm = 0;                // the trace's resampling step [mm]
  // a time-lapse trace (RSML 2D+t): the hour each point was reached, and the file's observation times;
  // both empty for a trace of one time
  std::vector<double> timesH, observationTimesH;
};
// the position uncertainty of a traced point [mm], the one every objective (observables, shape,
// time-lapse) and every goodness of fit takes: --sigma-mm when given (flagMm, named flag); else the root's
// estimated noise (traits.noiseMm, analysis.csv's noise_mm), at least a pixel's quantisation p / sqrt(12);
// else (exact: a rootsim export, a run's nodes without a tracer's noise; or too few points to estimate it)
// a pixel, else 0.05 mm (a 20 px/mm scan's pixel). source names which.
struct TraceUncertainty {
  double sigmaMm = 0;
  std::string source;
};
TraceUncertainty traceUncertainty(const RootTraits& traits, double pixelMm, bool exact, double flagMm, const std::string& flag);
// SceneError for bad input (the file, the flags, the root)
TraceTarget loadTarget(const TraceFlags& f, const Model& m);

// the simulated root of a snapshot of a run of model m, measured as the trace is
struct SimRoot {
  Eigen::Matrix3Xd plateMm;       // nodes in plate coordinates [mm], the seed (node 0) at the origin
  RootTraits traits;
  double timeH = 0;
  int step = 0;
};
// (the run as a scan of the plate sees it, as the trace was seen: its height off the plate dropped, so its
// length, distances and shape samples are the plate's, the trace's; its observables measured as the trace
// `as` was, rootTraitsAs: smoothed at the trace's smoothing_mm and resampled at its step, so a trace's
// smoothing biases a run alike and the two differ by what differs in the roots)
SimRoot simRootOf(const Model& m, const Snapshot& s, const TraceTarget& as);
// the snapshot a trace of one time is compared with: the one whose root's length on the plate is nearest
// lengthMm (the trace's root length, rootLengthMm), the earlier of two as near
int snapshotOfLength(const Model& m, const std::vector<Snapshot>& snaps, double lengthMm);

struct Comparison {
  std::vector<Observation> obs;
  double chi2 = 0;
  int used = 0;                   // observables in chi2
  double distanceMm = 0;          // arcLengthDistanceMm at 0.05 mm over the shorter root
  double frechetMm = 0;           // frechetDistanceMm at 0.05 mm
};
Comparison compareRoots(const TraceTarget& t, const SimRoot& s);

// a time-lapse trace against a run at one observation time: the trace as it was then; the run recorded as
// a 2D+t trace records a root whose old parts do not move: its length from the snapshot nearest that time,
// its shape, tip and tip angle from its root at the last observation time up to that length
struct TimeLapseRow {
  double timeH = 0, snapshotH = 0;
  double traceLengthMm = 0, runLengthMm = 0;
  double traceTipLateralMm = 0, traceTipDownhillMm = 0, runTipLateralMm = 0, runTipDownhillMm = 0;
  double traceThetaTipDeg = 0, runThetaTipDeg = 0;
  double distanceMm = 0;          // arcLengthDistanceMm of the two then
  // at the last observation time: the strongest wave of each root (strongestWave over the trace's
  // waveRange then); NaN at the other times
  WaveFit traceWave, runWave;
};
// one row per observation at which the trace has a length (empty for a trace without times)
std::vector<TimeLapseRow> compareTimeLapse(const TraceTarget& t, const Model& m, const std::vector<Snapshot>& snaps);

// a time-lapse trace at one observation time
struct TraceAtTime {
  double timeH = 0, lengthMm = 0, tipLateralMm = 0, tipDownhillMm = 0, thetaTipDeg = 0;
  bool thetaDefined = false;      // the tip angle's span (tipAngleSpanMm) fits twice in the root then
};
// the polyline p (its points reached at timesH) at each of the observation times at which it has a length;
// pixelMm: the tip angle's pixel (0: none)
std::vector<TraceAtTime> traceAtTimes(const Eigen::Matrix3Xd& p, const std::vector<double>& timesH, const std::vector<double>& observationTimesH,
                                      double pixelMm);
// the pixel a trace's tip angle is taken over (0 when its uncertainty is not a pixel's)
double tipPixelMm(const TraceTarget& t);

// the time-lapse objective's trace side (docs/experiments.md, "Fit"): at each observation time the root's
// length, tip lateral and downhill position [mm] and, where it is defined, its tip angle [deg]; at the
// last, the wavelength and amplitude of its strongest wave (strongestWave: the shape the tips left
// behind, whose waves a tip sampled every few hours aliases) where the root has 8 points to fit. Their
// covariance is the trace's points' noise (sigmaMm, traceUncertainty) propagated through the same
// measurement (noiseDraws of the denoised trace); that noise's mean shift (a noisy polyline is longer) is
// taken off the trace's values.
struct TimeLapseObjective {
  FitComponents trace;            // names, trace (bias taken off), sigma, cov; sim empty
  Eigen::VectorXd bias;           // per output: the noise's mean shift taken off
  std::vector<double> timesH;     // the observation times used
  std::vector<bool> withTheta;    // per time: its tip angle is an output
  bool withWave = false;          // the last time's strongest wave is an output (two: lambda, amplitude)
  double growthMmPerH = 0;        // the trace's dL/dt: the least-squares slope of its lengths over time
  double growthSigma = 0;         // its standard uncertainty (from the lengths' covariance)
};
// SceneError when the trace has no times or fewer than two observations with a length
TimeLapseObjective timeLapseObjective(const TraceTarget& t, int draws = 400);
// a run's outputs beside the trace's (rows: compareTimeLapse of the run); std::invalid_argument when the
// rows are not at the objective's times
FitComponents timeLapseComponents(const TimeLapseObjective& o, const std::vector<TimeLapseRow>& rows);

// a one-line summary "distance 0.12 mm (RMS at equal arc length), Frechet 0.3 mm, chi2 1.2 (3 observables)"
std::string comparisonCaption(const Comparison& c);
// the observables table of compare.csv (name, unit, trace, sim, sigma, residual, used, how)
std::string observablesCsv(const Comparison& c);

struct CompareOptions {
  static constexpr double kUnset = AnalyzeOptions::kUnset;
  std::string runDir;
  TraceFlags trace;
  double atH = kUnset;            // --at-h: the run's snapshot nearest this time; default: the first
                                  // snapshot as long as the trace (the final one when none is)
  std::string out;                // --out DIR (default compare/<run>_vs_<trace stem>)
  std::string groups;             // --groups SHEET.csv: a plate's run, its plants paired by a sample sheet
                                  // (columns plant, seedling) instead of by the nearest seed
  bool force = false;
  bool quiet = false;
  bool printTable = true;         // the observables' table on stdout (the command line's; not Python's)
};
// compare.json, compare.csv and compare.{pdf,svg,png} into --out (a compare folder, written whole); the
// table on stdout. A plate's run (docs/plate.md, Compare a traced plate): every traced plant's primary
// root paired with a seedling (nearest seed, or --groups), each pair compared as one root is, pairs.csv
// and compare.csv holding every pair, the picture both plates side by side. Returns 0; *outDir (when given): the folder written.
int compareCommand(const CompareOptions& o, std::string* outDir = nullptr);

}  // namespace rootsim::app
