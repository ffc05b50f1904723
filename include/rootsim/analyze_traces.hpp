#pragma once
// `rootsim analyze FILE.rsml...` (docs/experiments.md): the phenotyping traits and the run observables of
// every root of traced (or exported) root systems, through the very analysis code of runs (traits.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/traits.hpp"
#include "rootsim/limits.hpp"

namespace rootsim::app {

struct AnalyzeOptions {
  static constexpr double kUnset = kUnsetFlag;  // a number flag not given (limits.hpp)
  std::vector<std::string> files;  // RSML files; several files of one plate at several times give rates
  double pxPerMm = kUnset;         // --px-per-mm: pixels per millimetre, for files whose unit is pixel
  std::string downhill = "+y";     // --downhill: +y, -y, or DEG (the angle of downhill from the file's +y
                                   // axis, positive towards +x)
  std::string times;               // --times T1,T2,...: growth time of each file [h] (else the file's
                                   // time_h property, if it has one)
  double dsMm = kUnset;            // --ds-mm: resampling step of the shape analysis [mm]; 0: the trace's
                                   // own points. Default: 0 for a file rootsim wrote (its points are a
                                   // run's nodes), else 0.05 mm (a run's element length)
  double excludeTipMm = kUnset;    // --exclude-tip-mm: the last part left out of the shape analysis (a
                                   // run's growth zone) [mm]; default: the file's growth.growth_zone_mm
                                   // property, else 0
  double radiusMm = kUnset;        // --radius-mm: the root radius R of the peaks' hysteresis [mm]; default:
                                   // the file's root.radius_mm, else half the median diameter, else 0.1
  std::string out;                 // --out DIR (default analysis/<first file's stem>)
  bool force = false;
  bool quiet = false;
  bool printLines = true;          // a line per root on stdout (the command line's; not Python's)
  std::string flagPrefix = "--";   // how messages name the flags: "--px-per-mm", or render's "--trace-px-per-mm"
};

// one row of analysis.csv: a root of a plant of a file
struct RootRow {
  std::string file, plant, plantLabel, root, rootLabel, parent, pattern, radiusSource;
  double timeH = 0;                  // NaN: unknown
  int order = 0, points = 0, lateralPeaks = 0;
  double lengthMm = 0, chordMm = 0, tortuosity = 0, skewDeg = 0, insertionDeg = 0;
  double wavelengthMm = 0, amplitudeMm = 0, amplitudeHalfMm = 0, waves = 0, skewWavesDeg = 0;
  double maxKappaPerMm = 0, thetaMinDeg = 0, thetaMaxDeg = 0;
  double growthRateMmPerH = 0;       // from the same root in the previous file in time; NaN for the first
  double dsMm = 0, excludeTipMm = 0, radiusMm = 0;
  // noise-aware measurement and the field's traits (docs/experiments.md, "Noise", "The field's traits")
  double noiseMm = 0, smoothingMm = 0, peakThresholdMm = 0;  // sigma (NaN: not estimated), the smoothing's
                                     // half-width, the peaks' hysteresis used [mm]
  std::string wavesNote;             // why wavelength_mm (and amplitude_mm) are empty
  double straightness = 0, hgi = 0, vgi = 0, thetaTipDeg = 0, bowMm = 0, bendDeg = 0;
  Eigen::Matrix3Xd traceMm;          // the file's points, plate coordinates [mm]
  Eigen::Matrix3Xd curveMm;          // the curve measured (smoothed for a trace), plate coordinates [mm]
  std::vector<int> peakNodes;        // its columns at the counted peaks
  int matureLast = 0;                // its last column in the shape analysis
};

// one root of a trace file in plate coordinates (docs/experiments.md, "Traced roots")
struct TracedRoot {
  std::string plant, plantLabel, root, rootLabel, parent;
  std::string key;           // plant/root ids ("#k" for a missing one): the root's identity across files
  std::string name;          // its id, or "#k" (its position in its plant)
  int order = 0, line = 0;   // branching order; the line of its <root> element
  int parentIndex = -1;      // its parent in TraceFile::roots
  Eigen::Matrix3Xd plateMm;  // points [mm]: lateral, downhill, height; origin at its plant's first root's base
  Eigen::Vector3d originMm = Eigen::Vector3d::Zero();  // that origin in the file's plate coordinates [mm]
                                                       // (one frame for every plant of the file)
  std::vector<double> timeIndex;  // a 2D+t file's coord_t per point (the observation index); else empty
  double radiusMm = 0;       // R of the peaks' hysteresis, and where it came from
  std::string radiusSource;
};
// an RSML file read for analysis: its roots in plate coordinates and how to measure them
struct TraceFile {
  std::string file;
  double timeH = 0;          // the file's time_h (NaN: none)
  double pixelMm = 0;        // a pixel's size [mm]: --px-per-mm's for a pixel file, else the file's own
                             // (a resolution, RootSystemTracker's <size>); 0: the file is in a physical unit
  std::string scaleSource;   // where the scale came from (the flag, or the file's unit and resolution/size)
  std::vector<double> observationTimesH;  // a 2D+t file's observation times [h] (index = coord_t); else empty
  bool ours = false;         // written by rootsim (its points are a run's nodes)
  double dsMm = 0, excludeTipMm = 0;  // the shape analysis' resampling step and tip exclusion (the flags or
                                      // the defaults of AnalyzeOptions)
  AnalysisParams set;        // the analysis thresholds (the file's analysis.* keys, else the defaults)
  std::vector<TracedRoot> roots;
};
// checks the number flags of o (SceneError naming the flag)
void checkTraceFlags(const AnalyzeOptions& o);
// reads one RSML file (SceneError naming file:line for bad input: no root, a pixel unit without
// --px-per-mm, ...)
TraceFile readTraceFile(const std::string& file, const AnalyzeOptions& o);
// the traits of one of its roots, measured at dsMm without the last excludeTipMm: a file rootsim wrote on
// its points as they are (a run's nodes), any other as a trace (traceTraits: noise estimated, smoothed).
// SceneError naming the root's line when it has fewer than two distinct points
RootTraits tracedTraits(const TraceFile& tf, const TracedRoot& r, double dsMm, double excludeTipMm);
// the root --root ID names (its id, "#k", or plant/root), or without an id the file's one primary root
// (SceneError listing the roots when that is ambiguous or the id matches none)
const TracedRoot& pickRoot(const TraceFile& tf, const std::string& id, const std::string& flag = "--root");

// the rows of every root of every file (bad input: SceneError naming the file:line or the flag)
std::vector<RootRow> analyzeTraces(const AnalyzeOptions& o);
// the files' times: --times, one per file (checks the flags; SceneError naming the flag); empty without
std::vector<double> traceTimes(const AnalyzeOptions& o);
// the rows of one file's roots at time timeH (growth rates NaN: trace_growth.hpp fills them)
std::vector<RootRow> fileRows(const TraceFile& tf, double timeH);

// one cell of a row: the column of analysis.csv / the key of analysis.json, its unit ("" for none), and
// its value (text, or a number: NaN for an empty cell)
struct RowField {
  const char* name;
  const char* unit;
  bool isText;
  std::string text;
  double number;
};
std::vector<RowField> rowFields(const RootRow& r);

// the command: analysis.csv and analysis.json into --out (a rootsim analysis folder, written whole), one
// summary line per root on stdout (printLines); result (may be null) receives the tables written. Returns 0.
struct Analysis;  // trace_growth.hpp
int analyzeCommand(const AnalyzeOptions& o, Analysis* result = nullptr);

}  // namespace rootsim::app
