#pragma once
// `rootsim fit TRACE.rsml --scene BASE.toml --free KEY=LO:HI,...` (docs/experiments.md, "Fit"): the values of
// free scene keys whose simulated root best matches a traced one. A start design (a grid over the box,
// written as a sweep file and run as a sweep), then trust regions: runs spread over a box, a quadratic
// response surface of the outputs (response_surface.hpp) whose minimum (NLopt's BOBYQA) centres the next,
// smaller box; the surface's slope and the runs' scatter about it give the uncertainties and the
// directions the trace cannot determine. Every evaluation is a run directory in OUT/runs, so a killed fit
// resumes where it stopped.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/compare_trace.hpp"
#include "rootsim/goodness.hpp"

namespace rootsim::app {

struct FitOptions {
  TraceFlags trace;
  std::vector<std::string> more;         // more RSML files of the plate (with --groups)
  std::string groups;                    // --groups SHEET.csv: a fit per group of the plate's plants
  std::string scene;                     // --scene BASE.toml
  std::string free;                      // --free KEY=LO:HI[,KEY=LO:HI...]
  std::string objective;                 // --objective observables | shape | timelapse ("": timelapse for a
                                         // trace with times, else observables)
  int jobs = 1;                          // -j: simultaneous runs
  int budget = 150;                      // --budget: most runs (the design and the trust regions together)
  std::string out;                       // --out DIR
  bool force = false;
  bool quiet = false;
  bool designOnly = false;               // --design-only: write each fit folder's start design as a sweep
                                         // file and stop (its runs made by rootsim sweep, found on rerun)
};

struct FreeKey {
  std::string key;
  double lo = 0, hi = 0;
};
// parses --free (SceneError naming the item: a key not in the scene schema, not a number key, a bound
// outside its range, LO >= HI, growth.steps, or a key that changes how far the root grows)
// (timeLapse: the fit grows every evaluation to the trace's last observation time, so growth.rate_per_h may be free)
std::vector<FreeKey> parseFreeKeys(const std::string& text, const std::string& scenePath, bool timeLapse = false);

struct FitEvaluation {
  std::vector<double> x;     // the free keys' values
  std::string phase;         // "design", "search", "stencil"
  std::string dir;           // its run directory (a group's: its first seedling's)
  std::vector<std::string> dirs;  // every run directory of it (a group's: one per sowing angle)
  double objective = 0;      // chi-square of its outputs against the trace's (with the model's scatter
                             // added in the report; the trace's uncertainty alone while the fit runs)
  double chi2Trace = 0;      // chi-square of its outputs against the trace's uncertainty alone
  double chi2 = 0;           // chi-square of the observables (trace's uncertainty alone)
  double distanceMm = 0;     // RMS distance at equal arc length
  std::string error;         // "" or why the run failed (its objective is then kFailedObjective)
  Eigen::VectorXd sim;       // the outputs the objective compares (FitComponents::sim)
  std::string pattern;       // its root's pattern (straight, waving, coiling, skewing)
  double amplitudeMm = 0;    // its root's peak-to-peak amplitude [mm] (0 without waves)
  double straightness = 0;   // its root's chord / length
  long order = 0;            // when it was asked for: the design's point index, then each batch's in turn
  std::vector<double> seedlingChi2;  // a fit by group: each seedling's own observables against its run
                                     // (compareRoots' chi-square, its trace's uncertainty alone); else empty
  Eigen::MatrixXd groupCov;  // a fit by group: the covariance of the group's mean from its seedlings'
                             // residuals against this run's (groupComponents); else empty
  Eigen::MatrixXd seedlingSim, seedlingTrace;  // a fit by group: each seedling's outputs of its own run,
                             // and its trace's (seedlings x outputs, 0 where a seedling does not use an
                             // output); else empty
};
inline constexpr double kFailedObjective = 1e12;
// a time-lapse trace's dL/dt this far (relative) from a fixed tip speed is named beside the verdict
inline constexpr double kGrowthMismatch = 0.2;

// a scene key the fit holds fixed that shapes its answer (the plate's tilt, the growth rate, ...)
struct FixedKey {
  std::string key;     // "plane.alpha_deg", or "tip_speed_mm_per_h" (growth.rate_per_h * growth.growth_zone_mm)
  std::string value;   // as the resolved scene writes it
  std::string source;  // "scene" (the base scene file sets it), "default", or how a derived value is made
};

struct FitReport {
  std::vector<FreeKey> keys;
  std::vector<FitEvaluation> evaluations;  // in the order they were made
  int best = -1;                           // index into evaluations: the answer, the run of smallest
                                           // objective (the surface's minimum's run on a tie)
  int surfaceRun = -1;                     // index of the response surface's minimum's run
  Goodness goodness;                       // the answer's run against the trace's uncertainty alone
  std::string misfit;                      // a poor fit: what the model could not reproduce, in one line
  std::string growthMismatch;              // a time-lapse whose dL/dt differs from the fixed tip speed by more
                                           // than kGrowthMismatch: the sentence saying so
  std::vector<FixedKey> fixed;             // the fixed keys that shape the answer, the tilt and growth first
  std::vector<double> sigma;               // per key (NaN: flat or at a bound)
  Eigen::MatrixXd covariance;              // per pair of keys, in their units: the surface's correlation
                                           // with sigma on its diagonal (empty: no surface covariance)
  double answerScale = 1;                  // the answer's chi2 / dof beyond the surface's scale (>= 1): the
                                           // factor sigma's variance was widened by
  std::vector<std::string> notes;          // identifiability and bounds, in words
  FitComponents trace;                     // the trace's side of the outputs, with the covariance the
                                           // answer was judged against (a group's: at the answer)
  std::string out;
  std::string design;                      // --design-only: the start design's sweep file (nothing run)
};

// runs the fit and writes its folder (fit.json, evaluations.csv, best.toml, compare.*, and for two keys
// landscape.*); SceneError for bad input before anything is written, RunError when no evaluation ran
FitReport runFit(const FitOptions& o, const std::function<void(const std::string&)>& log);

// the command: runFit (runGroupFit with --groups), then the values and notes on stdout
int fitCommand(const FitOptions& o);

// ---- a traced plate fitted by group (fit --groups; docs/experiments.md, "A plate by group") ----
struct GroupFit {
  std::string name;
  std::vector<std::string> plants;  // its seedlings, as the sheet names them
  std::vector<double> sowingDeg;    // each seedling's start angle, its runs' root.initial_angle_deg
  FitReport report;                 // its fit (folder OUT/groups/NAME)
  std::vector<double> value, sigma; // per key: the answer's value, its sigma (NaN: flat or at a bound)
  FitComponents outputs;            // the group's mean observables and their covariance (sim empty)
  Eigen::MatrixXd scatter;          // the seedlings' sample covariance of those observables
  Eigen::VectorXd answerSim;        // the answer's run's outputs
  // per seedling: its own answer among the group's runs, the run whose values its own observables fit
  // best (seedlingChi2), and that chi-square; the keys' values per seedling (NaN: no run measured)
  std::vector<std::vector<double>> seedlingValue;
  std::vector<double> seedlingChi2;
};
// one key between two groups: difference A - B with its sigma and two-sided Wald p-value; flat (no
// difference, no p-value) when either group does not determine the key
struct GroupContrast {
  std::string key, a, b;
  bool flat = false;
  std::string why;                  // a flat contrast's reason
  double difference = 0, sigma = 0, pValue = 1;
};
struct GroupFitReport {
  std::vector<FreeKey> keys;
  std::vector<GroupFit> groups;     // in the order the sheet first names them
  std::vector<GroupContrast> contrasts;  // every pair of groups (a before b in the sheet), every key
  std::vector<std::string> designs;     // --design-only: each group's start design's sweep file (nothing run)
  std::string out;
};
// every key of every pair of groups (a named before b)
std::vector<GroupContrast> groupContrasts(const std::vector<FreeKey>& keys, const std::vector<GroupFit>& groups);
// "mut - WT: tropism.beta +0.20 +- 0.03, p < 0.001; rod.youngs_modulus_mpa flat (...)" one line per pair
std::string contrastsTable(const std::vector<GroupContrast>& contrasts);
// SceneError for bad input (the sheet naming SHEET:LINE, a plate key free, ...) before anything is written;
// writes OUT/fit.json and one fit folder per group in OUT/groups
GroupFitReport runGroupFit(const FitOptions& o, const std::function<void(const std::string&)>& log);
int groupFitCommand(const FitOptions& o);

}  // namespace rootsim::app
