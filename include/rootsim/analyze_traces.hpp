#pragma once
// `rootsim analyze FILE.rsml...` (docs/experiments.md): the phenotyping traits and the run observables of
// every root of traced (or exported) root systems, through the very analysis code of runs (traits.hpp).
#include <filesystem>
#include <string>
#include <vector>

namespace rootsim::app {

struct AnalyzeOptions {
  static constexpr double kUnset = -1e300;  // a number flag not given
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
};

// the rows of every root of every file (bad input: SceneError naming the file:line or the flag)
std::vector<RootRow> analyzeTraces(const AnalyzeOptions& o);

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
// summary line per root on stdout. Returns 0.
int analyzeCommand(const AnalyzeOptions& o);

}  // namespace rootsim::app
