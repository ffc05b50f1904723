#pragma once
// The parts of `rootsim fit` after its search (src/analysis/fit_trace.cpp runs the design and the trust
// regions): the answer and its goodness (fit_goodness.cpp), and the fit folder's files (fit_output.cpp).
#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rootsim/compare_trace.hpp"
#include "rootsim/fit_trace.hpp"
#include "rootsim/json.hpp"
#include "rootsim/response_surface.hpp"
#include "rootsim/scene.hpp"

namespace rootsim::app {

// a group of a plate's seedlings fitted together (fit --groups, docs/experiments.md "A plate by group"):
// the outputs are the observables two or more seedlings' traces use, the group's mean against the mean over
// those seedlings of their runs' values (each seedling's run sown at its own angle) measured as each
// seedling is; their covariance the mean's, from the scatter of each seedling's residual against its own
// run at the fit's answer (groupComponents), at least the seedlings' tracing noise
struct GroupSide {
  std::string name;
  std::vector<std::string> plants;     // the sheet's names of its seedlings
  std::vector<TraceTarget> seedlings;  // each seedling's primary root
  TraceTarget target;                  // the first seedling's, grown to the group's mean root length: the
                                       // length every run grows to, and the root of the compare picture
  FitComponents trace;                 // names, the mean (trace), and the covariance the fit starts from
                                       // (cov: the mean's, from the seedlings' observables) and its sigma
  Eigen::VectorXd floor;               // per output: the least variance of the mean, the mean of its
                                       // seedlings' tracing variances / n
  std::vector<std::vector<bool>> users;  // per output, per seedling: its trace measures it
  double userCount(std::size_t output) const {
    return static_cast<double>(std::count(users[output].begin(), users[output].end(), true));
  }
  // the sowing: each seedling's angle (the sheet's angle_deg, else its trace's start: its base's direction
  // over the scene's initial root length; to 0.1 deg), the distinct ones as root.initial_angle_deg texts,
  // and per seedling the index of its own; every evaluation is a run per distinct angle
  std::vector<double> sowingDeg;
  std::vector<std::string> angles;
  std::vector<int> angleOf;
  Eigen::MatrixXd scatter;             // the seedlings' sample covariance
  std::vector<std::string> inputs;     // the RSML files and the sheet
  std::string settings;                // for base.toml's settings line: the sheet, the group and its plants
};
// the scene key a group's runs are sown by, and the sample sheet's optional column of each plant's angle
inline constexpr const char* kSowingKey = "root.initial_angle_deg";
inline constexpr const char* kSheetSowingColumn = "angle_deg";
// the covariance of a group's mean of values measured per seedling (v: seedlings x outputs): S / n from
// their sample covariance S, each variance at least g.floor, none between outputs measured on different
// seedlings or on too few to estimate it (n - 1 below the outputs measured on them); scatter: S
Eigen::MatrixXd groupMeanCovariance(const GroupSide& g, const Eigen::MatrixXd& v, Eigen::MatrixXd* scatter);
// what the group's covariance of a run is, in the words of a goodness line
inline constexpr const char* kGroupResidualCovName =
    "the group mean's covariance at the answer (its seedlings' residuals against their own runs: their scatter / n, "
    "each variance at least their tracing noise / n)";
// the same from the seedlings' residuals against a smooth surface of their own runs' outputs over the runs
// around the answer (groupSurfaceCovariance): the runs' jumps between neighbouring values stay in the
// model's covariance alone
inline constexpr const char* kGroupSurfaceCovName =
    "the group mean's covariance at the answer (its seedlings' residuals against a surface of their own runs' outputs: "
    "their scatter / n, each variance at least their tracing noise / n)";
// each seedling's outputs (seedlings x outputs, 0 where it does not use an output): its trace's, and its own
// run's measured as that seedling is (a run without the waves the trace has: 0, as observableComponents)
void seedlingOutputs(const GroupSide& g, const std::vector<SimRoot>& sims, Eigen::MatrixXd& trace, Eigen::MatrixXd& sim);
// the covariance of the group's mean from its seedlings' residuals against their own runs' outputs smoothed
// over the runs: one quadratic surface per seedling's output fitted to the runs at points us (scaled keys;
// seedlingSim of each), taken at u, each residual its trace less that (groupMeanCovariance). Throws
// std::invalid_argument when the runs are too few for a surface (fitResponseSurface)
Eigen::MatrixXd groupSurfaceCovariance(const GroupSide& g, const Eigen::MatrixXd& trace, const std::vector<Eigen::VectorXd>& us,
                                       const std::vector<Eigen::MatrixXd>& sims, const Eigen::VectorXd& u, double scale);
// the group's outputs of its runs' roots (sims: one per seedling, its own sowing's run): the mean over
// seedlings of each one's run measured as that seedling is (observeBoth), and as cov the covariance of
// the group's mean from the seedlings' residuals (trace less own run; groupMeanCovariance)
FitComponents groupComponents(const GroupSide& g, const std::vector<SimRoot>& sims);
// the size of a fit of n keys: the start design's levels per key and runs, the surface's terms, a trust
// region's runs; SceneError when --budget cannot hold the design and one trust region
struct FitSize {
  int levels = 0, design = 0, terms = 0, regionPoints = 0;
};
FitSize fitSize(const FitOptions& o, int n);
// --design-only's line on stdout: each design's rootsim sweep command, and the fit again
std::string designOnlyText(const std::vector<std::string>& designs);
// runFit, or a group's fit when group is given (its outputs the group's: groupComponents)
FitReport runFitOn(const FitOptions& o, const GroupSide* group, const std::function<void(const std::string&)>& log);

// the smallest trust region's half width, in design cells. A root's outputs are a sensitive function of
// its parameters: a skewing root's skew jumps by 1-2 degrees between runs whose twist differs by 0.005
// (docs/experiments.md). A surface fitted in a box not much wider than that chases those jumps: its
// slopes are the jumps' and its scatter too small, and the uncertainties it gives shrink with the box.
// Half a design cell (one halving of the first box): over the synthetic traces of docs/experiments.md
// ("Validation") it covered the truth within 2 sigma more often than a quarter cell did.
inline constexpr double kSmallestBox = 0.5;

// the snapshot of an evaluation that is compared with the trace: a time-lapse's last (the trace's last
// observation time); for a trace of one time, the one whose root is as long on the plate as the traced
// root (snapshotOfLength), so a root that leaves the plate's plane is not compared younger than the trace
inline const Snapshot& comparedSnapshot(const Model& m, const std::vector<Snapshot>& snaps, const TraceTarget& t, bool lapse) {
  return snaps[static_cast<std::size_t>(lapse ? static_cast<int>(snaps.size()) - 1 : snapshotOfLength(m, snaps, t.rootLengthMm))];
}

// the fixed keys of the base model that shape a fit's answer, the plate's tilt and the growth first, the
// free keys left out; fileKeys: the keys the base scene file sets (sceneFileKeys), the others are defaults
std::vector<FixedKey> sceneFixedKeys(const Model& base, const std::vector<FreeKey>& free, const std::vector<std::string>& fileKeys);
// "plane.alpha_deg = 40 (scene), growth.rate_per_h = 0.2 (default), ..."
std::string fixedKeysText(const std::vector<FixedKey>& fixed);

// what a poor fit's model could not reproduce, and the fixed key to check or free, in one line: "the model
// with these free keys and this scene does not reproduce the trace: the trace is straight, every run waves
// (A 0.8-1.2 mm); check plane.alpha_deg (40, scene) or free it"
// (modelSigma: the runs' scatter about the response surface per output, shown beside the output missed most)
std::string misfitSentence(const TraceTarget& target, const std::vector<FitEvaluation>& evaluations, const FitEvaluation& answer,
                           const FitComponents& trace, const Eigen::VectorXd& modelSigma, const std::vector<FixedKey>& fixed);

// the keys' covariance a fit reports (fit.json, the landscape's 1-sigma ellipse): the correlation between
// the keys of the surface's covariance (any scale: the scaled box's), with the reported sigmas on its
// diagonal, so that covariance and sigma say one uncertainty; empty when the surface had no covariance
// of this size, or a sigma or a variance is not finite and positive
Eigen::MatrixXd reportedCovariance(const Eigen::MatrixXd& surfaceCov, const std::vector<double>& sigma);

// the answer among the evaluations: rep.best (answerIndex over the objectives, rep.surfaceRun preferred on
// a tie), its goodness against the trace's uncertainty alone (answerChi2: the answer's chi-square against
// the trace as a trace of its run would scatter), the fixed keys, and for a poor fit the sentence
void chooseAnswer(FitReport& rep, const TraceTarget& target, const FitComponents& trace, const Eigen::VectorXd& modelSigma,
                  const Model& base, const std::vector<std::string>& fileKeys,
                  const std::function<double(const FitEvaluation&)>& answerChi2);

// what the files of a fit folder are made of
struct FitOutcome {
  const FitOptions* options = nullptr;
  const TraceTarget* target = nullptr;
  std::filesystem::path out;
  long steps = 0;             // growth steps of every evaluation
  int levels = 0;             // the start design's levels per key
  int regionPoints = 0;       // runs per trust region
  int regions = 0;            // trust regions run
  double rho = 0;             // the last box's half width (scaled)
  ResponseSurface surface;    // the last trust region's
  FitUncertainty unc;         // at the surface's minimum
  Eigen::VectorXd ustar;      // the surface's minimum (scaled)
  std::vector<double> surfaceX, bootSigma;  // its values, and the bootstrap's sigma per key
  FitComponents trace;        // the trace's side of the outputs
};
// fit.json's goodness block
Json goodnessJson(const Goodness& g);
// fit.json, evaluations.csv, best.toml, compare.* and for two keys landscape.* of rep's answer
void writeFitOutputs(const FitOutcome& f, const FitReport& rep, const Scene& bestScene);

}  // namespace rootsim::app
