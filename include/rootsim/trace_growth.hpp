#pragma once
// Traced root systems over time and per plant (docs/experiments.md, "Plants" and "Time-lapse"): a 2D+t
// file's roots at each observation, roots matched across dated files by geometry, each root's L(t), tip
// position and tip angle (growth.csv), and the per-plant traits of plants.csv.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/analyze_traces.hpp"

namespace rootsim::app {

// the plausible length of a seedling's primary root [mm]: a primary outside it is a warning naming the
// scale to check (a wrong unit, resolution or --px-per-mm gives lengths 25x or 1/25 of the real ones)
inline constexpr double kPlausiblePrimaryMinMm = 0.2;
inline constexpr double kPlausiblePrimaryMaxMm = 200.0;
// the warnings of a file's primary roots outside that range ("" when all are plausible), one line each
std::vector<std::string> plausibilityWarnings(const TraceFile& tf, const AnalyzeOptions& o);

// one row of plants.csv: a seedling of a file (a base root and every root branching from it)
struct PlantRow {
  std::string file, plant, plantLabel, root;  // the file, its plant, the seedling's base root
  double timeH = 0;                           // NaN: unknown
  int roots = 0, lateralCount = 0, primaryLaterals = 0;
  double primaryLengthMm = 0, totalLengthMm = 0, lateralLengthMm = 0;
  double branchedZoneMm = 0;                  // first to last insertion along the primary [mm]; NaN below 2
  double lateralDensityPerMm = 0;             // primaryLaterals / branchedZoneMm; NaN below 2 laterals
  double lateralsPerPrimaryMm = 0;            // primaryLaterals / primaryLengthMm
  double depthMm = 0, widthMm = 0;            // the seedling's extent along / across downhill [mm]
};
std::vector<PlantRow> plantRows(const TraceFile& tf, double timeH);

// one row of growth.csv: a root at one time
struct GrowthRow {
  std::string file, plant, root;
  std::string track;             // the root's identity over time: FILE:plant/root where it was first seen
  double timeH = 0;
  double lengthMm = 0;
  double tipLateralMm = 0, tipDownhillMm = 0;  // the tip in the plate, from the plant's origin [mm]
  double thetaTipDeg = 0;        // the tip's direction from downhill, signed as theta [deg]
};

// a 2D+t root at (fractional) observation k: its polyline up to coord_t = k, the last point interpolated
// linearly in coord_t between the two points around k; no columns when the root had not started at k
Eigen::Matrix3Xd rootAtObservation(const TracedRoot& r, double k);
// a 2D+t root's points' times [h]: each point's coord_t turned into hours between the observation times
// around it (linearly); empty for a root of a file without times
std::vector<double> pointTimesH(const TraceFile& tf, const TracedRoot& r);
// the polyline p (points reached at the hours timesH, never decreasing) as it was at time tH: the points
// reached by then and the last one interpolated linearly in time; no columns before the first point
Eigen::Matrix3Xd polylineAtTime(const Eigen::Matrix3Xd& p, const std::vector<double>& timesH, double tH);
// the tip's direction [deg] from downhill, signed as theta (towards +lateral positive), over the last
// span of arc length: max(0.5 mm, 10 pixels), at most half the root (a tracer's pixel steps average out)
double tipAngleDeg(const Eigen::Matrix3Xd& plateMm, double pixelMm);
// that span before it is cut to half the root: max(0.5 mm, 10 pixels) [mm]
double tipAngleSpanMm(double pixelMm);

// the roots of `later` that extend a root of `earlier` (one entry per root of later: the index in earlier,
// or -1): the earlier polyline lies along the later one's base (RMS distance of its points to the later
// polyline within kMatchSigmas·√2·σ, every point within twice that, its base within twice that of the
// later base, the later no shorter), on the matched parent for laterals (base roots first, then by
// order); one-to-one, the closest pairs first (ties: document order). σ: one pixel, else 0.05 mm.
inline constexpr double kMatchSigmas = 3.0;
std::vector<int> matchRoots(const TraceFile& earlier, const TraceFile& later);
// the position noise σ the matching assumes for a file [mm]
double matchSigmaMm(const TraceFile& tf);

// every file read for analyze: the rows of analysis.csv (growth rates filled from the time-lapse), of
// plants.csv and growth.csv, and the warnings (implausible lengths)
struct Analysis {
  std::vector<RootRow> roots;
  std::vector<PlantRow> plants;
  std::vector<GrowthRow> growth;
  std::vector<std::string> warnings;
};
Analysis analyzeAll(const AnalyzeOptions& o);

// the columns of plants.csv and growth.csv: name, unit, and the cell (text, or a number: NaN empty)
std::vector<RowField> plantFields(const PlantRow& r);
std::vector<RowField> growthFields(const GrowthRow& r);

}  // namespace rootsim::app
