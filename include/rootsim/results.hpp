#pragma once
// What one run measured, with the theory beside it: the row of result.csv (and of a sweep's table.csv).
// One column table (name, unit, value) writes the row and reads it back, so the header and the row can
// never drift apart, and readers (sweeps, figures) get typed values instead of strings.
#include <filesystem>
#include <string>
#include <vector>

#include "rootsim/analysis.hpp"
#include "rootsim/model.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/theory.hpp"

namespace rootsim {

struct RunResult {
  bool grows = true;               // a growth run (else mechanics only: the first 8 columns)
  std::string scene, status = "complete", pattern, sensing;
  double steps = 0, timeH = 0, lengthMm = 0, elements = 0, thetaTipDeg = 0, totalSubsteps = 0;
  double wavelengthMm = NAN, amplitudeMm = NAN, amplitudeHalfMm = NAN, lateralPeaks = 0;
  double skewDeg = NAN, maxKappaPerMm = NAN, thetaMinDeg = NAN, thetaMaxDeg = NAN;
  double snapOrTurningH = NAN;     // first sideways snap on a plate; time to reach the vertical without [h]
  double alphaDeg = NAN, beta = NAN, gamma = NAN, rTau = NAN;
  // theory (docs/model.md, Theory)
  double effectiveGain = NAN, T0h = NAN, maxKappaEq8PerMm = NAN, wavelengthEq9Mm = NAN, amplitudeEq10Mm = NAN,
         alphaSToWEq12Deg = NAN, alphaWToCEq13Deg = NAN, omegaT0 = NAN;

  // the value of a column by its name (NaN for an empty or unknown numeric column)
  double number(const std::string& column) const;
};

// one column of result.csv
struct ResultColumn {
  const char* name;
  const char* unit;                // "" for dimensionless or text
  bool growthOnly;                 // absent from mechanics-only runs
  bool text;                       // a string column
  double RunResult::*num;          // numeric columns
  std::string RunResult::*str;     // text columns
};
const std::vector<ResultColumn>& resultColumns();

// the result of a finished simulation (the final shape analysed, the theory of its model)
RunResult makeResult(const Model& m, const Simulation& sim, const ShapeAnalysis* shape, double snapOrTurningH);
// header line of result.csv for a growth (grows) or mechanics-only run
std::string resultHeader(bool grows);
// header and row, each ending in a newline
std::string resultCsv(const RunResult& r);
// reads result.csv; throws RunError naming the file when it is missing or its header is not the table's
RunResult readResult(const std::filesystem::path& path);

}  // namespace rootsim
