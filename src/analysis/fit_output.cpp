// `rootsim fit`: the fit folder's files (docs/experiments.md, "Fit", Outputs): fit.json, evaluations.csv,
// best.toml, the answer's picture compare.* and for two keys the landscape.*
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "fit_parts.hpp"
#include "rootsim/compare_panel.hpp"
#include "rootsim/json.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/trajectory.hpp"
#include "rootsim/write_rule.hpp"
#include "rootsim/run_snapshots.hpp"
#include "analysis_numbers.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

std::string csvCell(double v) { return std::isfinite(v) ? numberText(v) : std::string(); }

}  // namespace

Json goodnessJson(const Goodness& g) {
  Json j;
  j.num("chi2", g.chi2).integer("dof", g.dof).integer("outputs", g.outputs).integer("p_dof", g.pDof).num("p_value", g.pValue)
      .str("verdict", g.verdict)
      .str("against", "the answer's own run against " + g.against + " (the model's scatter is in the keys' sigma, not here)");
  return j;
}

void writeFitOutputs(const FitOutcome& f, const FitReport& rep, const Scene& bestScene) {
  const FitOptions& o = *f.options;
  const TraceTarget& target = *f.target;
  const std::vector<FreeKey>& keys = rep.keys;
  const fs::path& out = f.out;
  const int n = static_cast<int>(keys.size()), k = f.levels;
  const FitEvaluation& b = rep.evaluations[static_cast<std::size_t>(rep.best)];
  auto width = [&](int i) { return keys[static_cast<std::size_t>(i)].hi - keys[static_cast<std::size_t>(i)].lo; };
  const std::vector<Snapshot> bestSnaps = loadSnapshots(b.dir);
  const SimRoot bestSim = simRootOf(bestScene.model, comparedSnapshot(bestScene.model, bestSnaps, target, o.objective == "timelapse"), target);
  const Comparison bc = compareRoots(target, bestSim);
  const std::string why = rep.best == rep.surfaceRun ? "the surface's minimum" : "the fit's best run, better by the objective than the surface's minimum's";
  writeFileAtomic(out / "best.toml", "# rootsim fit: " + why + " (" + b.dir + ")\n" + bestScene.resolvedToml);
  recordWritten({out / "best.toml"});
  // the picture: the answer, the trace over its run, and its goodness
  std::string title = "fit of " + literalLabel(fs::path(o.trace.trace).filename().string()) + ":";
  for (int i = 0; i < n; ++i) {
    title += " " + literalLabel(keys[static_cast<std::size_t>(i)].key) + " = " + numberText(std::round(b.x[static_cast<std::size_t>(i)] * 1e4) / 1e4);
    if (std::isfinite(rep.sigma[static_cast<std::size_t>(i)]))
      title += " ± " + numberText(std::round(rep.sigma[static_cast<std::size_t>(i)] * 1e4) / 1e4);
  }
  char caption[200];
  std::snprintf(caption, sizeof caption, "distance %.3g mm (RMS at equal arc length), Fréchet %.3g mm; ", bc.distanceMm, bc.frechetMm);
  saveComparePanel(bestScene.model, comparedSnapshot(bestScene.model, bestSnaps, target, o.objective == "timelapse"), target.plateMm, title, caption + goodnessText(rep.goodness, "χ²") + (rep.growthMismatch.empty() ? "" : "; " + rep.growthMismatch),
                   (out / "compare").string());
  if (n == 2) {
    std::vector<LandscapePoint> pts;
    for (const FitEvaluation& e : rep.evaluations)
      if (e.error.empty()) pts.push_back(LandscapePoint{e.x[0], e.x[1], e.objective, e.phase == "design"});
    // the ellipse of the covariance reported, sigma on its diagonal
    const bool haveCov = rep.covariance.rows() == 2;
    const Eigen::Matrix2d cov = haveCov ? Eigen::Matrix2d(rep.covariance) : Eigen::Matrix2d::Zero();
    // the zoom: the smallest trust region, or 4 sigma when that is wider
    const double zx = std::max(kSmallestBox / k * width(0), 4.0 * (std::isfinite(rep.sigma[0]) ? rep.sigma[0] : 0.0));
    const double zy = std::max(kSmallestBox / k * width(1), 4.0 * (std::isfinite(rep.sigma[1]) ? rep.sigma[1] : 0.0));
    saveLandscapePanel(pts, keys[0].key, keys[1].key, keys[0].lo, keys[0].hi, keys[1].lo, keys[1].hi, k, b.x[0], b.x[1],
                       haveCov ? &cov : nullptr, zx, zy,
                       "χ² of the " + o.objective + " with the model's scatter: " + std::to_string(rep.evaluations.size()) + " runs",
                       (out / "landscape").string());
  }
  // evaluations.csv
  std::string csv = "index,phase";
  for (const FreeKey& fk : keys) csv += "," + fk.key;
  csv += ",objective,chi2_trace,chi2_observables,distance_mm,dir,error\n";
  for (std::size_t i = 0; i < rep.evaluations.size(); ++i) {
    const FitEvaluation& e = rep.evaluations[i];
    csv += std::to_string(i) + "," + e.phase;
    for (double v : e.x) csv += "," + numberText(v);
    std::string err = e.error;
    std::replace(err.begin(), err.end(), '"', '\'');
    std::replace(err.begin(), err.end(), '\n', ' ');
    csv += "," + csvCell(e.error.empty() ? e.objective : kNaN) + "," + csvCell(e.error.empty() ? e.chi2Trace : kNaN) + "," +
           csvCell(e.error.empty() ? e.chi2 : kNaN) + "," + csvCell(e.distanceMm) + "," + fs::path(e.dir).filename().string() +
           ",\"" + err + "\"\n";
  }
  writeFileAtomic(out / "evaluations.csv", csv);
  recordWritten({out / "evaluations.csv"});
  // fit.json
  const FitComponents& tc = f.trace;
  const FitUncertainty& unc = f.unc;
  Json j;
  j.str("software", outputSignatureText())
      .str("trace", o.trace.trace)
      .str("root", target.rootKey)
      .str("scene", o.scene)
      .integer("growth_steps", f.steps)
      .num("trace_length_mm", target.traits.lengthMm)
      .num("root_length_mm", target.rootLengthMm)
      .num("sigma_mm", target.sigmaMm)
      .str("sigma_source", target.sigmaSource)
      .num("smoothing_mm", target.traits.smoothingMm)
      .str("objective", o.objective)
      .str("method", "start design: a " + std::to_string(k) + "^" + std::to_string(n) +
                         " grid of cell centres (a sweep: design.toml); then trust regions: " + std::to_string(f.regionPoints) +
                         " runs per box (Halton points), a quadratic surface of every output fitted to them by least squares, "
                         "its chi-square minimised in the box by NLopt's BOBYQA; the box halves around a minimum inside it "
                         "(down to half a design cell) and moves to one on its edge; the surface's minimum is the mean of the "
                         "minima of the last 4 boxes; the answer is the run of smallest objective, the surface minimum's run "
                         "or one the fit made before")
      .str("uncertainty", "variance = the linearised surface's, (J' C^-1 J)^-1 with C = the trace's covariance + the covariance "
                          "of the runs' scatter about the surface, scaled by max(1, chi2 / dof), mean over the last trust "
                          "regions; plus the surface's own estimation error: the larger of its minima's spread over those "
                          "regions and a bootstrap of 200 resamples of the runs around the answer; all times answer_scale, the "
                          "answer's chi2 / dof against the trace's uncertainty beyond the surface's scale, at least 1; covariance: "
                          "the surface's correlation between the keys with these sigmas on its diagonal")
      .integer("trust_regions", f.regions)
      .num("last_box_half_width", f.rho)
      .integer("evaluations", static_cast<long long>(rep.evaluations.size()))
      .integer("budget", o.budget);
  Json bestJ;
  for (int i = 0; i < n; ++i) {
    Json v;
    v.num("value", b.x[static_cast<std::size_t>(i)]).num("sigma", rep.sigma[static_cast<std::size_t>(i)])
        .num("sigma_bootstrap", f.bootSigma[static_cast<std::size_t>(i)])
        .num("lo", keys[static_cast<std::size_t>(i)].lo).num("hi", keys[static_cast<std::size_t>(i)].hi);
    bestJ.object(keys[static_cast<std::size_t>(i)].key, v);
  }
  j.object("best", bestJ)
      .str("answer", rep.best == rep.surfaceRun ? "surface minimum" : "best run")
      .object("goodness", goodnessJson(rep.goodness));
  if (!rep.misfit.empty()) j.str("misfit", rep.misfit);
  if (!rep.growthMismatch.empty()) j.str("growth_mismatch", rep.growthMismatch);
  Json fixedJ;
  for (const FixedKey& fk : rep.fixed) fixedJ.object(fk.key, Json().str("value", fk.value).str("source", fk.source));
  j.object("scene_fixed", fixedJ);
  Json surfJ;
  for (int i = 0; i < n; ++i) surfJ.num(keys[static_cast<std::size_t>(i)].key, f.surfaceX[static_cast<std::size_t>(i)]);
  if (rep.surfaceRun >= 0) {
    const FitEvaluation& s = rep.evaluations[static_cast<std::size_t>(rep.surfaceRun)];
    surfJ.str("run", fs::path(s.dir).filename().string()).num("objective", s.objective).num("chi2_trace", s.chi2Trace);
  }
  j.object("surface_minimum", surfJ)
      .num("chi2", unc.chi2)
      .integer("dof", unc.dof)
      .str("chi2_with", "the surface's value at its minimum against the trace's covariance plus the model's scatter")
      .num("covariance_scale", unc.scale)
      .num("answer_scale", rep.answerScale)
      .str("best_run", fs::path(b.dir).filename().string())
      .num("best_run_objective", b.objective)
      .num("best_run_distance_mm", b.distanceMm);
  if (rep.covariance.rows() == n) {
    Json cj;
    for (int r = 0; r < n; ++r) {
      Json row;
      for (int c = 0; c < n; ++c) row.num(keys[static_cast<std::size_t>(c)].key, rep.covariance(r, c));
      cj.object(keys[static_cast<std::size_t>(r)].key, row);
    }
    j.object("covariance", cj);
  }
  std::vector<Json> notes;
  for (const std::string& s : rep.notes) notes.push_back(Json().str("note", s));
  j.array("notes", notes);
  // the outputs: the trace's value, its uncertainty, the model's scatter, the surface at the minimum
  const Eigen::VectorXd atMin = f.surface.value(f.ustar);
  std::vector<Json> outs;
  for (int c = 0; c < tc.trace.size(); ++c)
    outs.push_back(Json()
                       .str("name", tc.names[static_cast<std::size_t>(c)])
                       .num("trace", tc.trace(c))
                       .num("sigma_trace", tc.sigma(c))
                       .num("sigma_model", std::sqrt(f.surface.noiseCov(c, c)))
                       .num("surface_at_minimum", atMin(c))
                       .num("best_run", b.sim(c)));
  j.array("outputs", outs);
  Json obsJ;
  for (const Observation& ob : bc.obs) {
    Json e;
    e.str("unit", ob.unit).num("trace", ob.trace).num("sim", ob.sim).boolean("used", ob.used && o.objective == "observables");
    obsJ.object(ob.name, e);
  }
  j.object("best_run_observables", obsJ);
  std::vector<Json> ev;
  for (const FitEvaluation& e : rep.evaluations) {
    Json x;
    x.str("phase", e.phase);
    for (int i = 0; i < n; ++i) x.num(keys[static_cast<std::size_t>(i)].key, e.x[static_cast<std::size_t>(i)]);
    x.num("objective", e.error.empty() ? e.objective : kNaN)
        .num("chi2_trace", e.error.empty() ? e.chi2Trace : kNaN)
        .num("distance_mm", e.distanceMm)
        .str("dir", fs::path(e.dir).filename().string());
    if (!e.error.empty()) x.str("error", e.error);
    ev.push_back(x);
  }
  j.array("evaluation_list", ev);
  writeFileAtomic(out / "fit.json", j.dump() + "\n");
  recordWritten({out / "fit.json"});
}

}  // namespace rootsim::app
