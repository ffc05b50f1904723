// `rootsim fit`: free scene keys fitted to a traced root (docs/experiments.md, "Fit").
#include "rootsim/fit_trace.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>
#include <random>
#include <sstream>
#include <thread>

#include "rootsim/compare_panel.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/json.hpp"
#include "rootsim/response_surface.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/sweep.hpp"
#include "rootsim/trajectory.hpp"
#include "rootsim/units.hpp"
#include "rootsim/write_rule.hpp"
#include "fit_parts.hpp"
#include "rootsim/run_snapshots.hpp"
#include "analysis_numbers.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

double parseBound(const std::string& text, const std::string& item) {
  double v = 0;
  std::size_t used = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !std::isfinite(v))
    throw SceneError("--free " + item + ": \"" + text + "\" is not a number (KEY=LO:HI)");
  return v;
}

// keys that change how far the root grows in a number of steps: the fit grows every evaluation to the
// trace's length with one growth.steps
const char* const kGrowthKeys[] = {"growth.steps", "growth.step_h", "growth.rate_per_h", "growth.growth_zone_mm",
                                   "root.initial_length_mm", "growth.enabled"};

std::string fileText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

std::vector<FreeKey> parseFreeKeys(const std::string& text, const std::string& scenePath, bool timeLapse) {
  std::vector<FreeKey> keys;
  if (text.empty()) throw SceneError("--free: give at least one KEY=LO:HI");
  for (const std::string& item : splitCommas(text)) {
    const auto eq = item.find('='), colon = item.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos)
      throw SceneError("--free " + item + ": expected KEY=LO:HI (e.g. tropism.beta=0.05:0.5)");
    FreeKey k;
    k.key = item.substr(0, eq);
    k.lo = parseBound(item.substr(eq + 1, colon - eq - 1), item);
    k.hi = parseBound(item.substr(colon + 1), item);
    const std::string type = sceneKeyType(k.key);
    if (type.empty()) {
      // the scene parser names the key and suggests one
      try {
        loadScene(scenePath, {k.key + "=0"});
      } catch (const SceneError& e) {
        throw SceneError("--free " + item + ": " + e.what());
      }
      throw SceneError("--free " + item + ": " + k.key + " is not a scene key");
    }
    if (type != "a number") throw SceneError("--free " + item + ": " + k.key + " is " + type + ", not a real number");
    for (const char* g : kGrowthKeys)
      // a time-lapse grows every evaluation to the trace's last observation time: its rate may be free
      if (k.key == g && !(timeLapse && k.key == "growth.rate_per_h"))
        throw SceneError("--free " + item + ": " + k.key +
                         (timeLapse ? " changes the run's time steps or start; a time-lapse fit grows every evaluation to the trace's "
                                      "last observation time with one growth.steps, so it cannot be free (growth.rate_per_h can)"
                                    : " changes how far the root grows; fit grows every evaluation to the trace's length with one "
                                      "growth.steps, so it cannot be free (growth.rate_per_h can with --objective timelapse)"));
    if (!(k.lo < k.hi)) throw SceneError("--free " + item + ": LO must be below HI");
    for (double v : {k.lo, k.hi}) {
      try {
        loadScene(scenePath, {k.key + "=" + numberText(v)});
      } catch (const SceneError& e) {
        throw SceneError("--free " + item + ": the bound " + numberText(v) + " is outside the key's range: " + e.what());
      }
    }
    for (const FreeKey& o : keys)
      if (o.key == k.key) throw SceneError("--free " + item + ": " + k.key + " is given twice");
    keys.push_back(k);
  }
  return keys;
}

namespace {

// the shape objective's points along each root
constexpr int kShapeSamples = 8;
// trust regions at the smallest box whose minima are averaged
constexpr int kFinalRegions = 4;
// bootstrap resamples of the runs around the answer (the surface's own estimation error)
constexpr int kBootstrap = 200;

// the outputs of a comparison that the objective uses (shapeCov: the trace's shape covariance)
// (lapse: the time-lapse objective's trace side; snaps: the run's snapshots, s its last)
FitComponents componentsOf(const std::string& objective, const TraceTarget& t, const Eigen::MatrixXd& shapeCov, const TimeLapseObjective& lapse,
                           const Model& m, const std::vector<Snapshot>& snaps, const SimRoot& s, const Comparison& c) {
  if (objective == "timelapse") return timeLapseComponents(lapse, compareTimeLapse(t, m, snaps));
  return objective == "shape" ? shapeComponents(t.plateMm, s.plateMm, shapeCov, kShapeSamples) : observableComponents(c.obs);
}

// chi-square of outputs sim against the trace's, with its uncertainty alone
double chi2Of(const FitComponents& t, const Eigen::VectorXd& sim) {
  return chiSquareOf(sim, t.trace, t.cov);
}

// one fit in progress: its evaluations (cached by their values' text, shared by the threads)
class Fit {
 public:
  Fit(const FitOptions& o, std::vector<FreeKey> keys, const fs::path& out, std::string baseText, TraceTarget target,
      const std::function<void(const std::string&)>& log, const GroupSide* group)
      : o_(o), keys_(std::move(keys)), out_(out), baseText_(std::move(baseText)), target_(std::move(target)), log_(log), group_(group) {
    // the trace's side of the shape: its covariance once, from its points' noise
    if (o_.objective == "shape") shapeCov_ = shapeTraceCovariance(target_.plateMm, target_.sigmaMm, kShapeSamples);
    if (o_.objective == "timelapse") lapse_ = timeLapseObjective(target_);
    // a group's side: its mean and the covariance it starts from (useCovarianceOf replaces it)
    if (group_) traceComp_ = group_->trace;
  }

  const std::vector<FreeKey>& keys() const { return keys_; }
  fs::path runs() const { return out_ / "runs"; }
  const FitComponents& traceComponents() const { return traceComp_; }
  bool byGroup() const { return group_ != nullptr; }

  // a fit by group: the group mean's covariance from the seedlings' residuals against the runs of e
  // (FitEvaluation::groupCov), and every evaluation's chi-square against it. Called between batches of
  // runs, at the fit's current best estimate, so the answer's uncertainty and goodness take the
  // covariance at the answer
  //
  // With a box (scaled [lo, hi], the trust region the runs around e lie in): each seedling's residual is
  // against a surface of its own run's outputs over the box's runs, taken at e (groupSurfaceCovariance),
  // so the runs' jumps between neighbouring values, which the model's covariance holds, are not counted
  // again; without one (the start design's best: no surface yet), or with too few runs in the box for a
  // surface, against e's own runs
  void useCovarianceOf(const FitEvaluation& e, const Eigen::VectorXd* lo = nullptr, const Eigen::VectorXd* hi = nullptr) {
    if (!group_ || !e.error.empty() || e.groupCov.size() == 0) return;
    std::lock_guard lk(mu_);
    Eigen::MatrixXd cov = e.groupCov;
    const char* name = kGroupResidualCovName;
    if (lo && hi) {
      // in the order they were asked for (as evaluations()): the runs finish in any order, the same fit
      // writes the same bytes
      std::vector<const FitEvaluation*> asked;
      for (const FitEvaluation& v : evals_) asked.push_back(&v);
      std::stable_sort(asked.begin(), asked.end(), [](const FitEvaluation* a, const FitEvaluation* b) { return a->order < b->order; });
      std::vector<Eigen::VectorXd> us;
      std::vector<Eigen::MatrixXd> sims;
      for (const FitEvaluation* p : asked) {
        const FitEvaluation& v = *p;
        if (!v.error.empty() || v.seedlingSim.size() == 0) continue;
        const Eigen::VectorXd u = uOf(v.x);
        if (((u.array() >= lo->array() - 1e-12) && (u.array() <= hi->array() + 1e-12)).all()) {
          us.push_back(u);
          sims.push_back(v.seedlingSim);
        }
      }
      if (static_cast<int>(us.size()) > quadraticTerms(static_cast<int>(keys_.size()))) {
        cov = groupSurfaceCovariance(*group_, e.seedlingTrace, us, sims, uOf(e.x), 0.5 * (*hi - *lo).maxCoeff());
        name = kGroupSurfaceCovName;
      }
    }
    traceComp_.cov = cov;
    traceComp_.sigma = cov.diagonal().cwiseSqrt();
    traceComp_.covName = name;
    for (FitEvaluation& v : evals_)
      if (v.error.empty()) v.objective = v.chi2Trace = chi2Of(traceComp_, v.sim);
  }
  // the evaluation of smallest objective so far (none: an empty one with an error)
  FitEvaluation bestSoFar() {
    std::lock_guard lk(mu_);
    const FitEvaluation* best = nullptr;
    for (const FitEvaluation& e : evals_)
      if (e.error.empty() && (!best || e.objective < best->objective || (e.objective == best->objective && e.order < best->order))) best = &e;
    if (best) return *best;
    FitEvaluation none;
    none.error = "no run";
    return none;
  }

  std::vector<double> xOf(const Eigen::VectorXd& u) const {
    std::vector<double> x(keys_.size());
    for (std::size_t i = 0; i < keys_.size(); ++i) {
      // to 9 significant digits: the value is its own text, in the scene and in the run's name
      x[i] = std::strtod(significantText(keys_[i].lo + std::clamp(u(static_cast<int>(i)), 0.0, 1.0) * (keys_[i].hi - keys_[i].lo), 9).c_str(), nullptr);
    }
    return x;
  }
  Eigen::VectorXd uOf(const std::vector<double>& x) const {
    Eigen::VectorXd u(static_cast<int>(keys_.size()));
    for (std::size_t i = 0; i < keys_.size(); ++i) u(static_cast<int>(i)) = (x[i] - keys_[i].lo) / (keys_[i].hi - keys_[i].lo);
    return u;
  }
  std::vector<std::string> texts(const std::vector<double>& x) const {
    std::vector<std::string> t;
    for (double v : x) t.push_back(numberText(v));
    return t;
  }
  std::vector<std::string> overrides(const std::vector<std::string>& t) const {
    std::vector<std::string> ov;
    for (std::size_t i = 0; i < keys_.size(); ++i) ov.push_back(keys_[i].key + "=" + t[i]);
    return ov;
  }
  Scene sceneAt(const std::vector<double>& x, const std::vector<std::string>& more = {}) const {
    std::vector<std::string> ov = overrides(texts(x));
    ov.insert(ov.end(), more.begin(), more.end());
    return parseScene(baseText_, (out_ / "base.toml").string(), ov);
  }

  // the outputs of the run directory dir of values x (which ran, or was found complete); a group's: its
  // runs dirs, one per sowing angle (GroupSide::angles), each seedling measured on its own angle's run
  FitEvaluation measure(const std::vector<double>& x, const std::string& phase, const std::vector<fs::path>& dirs, const std::string& error) {
    FitEvaluation e;
    e.x = x;
    e.phase = phase;
    e.dir = dirs.front().string();
    for (const fs::path& d : dirs) e.dirs.push_back(d.string());
    e.error = error;
    if (e.error.empty()) {
      try {
        const Scene sc = sceneAt(x);
        const std::vector<Snapshot> snaps = loadSnapshots(dirs.front());
        SimRoot sim = simRootOf(sc.model, comparedSnapshot(sc.model, snaps, target_, o_.objective == "timelapse"), target_);
        FitComponents fc;
        if (group_) {
          std::vector<std::vector<Snapshot>> runs;
          for (const fs::path& d : dirs) runs.push_back(d == dirs.front() ? snaps : loadSnapshots(d));
          std::vector<SimRoot> sims;
          for (std::size_t i = 0; i < group_->seedlings.size(); ++i) {
            const std::vector<Snapshot>& own = runs[static_cast<std::size_t>(group_->angleOf[i])];
            sims.push_back(simRootOf(sc.model, comparedSnapshot(sc.model, own, group_->seedlings[i], false), group_->seedlings[i]));
            e.seedlingChi2.push_back(compareRoots(group_->seedlings[i], sims.back()).chi2);
          }
          fc = groupComponents(*group_, sims);
          e.groupCov = fc.cov;
          seedlingOutputs(*group_, sims, e.seedlingTrace, e.seedlingSim);
          sim = sims.front();  // the first seedling's run: the distance, pattern and amplitude shown
        }
        const Comparison c = compareRoots(group_ ? group_->seedlings.front() : target_, sim);
        if (!group_) fc = componentsOf(o_.objective, target_, shapeCov_, lapse_, sc.model, snaps, sim, c);
        {
          std::lock_guard lk(mu_);
          if (traceComp_.names.empty()) traceComp_ = fc;  // the trace's side: the same for every run
          // a group's against the fit's current covariance (it follows the answer: useCovarianceOf)
          e.objective = e.chi2Trace = group_ ? chi2Of(traceComp_, fc.sim) : chi2Of(fc, fc.sim);
        }
        e.sim = fc.sim;
        e.chi2 = c.chi2;
        e.distanceMm = c.distanceMm;
        e.pattern = sim.traits.shape.pattern;
        e.amplitudeMm = sim.traits.shape.amplitude / units::mm;
        e.straightness = sim.traits.chordMm / sim.traits.lengthMm;
      } catch (const std::exception& ex) {
        e.error = ex.what();
      }
    }
    if (!e.error.empty()) {
      e.objective = e.chi2 = e.chi2Trace = kFailedObjective;
      e.distanceMm = kNaN;
    }
    return e;
  }

  // the evaluation of x: from the cache, or a run into runs/eval_<values> (another thread running the
  // same values is waited for)
  FitEvaluation evaluate(const std::vector<double>& x, const std::string& phase, long order) {
    const std::vector<std::string> t = texts(x);
    std::string key;
    for (const std::string& s : t) key += s + ";";
    {
      std::unique_lock lk(mu_);
      for (;;) {
        auto it = cache_.find(key);
        if (it == cache_.end()) break;
        if (it->second >= 0) return evals_[static_cast<std::size_t>(it->second)];
        cv_.wait(lk);  // being run by another thread
      }
      cache_[key] = -1;
    }
    std::string name = "eval";
    for (std::size_t i = 0; i < keys_.size(); ++i) name += "_" + runNameSlug(keys_[i].key, t[i]);
    // a group's: a run per sowing angle of its seedlings, eval_<values>_root.initial_angle_deg_<angle>
    std::vector<fs::path> dirs;
    std::vector<std::string> extra;
    if (group_)
      for (const std::string& a : group_->angles) {
        dirs.push_back(runs() / (name + "_" + runNameSlug(kSowingKey, a)));
        extra.push_back(std::string(kSowingKey) + "=" + a);
      }
    else
      dirs.push_back(runs() / name), extra.push_back("");
    std::string error;
    for (std::size_t r = 0; r < dirs.size() && error.empty(); ++r) {
      const fs::path& dir = dirs[r];
      const Scene sc = extra[r].empty() ? sceneAt(x) : sceneAt(x, {extra[r]});
      const bool whole = fs::is_directory(dir) && whyNotOurs(dir, runFolder()).empty() && whyNotWhole(dir).empty() &&
                         fileText(dir / "scene.toml") == sc.resolvedToml;
      if (whole) continue;
      RunDirOptions ro;
      ro.force = true;   // a run of this fit's own folder that did not finish
      ro.resume = true;
      try {
        runSceneToDir(sc, dir.string(), ro, nullptr);
      } catch (const SceneError& ex) {
        error = ex.what();
      } catch (const RunError& ex) {
        error = ex.what();
      } catch (const RelaxError& ex) {
        error = ex.what();
      }
    }
    FitEvaluation e = measure(x, phase, dirs, error);
    e.order = order;
    return record(e, key);
  }

  FitEvaluation record(FitEvaluation e, const std::string& key) {
    std::lock_guard lk(mu_);
    evals_.push_back(e);
    cache_[key] = static_cast<int>(evals_.size()) - 1;
    cv_.notify_all();
    if (!o_.quiet) {
      std::string line = "fit " + std::to_string(evals_.size()) + "/" + std::to_string(o_.budget) + " " + e.phase;
      for (std::size_t i = 0; i < keys_.size(); ++i) line += " " + keys_[i].key + "=" + numberText(e.x[i]);
      char b[200];
      if (e.error.empty())
        std::snprintf(b, sizeof b, ": chi2 %.4g against %s (distance %.3g mm)", e.objective,
                      traceComp_.covName.c_str(), e.distanceMm);
      else
        std::snprintf(b, sizeof b, ": FAILED (%.120s)", e.error.c_str());
      log_(line + b);
    }
    return e;
  }

  void recordDesign(const std::vector<double>& x, const std::vector<fs::path>& dirs, const std::string& error, long order) {
    std::string key;
    for (const std::string& s : texts(x)) key += s + ";";
    FitEvaluation e = measure(x, "design", dirs, error);
    e.order = order;
    record(e, key);
  }

  // runs the points (scaled) jobs at a time
  void evaluateAll(const std::vector<Eigen::VectorXd>& us, const std::string& phase) {
    const long base = nextOrder(static_cast<long>(us.size()));
    std::mutex m;
    std::size_t next = 0;
    std::vector<std::thread> pool;
    std::string firstError;
    for (int j = 0; j < std::min<int>(o_.jobs, static_cast<int>(us.size())); ++j)
      pool.emplace_back([&] {
        for (;;) {
          std::size_t i;
          {
            std::lock_guard lk(m);
            if (next >= us.size() || !firstError.empty()) return;
            i = next++;
          }
          try {
            evaluate(xOf(us[i]), phase, base + static_cast<long>(i));
          } catch (const std::exception& e) {
            std::lock_guard lk(m);
            if (firstError.empty()) firstError = e.what();
          }
        }
      });
    for (std::thread& t : pool) t.join();
    if (!firstError.empty()) throw RunError("fit: " + firstError);
  }

  int count() {
    std::lock_guard lk(mu_);
    return static_cast<int>(evals_.size());
  }
  // every evaluation in the order they were asked for (the design's points, then each batch's), whatever
  // order the threads finished them in: the same fit gives the same surfaces and the same files
  std::vector<FitEvaluation> evaluations() {
    std::lock_guard lk(mu_);
    std::vector<FitEvaluation> e = evals_;
    std::stable_sort(e.begin(), e.end(), [](const FitEvaluation& a, const FitEvaluation& b) { return a.order < b.order; });
    return e;
  }
  // the first of `count` order numbers after the design's
  long nextOrder(long count) {
    std::lock_guard lk(mu_);
    const long o = next_;
    next_ += count;
    return o;
  }

 private:
  const FitOptions& o_;
  std::vector<FreeKey> keys_;
  fs::path out_;
  std::string baseText_;
  TraceTarget target_;
  const std::function<void(const std::string&)>& log_;
  const GroupSide* group_;    // a group of seedlings (fit --groups): their mean observables, else nullptr
  std::mutex mu_;
  std::condition_variable cv_;
  std::map<std::string, int> cache_;  // values' text -> index into evals_ (-1: running)
  std::vector<FitEvaluation> evals_;
  FitComponents traceComp_;
  Eigen::MatrixXd shapeCov_;  // the trace's shape outputs' covariance (the shape objective)
  TimeLapseObjective lapse_;  // the time-lapse objective's trace side
  long next_ = 1L << 40;  // order numbers after the design's point indices
};

// the radical inverse of i in base b: the Halton sequence's coordinate
double halton(long i, int b) {
  double f = 1, r = 0;
  while (i > 0) {
    f /= b;
    r += f * static_cast<double>(i % b);
    i /= b;
  }
  return r;
}

// the levels of the start design per key: k cell centres of the box
int designLevels(int n, int budget) {
  // about a third of the budget, at least 3 levels per key (a minimum needs neighbours on both sides)
  int k = 3;
  while (std::pow(k + 1, n) <= budget / 3.0) ++k;
  return k;
}

struct SurfaceData {
  const ResponseSurface* s;
  const FitComponents* t;
};
double surfaceObjective(unsigned n, const double* u, double*, void* data) {
  const auto* d = static_cast<const SurfaceData*>(data);
  return surfaceChiSquare(*d->s, Eigen::Map<const Eigen::VectorXd>(u, n), d->t->trace, d->t->cov);
}

// the minimum of the surface's chi-square over the box [lo, hi] (BOBYQA from its centre and corners' midpoints)
Eigen::VectorXd surfaceMinimum(const ResponseSurface& s, const FitComponents& t, const Eigen::VectorXd& lo,
                               const Eigen::VectorXd& hi) {
  const unsigned n = static_cast<unsigned>(lo.size());
  SurfaceData d{&s, &t};
  Eigen::VectorXd best = 0.5 * (lo + hi);
  double bestF = surfaceChiSquare(s, best, t.trace, t.cov);
  std::vector<Eigen::VectorXd> starts = {best};
  for (unsigned i = 0; i < n; ++i)
    for (double f : {0.25, 0.75}) {
      Eigen::VectorXd st = best;
      st(i) = lo(i) + f * (hi(i) - lo(i));
      starts.push_back(st);
    }
  for (const Eigen::VectorXd& st : starts) {
    nlopt_opt opt = nlopt_create(NLOPT_LN_BOBYQA, n);
    nlopt_set_lower_bounds(opt, lo.data());
    nlopt_set_upper_bounds(opt, hi.data());
    nlopt_set_min_objective(opt, surfaceObjective, &d);
    nlopt_set_xtol_abs1(opt, 1e-6);
    nlopt_set_maxeval(opt, 2000);
    Eigen::VectorXd u = st;
    double f = 0;
    if (nlopt_optimize(opt, u.data(), &f) > 0 && f < bestF) {
      bestF = f;
      best = u;
    }
    nlopt_destroy(opt);
  }
  return best;
}

// a time-lapse fit whose growth rate is not free: the trace's own dL/dt beside the scene's tip speed in
// scene_fixed, and a mismatch beyond kGrowthMismatch named in the verdict line
void growthAgainstTrace(FitReport& rep, const TimeLapseObjective& lapse, const Model& base) {
  if (std::any_of(rep.keys.begin(), rep.keys.end(), [](const FreeKey& k) { return k.key == "growth.rate_per_h"; })) return;
  const double scene = base.growth.rate * base.growth.zoneLength / (units::mm / units::hour);
  auto at = std::find_if(rep.fixed.begin(), rep.fixed.end(), [](const FixedKey& f) { return f.key == "tip_speed_mm_per_h"; });
  rep.fixed.insert(at == rep.fixed.end() ? at : at + 1,
                   FixedKey{"trace_growth_mm_per_h", significantText(lapse.growthMmPerH, 4), "the trace's dL/dt: least-squares slope of its lengths over its observation times"});
  const double apart = std::abs(lapse.growthMmPerH - scene) / scene;
  if (apart > kGrowthMismatch) {
    char line[300];
    std::snprintf(line, sizeof line,
                  "the trace grows at %.3g mm/h, the scene's tip speed is %.3g mm/h (%.0f %% apart): check growth.rate_per_h or free it",
                  lapse.growthMmPerH, scene, 100 * apart);
    rep.growthMismatch = line;
  }
}

}  // namespace

FitSize fitSize(const FitOptions& o, int n) {
  if (o.budget < 1 || o.budget > 100000)
    throw SceneError("--budget " + std::to_string(o.budget) + ": expected an integer in [1, 100000] runs");
  const int k = designLevels(n, o.budget);
  const int design = static_cast<int>(std::lround(std::pow(k, n)));
  const int terms = quadraticTerms(n);
  // runs a trust region's surface is fitted to: enough beyond the surface's terms to estimate the
  // scatter's covariance between the outputs
  // (a time-lapse's many outputs: their scatter's covariance from fewer runs is singular, the trace's own
  // covariance added to it in every chi-square is not)
  const int outputs = o.objective == "shape" ? 2 * kShapeSamples : 3;
  const int regionPoints = std::max(2 * terms + 4, terms + outputs + 4);
  // the budget: the design, a trust region's runs and its minimum's, and the answer's run
  if (o.budget < design + regionPoints + 2)
    throw SceneError("--budget " + std::to_string(o.budget) + ": too small for " + std::to_string(n) + " free key(s): the start design takes " +
                     std::to_string(design) + " runs and one trust region " + std::to_string(regionPoints + 2) +
                     "; give at least " + std::to_string(design + regionPoints + 2));
  return FitSize{k, design, terms, regionPoints};
}

FitReport runFit(const FitOptions& given, const std::function<void(const std::string&)>& log) {
  if (!given.groups.empty() || !given.more.empty()) throw SceneError("fit: --groups and more than one RSML file: a fit by group (runGroupFit)");
  return runFitOn(given, nullptr, log);
}

namespace {

// what a fit is asked, checked before anything is written: its options (the objective resolved: the
// trace's own default), its folder (locked before any work: a run, sweep or second fit there is refused),
// the base scene, the trace, the free keys, and how long every evaluation grows
struct FitSetup {
  FitOptions o;
  fs::path out;
  OutputLock lock;
  Scene base;
  TraceTarget target;
  bool lapse = false;  // the time-lapse objective
  TimeLapseObjective lapseTrace;
  std::vector<FreeKey> keys;
  FitSize size;
  long steps = 0;  // every evaluation's growth.steps
  long every = 1;  // and output.every_steps
};

FitSetup checkFit(const FitOptions& given, const GroupSide* group, const std::function<void(const std::string&)>& log) {
  FitOptions o = given;  // its objective resolved below (the trace's own default)
  // bad input first, before anything is written
  if (o.scene.empty()) throw SceneError("--scene: give the base scene (a TOML file)");
  if (o.budget < 1 || o.budget > 100000)
    throw SceneError("--budget " + std::to_string(o.budget) + ": expected an integer in [1, 100000] runs");
  if (o.jobs < 1 || o.jobs > 256) throw SceneError("-j " + std::to_string(o.jobs) + ": must be in [1, 256]");
  if (!o.objective.empty() && o.objective != "observables" && o.objective != "shape" && o.objective != "timelapse")
    throw SceneError("--objective " + o.objective + ": expected observables, shape or timelapse");
  if (o.out.empty()) throw SceneError("--out: give the fit's folder");
  const fs::path out = checkOutputName(o.out, "--out");
  OutputLock lock = lockOutput(out, "--out");
  const Scene base = loadScene(o.scene);
  if (base.isPlate())
    throw SceneError("--scene " + o.scene + ": a plate's scene; fit takes the scene of one root (docs/experiments.md)");
  const Model& bm = base.model;
  if (!bm.growth.enabled) throw SceneError(o.scene + ": growth.enabled = false; fit grows the root to the trace's length");
  const TraceTarget target = group ? group->target : loadTarget(o.trace, bm);
  // a trace with times is fitted at every observation time unless another objective is asked for
  if (o.objective.empty()) o.objective = target.timesH.empty() ? "observables" : "timelapse";
  const bool lapse = o.objective == "timelapse";
  if (lapse && target.timesH.empty())
    throw SceneError("--objective timelapse: " + o.trace.trace + " (root " + target.rootKey +
                     ") has no observation times (a trace of one time); use --objective observables or shape");
  const TimeLapseObjective lapseTrace = lapse ? timeLapseObjective(target) : TimeLapseObjective{};
  const std::vector<FreeKey> keys = parseFreeKeys(o.free, o.scene, lapse);
  const int n = static_cast<int>(keys.size());
  const FitSize size = fitSize(o, n);
  if (!group && o.objective == "observables" && usedCount(observeBoth(target.traits, target.traits, target.sigmaMm)) < n)
    log("fit: note: the trace defines " + std::to_string(usedCount(observeBoth(target.traits, target.traits, target.sigmaMm))) +
        " observable(s) for " + std::to_string(n) + " free key(s): some direction stays undetermined (try --objective shape)");
  // grow every evaluation to the trace's length: L0 + steps * step * rate * Lgz
  const double perStepMm = bm.growth.stepTime * bm.growth.rate * bm.growth.zoneLength / units::mm;
  const double l0 = bm.initial.length / units::mm;
  // the root's length, not its noisy trace's: a run grown to the trace's would be the time of the extra
  // length older (on the validation's skewing root, 1.5 h of a tip that swings every 2.5 h)
  if (target.rootLengthMm <= l0)
    throw SceneError(o.trace.trace + ": the traced root (" + numberText(target.rootLengthMm) +
                     " mm) is not longer than the scene's initial root (root.initial_length_mm = " + numberText(l0) + ")");
  // a time-lapse: to its last observation time, a snapshot at every observation time that falls on a step
  // (the largest common divisor of their steps; else every step)
  const double stepH = bm.growth.stepTime / units::hour;
  // a trace of one time: past the root's length by kLengthMargin, a snapshot every kSnapshotMm of growth,
  // and the snapshot as long on the plate as the root compared (comparedSnapshot; the nearest, within
  // kSnapshotMm / 2, where stopping at the root's length held it to a step): a root that rises off the
  // plate is longer than a scan of it shows
  constexpr double kLengthMargin = 0.03, kSnapshotMm = 0.025;
  const long steps = lapse ? std::lround(std::ceil(lapseTrace.timesH.back() / stepH - 1e-9))
                           : std::lround(std::ceil((target.rootLengthMm * (1.0 + kLengthMargin) - l0) / perStepMm - 1e-9));
  long every = std::max(1L, static_cast<long>(std::floor(kSnapshotMm / perStepMm)));
  if (lapse) {
    every = steps;
    for (double t : lapseTrace.timesH) {
      const double at = t / stepH;
      every = std::abs(at - std::round(at)) < 1e-6 ? std::gcd(every, std::lround(at)) : 1;
      if (every == 1) break;
    }
    every = std::max(1L, every);
  }
  return FitSetup{std::move(o), out, std::move(lock), base, target, lapse, lapseTrace, keys, size, steps, every};
}

// the fit's folder claimed, its base scene (base.toml: the scene grown to the trace, with the fit's
// settings) and its start design (design.toml) written; returns base.toml's text
std::string writeBaseAndDesign(const FitSetup& setup, const GroupSide* group) {
  const FitOptions& o = setup.o;
  const fs::path& out = setup.out;
  const std::vector<FreeKey>& keys = setup.keys;
  const long steps = setup.steps, every = setup.every;
  const bool lapse = setup.lapse;
  const int k = setup.size.levels;
  WriteRule rule;
  rule.force = o.force;
  rule.inputs.push_back(WriteInput{o.scene, {}, true});
  if (group)
    for (const std::string& f : group->inputs) rule.inputs.push_back(WriteInput{f, {}, true});
  else
    rule.inputs.push_back(WriteInput{o.trace.trace, {}, true});
  rule.inputs.push_back(workingFolder());
  claimFolder(out, fitFolder(), rule, "--out", false);
  // the base scene every evaluation starts from: the scene, grown to the trace's length, without ParaView files
  const Scene grown = loadScene(o.scene, {"growth.steps=" + std::to_string(steps), "output.vtk=false", "output.trajectory=true",
                                          "output.every_steps=" + std::to_string(every)});
  // the fit's settings in a comment: a second fit into this folder with any other setting starts again
  // (only with --force); with the same settings it continues, its finished runs reused
  std::string settings = "# rootsim fit settings: --free";
  for (const FreeKey& fk : keys) settings += " " + fk.key + "=" + numberText(fk.lo) + ":" + numberText(fk.hi);
  auto flagNum = [](double v) { return v == TraceFlags::kUnset ? std::string("default") : numberText(v); };
  settings += " --objective " + o.objective + " --budget " + std::to_string(o.budget) + " --trace " + o.trace.trace +
              " --root " + (o.trace.root.empty() ? std::string("default") : o.trace.root) + " --px-per-mm " +
              flagNum(o.trace.pxPerMm) + " --downhill " + o.trace.downhill + " --sigma-mm " + flagNum(o.trace.sigmaMm) +
              (group ? " " + group->settings : std::string()) + "\n";
  const std::string baseText = "# rootsim fit: " + o.scene + " with growth.steps = " + std::to_string(steps) +
                               (lapse ? " (the trace's last observation time), output.every_steps = " + std::to_string(every) : " (the trace's length and 3 %), output.every_steps = " + std::to_string(every)) +
                               " and output.vtk = false\n" + settings + grown.resolvedToml;
  const bool stale = fs::exists(out / "base.toml") && fileText(out / "base.toml") != baseText;
  if (stale && !o.force)
    throw SceneError("--out " + out.string() + ": holds a fit of another scene, trace or settings (its base.toml differs: " +
                     "--free, --objective, --budget, the trace's flags); pass --force to start it again, or choose another --out");
  createOwnFolder(out, fitFolder());
  if (stale) {
    // --force: the earlier evaluations belong to another base scene
    std::error_code ec;
    if (fs::is_directory(out / "runs") && whyNotOurs(out / "runs", sweepFolder()).empty()) fs::remove_all(out / "runs", ec);
  }
  writeFileAtomic(out / "base.toml", baseText);
  recordWritten({out / "base.toml"});
  // the start design as a sweep file: `rootsim sweep DIR/design.toml --out DIR/runs --shard K/N` runs it
  // anywhere (SLURM), and the fit then finds its runs complete
  std::string designText = "# rootsim fit: the start design (" + std::to_string(k) + " levels per key, cell centres of the box)\n"
                           "[sweep]\nscene = \"base.toml\"\n\n[grid]\n";
  for (const FreeKey& fk : keys) {
    designText += "\"" + fk.key + "\" = [";
    for (int i = 0; i < k; ++i) {
      designText += (i ? ", " : "") + numberText(std::strtod(significantText(fk.lo + (i + 0.5) / k * (fk.hi - fk.lo), 9).c_str(), nullptr));
    }
    designText += "]\n";
  }
  // a group's: each point run once per sowing angle of its seedlings
  if (group) {
    designText += "\"" + std::string(kSowingKey) + "\" = [";
    for (std::size_t i = 0; i < group->angles.size(); ++i) designText += (i ? ", " : "") + group->angles[i];
    designText += "]\n";
  }
  writeFileAtomic(out / "design.toml", designText);
  recordWritten({out / "design.toml"});
  return baseText;
}

// 1. the start design, as a sweep: every point's run recorded in the fit
void runStartDesign(const FitSetup& setup, const GroupSide* group, Fit& fit, const std::function<void(const std::string&)>& log) {
  const FitOptions& o = setup.o;
  const fs::path& out = setup.out;
  const std::vector<FreeKey>& keys = setup.keys;
  const SweepPlan plan = loadSweep((out / "design.toml").string());
  SweepOptions so;
  so.jobs = o.jobs;
  so.out = (out / "runs").string();
  so.quiet = true;
  so.force = true;  // its own runs: a point whose run failed is run again
  so.inputs = {out / "design.toml", out / "base.toml"};
  // a group's design point is complete when each of its sowing angles' runs is: gathered here
  struct Gathered {
    std::vector<fs::path> dirs;
    std::string error;
    int have = 0;
    long order = 0;
  };
  std::map<std::string, Gathered> gathered;
  std::mutex gatherMu;
  const std::size_t angles = group ? group->angles.size() : 1;
  so.onPoint = [&](const SweepPointDone& d) {
    // in the free keys' order (a sweep file's grid comes back in its keys' sorted order)
    std::vector<double> x;
    std::string xText, angle;
    for (const FreeKey& fk : keys)
      for (const auto& [key, val] : d.point->grid)
        if (key == fk.key) x.push_back(std::stod(val)), xText += val + ";";
    for (const auto& [key, val] : d.point->grid)
      if (key == kSowingKey) angle = val;
    if (x.size() != keys.size()) throw RunError("fit: the design point " + d.dir + " lacks a free key");
    if (!group) {
      fit.recordDesign(x, {d.dir}, d.error, d.point->index);
      return;
    }
    const auto at = std::find_if(group->angles.begin(), group->angles.end(),
                                 [&](const std::string& a) { return !angle.empty() && std::stod(a) == std::stod(angle); });
    if (at == group->angles.end()) throw RunError("fit: the design point " + d.dir + " has no sowing angle of the group's");
    Gathered done;
    {
      std::lock_guard lk(gatherMu);
      Gathered& g = gathered[xText];
      if (g.dirs.empty()) g.dirs.resize(angles), g.order = d.point->index;
      g.dirs[static_cast<std::size_t>(at - group->angles.begin())] = d.dir;
      g.order = std::min<long>(g.order, d.point->index);
      if (g.error.empty()) g.error = d.error;
      if (++g.have < static_cast<int>(angles)) return;
      done = g;
    }
    fit.recordDesign(x, done.dirs, done.error, done.order);
  };
  runSweep(plan, so, [&](const std::string& line) {
    if (!o.quiet && line.find("FAILED") != std::string::npos) log(line);
  });
  {
    const std::vector<FitEvaluation> ev = fit.evaluations();
    if (std::all_of(ev.begin(), ev.end(), [](const FitEvaluation& e) { return !e.error.empty(); }))
      throw RunError("fit: every run of the start design failed; the first: " + ev.front().error);
  }
}

// `count` points of the Halton sequence from index `index` on (advanced past them), spread over the box
// [lo, hi]: one prime base per key (at most 12 keys)
std::vector<Eigen::VectorXd> haltonPoints(const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, int count, long& index) {
  static const int kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
  const auto n = static_cast<int>(lo.size());
  std::vector<Eigen::VectorXd> batch;
  for (int i = 0; i < count; ++i, ++index) {
    Eigen::VectorXd u(n);
    for (int d = 0; d < n; ++d) u(d) = lo(d) + halton(index, kPrimes[d]) * (hi(d) - lo(d));
    batch.push_back(u);
  }
  return batch;
}

// the progress line of trust region `region` (from 1): its half width, its runs, the surface's minimum xs
// with each key's sigma, the minimum's chi-square and the model's scatter
std::string regionLine(int region, double rho, std::size_t runs, const std::vector<FreeKey>& keys, const std::vector<double>& xs,
                       const FitUncertainty& unc, const ResponseSurface& surface) {
  std::string line = "fit: trust region " + std::to_string(region) + " (half width " + numberText(std::round(rho * 1e4) / 1e4) +
                     " of the box, " + std::to_string(runs) + " runs): surface minimum";
  for (std::size_t i = 0; i < keys.size(); ++i) {
    char b[96];
    std::snprintf(b, sizeof b, " %s=%.5g +- %.2g", keys[i].key.c_str(), xs[i], unc.sigma[i] * (keys[i].hi - keys[i].lo));
    line += b;
  }
  char b[96];
  std::snprintf(b, sizeof b, ", chi2 %.3g for %d dof, model scatter %.3g (RMS over outputs)", unc.chi2, unc.dof,
                std::sqrt(surface.noiseVar().mean()));
  return line + b;
}

// what the trust regions found: the last box's half width (scaled), surface and minimum's uncertainty, the
// minima of the regions at the smallest box and their uncertainties, the last minimum, the regions' count
struct TrustRegions {
  double rho = 0;
  ResponseSurface surface;
  FitUncertainty unc;
  std::vector<Eigen::VectorXd> atSmallest;
  std::vector<FitUncertainty> smallestUnc;
  std::vector<ResponseSurface> smallestSurfaces;  // and their surfaces
  Eigen::VectorXd ustar;
  int regions = 0;
};

// 2. trust regions: runs spread over a box around the best point so far, a quadratic surface of the
//   outputs fitted to them, its minimum the next centre; a minimum inside the box halves it (down to
//   kSmallestBox), one on its edge moves it. At the smallest box it stops when the minimum moves by
//   less than half its uncertainty, when a direction is flat, or when the budget is spent.
TrustRegions runTrustRegions(const FitSetup& setup, Fit& fit, const std::function<void(const std::string&)>& log) {
  const FitOptions& o = setup.o;
  const std::vector<FreeKey>& keys = setup.keys;
  const int n = static_cast<int>(keys.size());
  const int k = setup.size.levels, terms = setup.size.terms, regionPoints = setup.size.regionPoints;
  // a group's covariance from the residuals at the start design's best run (chosen against the
  // seedlings' own scatter; an offset common to the seedlings is not scatter), estimated again at each
  // region's minimum and last at the answer's point (covarianceAtAnswer)
  if (fit.byGroup()) fit.useCovarianceOf(fit.bestSoFar());
  Eigen::VectorXd centre;
  {
    double bestF = std::numeric_limits<double>::infinity();
    for (const FitEvaluation& e : fit.evaluations())
      if (e.error.empty() && e.objective < bestF) {
        bestF = e.objective;
        centre = fit.uOf(e.x);
      }
  }
  double rho = 1.0 / k;  // the box's half width (scaled)
  long haltonIndex = 1;
  ResponseSurface surface;
  FitUncertainty unc;
  std::vector<Eigen::VectorXd> atSmallest;   // the minima of the regions at the smallest box
  std::vector<FitUncertainty> smallestUnc;   // and their uncertainties
  std::vector<ResponseSurface> smallestSurfaces;
  Eigen::VectorXd ustar = centre;
  bool haveSurface = false;
  int regions = 0;
  if (n > 12) throw SceneError("--free: at most 12 free keys");
  for (; regions < 20; ++regions) {
    const Eigen::VectorXd lo = (centre.array() - rho).max(0.0).matrix(), hi = (centre.array() + rho).min(1.0).matrix();
    auto inBox = [&](const Eigen::VectorXd& u) {
      return ((u.array() >= lo.array() - 1e-12) && (u.array() <= hi.array() + 1e-12)).all();
    };
    int have = 0;
    for (const FitEvaluation& e : fit.evaluations()) have += e.error.empty() && inBox(fit.uOf(e.x));
    // kept back: this region's minimum and the answer's run
    const int left = o.budget - fit.count() - 2;
    const int need = std::min(std::max(0, regionPoints - have), std::max(0, left));
    if (have + need <= terms + 1) break;  // no budget for a surface here
    fit.evaluateAll(haltonPoints(lo, hi, need, haltonIndex), "region " + std::to_string(regions + 1));
    std::vector<Eigen::VectorXd> us, ys;
    for (const FitEvaluation& e : fit.evaluations())
      if (e.error.empty() && inBox(fit.uOf(e.x))) {
        us.push_back(fit.uOf(e.x));
        ys.push_back(e.sim);
      }
    if (static_cast<int>(us.size()) <= terms) break;
    surface = fitResponseSurface(us, ys, centre, rho);
    // rounded to 1e-6 of the box: short run names, and the same names when a fit resumes
    const Eigen::VectorXd next = (surfaceMinimum(surface, fit.traceComponents(), lo, hi) * 1e6).array().round().matrix() / 1e6;
    unc = uncertaintyAt(surface, next, fit.traceComponents().trace, fit.traceComponents().cov);
    haveSurface = true;
    ustar = next;
    if (!o.quiet) log(regionLine(regions + 1, rho, us.size(), keys, fit.xOf(next), unc, surface));
    if (fit.count() < o.budget - 1)
      fit.useCovarianceOf(fit.evaluate(fit.xOf(next), "minimum " + std::to_string(regions + 1), fit.nextOrder(1)), &lo, &hi);
    bool onEdge = false;
    for (int d = 0; d < n; ++d)
      onEdge = onEdge || (next(d) - lo(d) < 0.05 * rho && lo(d) > 0) || (hi(d) - next(d) < 0.05 * rho && hi(d) < 1);
    centre = next;
    const bool smallest = rho <= kSmallestBox / k * 1.0001;
    if (smallest && !onEdge) {
      atSmallest.push_back(next);
      smallestUnc.push_back(unc);
      smallestSurfaces.push_back(surface);
    }
    if (fit.count() >= o.budget - 1) break;
    if (onEdge) continue;
    if (!unc.flat.empty()) break;  // more runs cannot find what the trace does not determine
    if (rho > kSmallestBox / k * 1.0001) {
      rho = std::max(0.5 * rho, kSmallestBox / k);
      continue;
    }
    // the smallest box: kFinalRegions of them, each re-centred on the last minimum; their minima scatter
    // by what a surface of this many runs can resolve
    if (static_cast<int>(atSmallest.size()) >= kFinalRegions) break;
  }
  if (!haveSurface) throw RunError("fit: the budget ran out before a surface could be fitted (raise --budget)");
  return TrustRegions{rho, surface, unc, atSmallest, smallestUnc, smallestSurfaces, ustar, regions};
}

// the answer's point (scaled): the mean of the minima at the smallest box, rounded to 1e-6 of the box
// (the last minimum without any)
Eigen::VectorXd answerPoint(const TrustRegions& tr) {
  if (tr.atSmallest.empty()) return tr.ustar;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(tr.ustar.size());
  for (const Eigen::VectorXd& m : tr.atSmallest) u += m / static_cast<double>(tr.atSmallest.size());
  return (u * 1e6).array().round().matrix() / 1e6;
}

// a fit by group: the covariance at the answer's point (its run made now, as the answer would make it),
// and the regions' uncertainties again against it
void covarianceAtAnswer(Fit& fit, TrustRegions& tr) {
  if (!fit.byGroup()) return;
  // the box of the answer's uncertainty (answerUncertainty's): its runs the seedlings' surfaces
  const Eigen::VectorXd u = answerPoint(tr);
  const Eigen::VectorXd lo = (u.array() - tr.rho).max(0.0).matrix(), hi = (u.array() + tr.rho).min(1.0).matrix();
  fit.useCovarianceOf(fit.evaluate(fit.xOf(u), "minimum", fit.nextOrder(1)), &lo, &hi);
  const FitComponents& tc = fit.traceComponents();
  for (std::size_t r = 0; r < tr.atSmallest.size(); ++r) tr.smallestUnc[r] = uncertaintyAt(tr.smallestSurfaces[r], tr.atSmallest[r], tc.trace, tc.cov);
  tr.unc = uncertaintyAt(tr.surface, tr.ustar, tc.trace, tc.cov);
}

// the answer's values (scaled) and their uncertainty: per key the scaled sigma, the bootstrap's part
// (in the key's units; NaN without one), and the covariance scale the sigmas' statistical part carries
struct AnswerUncertainty {
  Eigen::VectorXd ustar;
  std::vector<double> sigmaU, bootSigma;
  double surfaceScale = 1;
};

// 3. the answer: the mean of the minima at the smallest box. Its variance: the linearised surface's (the
// trace's error and the model's scatter, mean over those regions) plus the surface's own estimation
// error, the larger of the minima's spread over the regions and a bootstrap over the runs in the box
// around the answer (kBootstrap resamples, each refitted and minimised)
AnswerUncertainty answerUncertainty(const FitSetup& setup, Fit& fit, const TrustRegions& tr) {
  const std::vector<FreeKey>& keys = setup.keys;
  const int n = static_cast<int>(keys.size());
  const int terms = setup.size.terms;
  const FitUncertainty& unc = tr.unc;
  const std::vector<Eigen::VectorXd>& atSmallest = tr.atSmallest;
  const std::vector<FitUncertainty>& smallestUnc = tr.smallestUnc;
  const double rho = tr.rho;
  Eigen::VectorXd ustar = tr.ustar;
  std::vector<double> sigmaU(static_cast<std::size_t>(n), kNaN);
  std::vector<double> bootSigma(static_cast<std::size_t>(n), kNaN);
  double surfaceScale = unc.scale;  // the covariance scale sigmaU's statistical part already carries
  if (atSmallest.empty()) {
    for (int i = 0; i < n; ++i) sigmaU[static_cast<std::size_t>(i)] = unc.sigma[static_cast<std::size_t>(i)];
  } else {
    ustar = answerPoint(tr);
    surfaceScale = 0;
    for (const FitUncertainty& u : smallestUnc) surfaceScale += u.scale / static_cast<double>(smallestUnc.size());
    const Eigen::VectorXd lo = (ustar.array() - rho).max(0.0).matrix(), hi = (ustar.array() + rho).min(1.0).matrix();
    std::vector<Eigen::VectorXd> us, ys;
    for (const FitEvaluation& e : fit.evaluations()) {
      const Eigen::VectorXd u = fit.uOf(e.x);
      if (e.error.empty() && ((u.array() >= lo.array() - 1e-12) && (u.array() <= hi.array() + 1e-12)).all()) {
        us.push_back(u);
        ys.push_back(e.sim);
      }
    }
    std::vector<Eigen::VectorXd> minima;
    std::mt19937 gen(20241202);  // fixed: the same fit, the same bytes
    std::uniform_int_distribution<std::size_t> pick(0, us.empty() ? 0 : us.size() - 1);
    for (int b = 0; b < kBootstrap && static_cast<int>(us.size()) > terms + 1; ++b) {
      std::vector<Eigen::VectorXd> bu, by;
      for (std::size_t k2 = 0; k2 < us.size(); ++k2) {
        const std::size_t j = pick(gen);
        bu.push_back(us[j]);
        by.push_back(ys[j]);
      }
      try {
        const ResponseSurface rs = fitResponseSurface(bu, by, ustar, rho);
        minima.push_back(surfaceMinimum(rs, fit.traceComponents(), lo, hi));
      } catch (const std::invalid_argument&) {
        // a resample without enough distinct runs: skipped
      }
    }
    for (int i = 0; i < n; ++i) {
      double var = 0, spread = 0;
      for (std::size_t r = 0; r < atSmallest.size(); ++r) {
        const double s = smallestUnc[r].sigma[static_cast<std::size_t>(i)];
        var += s * s / static_cast<double>(atSmallest.size());
        spread += std::pow(atSmallest[r](i) - ustar(i), 2);
      }
      if (atSmallest.size() > 1) spread /= static_cast<double>(atSmallest.size() - 1);
      double boot = 0;
      if (minima.size() > 1) {
        double mean = 0;
        for (const Eigen::VectorXd& m : minima) mean += m(i) / static_cast<double>(minima.size());
        for (const Eigen::VectorXd& m : minima) boot += std::pow(m(i) - mean, 2) / static_cast<double>(minima.size() - 1);
        bootSigma[static_cast<std::size_t>(i)] = std::sqrt(boot) * (keys[static_cast<std::size_t>(i)].hi - keys[static_cast<std::size_t>(i)].lo);
      }
      sigmaU[static_cast<std::size_t>(i)] = std::sqrt(var + std::max(spread, boot));  // NaN when a surface had none
    }
  }
  return AnswerUncertainty{ustar, sigmaU, bootSigma, surfaceScale};
}

// 4. the answer: the run at the surface's minimum (made when no run had its values), the run chosen,
// its sigmas (widened by the Birge ratio), the notes; returns the surface minimum's values
std::vector<double> chooseFitAnswer(FitReport& rep, const FitSetup& setup, Fit& fit, const TrustRegions& tr,
                                    const AnswerUncertainty& au) {
  const FitOptions& o = setup.o;
  const std::vector<FreeKey>& keys = setup.keys;
  const int n = static_cast<int>(keys.size());
  const Model& bm = setup.base.model;
  const TraceTarget& target = setup.target;
  const bool lapse = setup.lapse;
  const TimeLapseObjective& lapseTrace = setup.lapseTrace;
  const ResponseSurface& surface = tr.surface;
  const FitUncertainty& unc = tr.unc;
  const Eigen::VectorXd& ustar = au.ustar;
  const std::vector<double>& sigmaU = au.sigmaU;
  const double surfaceScale = au.surfaceScale;
  const std::vector<double> bx = fit.xOf(ustar);
  rep.sigma.assign(static_cast<std::size_t>(n), kNaN);
  for (int i = 0; i < n; ++i)
    rep.sigma[static_cast<std::size_t>(i)] = sigmaU[static_cast<std::size_t>(i)] * (keys[static_cast<std::size_t>(i)].hi - keys[static_cast<std::size_t>(i)].lo);
  for (int i = 0; i < n; ++i) {
    const double u = ustar(i);
    if (u < 1e-3 || u > 1 - 1e-3)
      rep.notes.push_back(keys[static_cast<std::size_t>(i)].key + " = " + numberText(bx[static_cast<std::size_t>(i)]) +
                          " lies at a bound of the box: widen it (the best value may lie beyond)");
  }
  for (const Eigen::VectorXd& v : unc.flat) {
    std::string dir;
    for (int i = 0; i < n; ++i) dir += (i ? ", " : "") + keys[static_cast<std::size_t>(i)].key + " " + numberText(std::round(v(i) * 100) / 100);
    rep.notes.push_back("flat: the objective rises by less than 1 across the whole box along (" + dir +
                        ") (each key scaled by its box width): the trace does not determine this combination");
  }
  if (unc.covariance.size() == 0 && unc.flat.empty())
    rep.notes.push_back("the surface's curvature at the minimum is singular: no uncertainty");
  // the run at the surface's minimum, made now when no run had its values
  auto surfaceRunOf = [&](const std::vector<FitEvaluation>& ev) {
    for (std::size_t i = 0; i < ev.size(); ++i)
      if (ev[i].x == bx && ev[i].error.empty()) return static_cast<int>(i);
    return -1;
  };
  rep.evaluations = fit.evaluations();
  if (surfaceRunOf(rep.evaluations) < 0 && std::none_of(rep.evaluations.begin(), rep.evaluations.end(), [&](const FitEvaluation& e) { return e.x == bx; })) {
    fit.evaluate(bx, "minimum", fit.nextOrder(1));
    rep.evaluations = fit.evaluations();
  }
  rep.surfaceRun = surfaceRunOf(rep.evaluations);
  if (rep.surfaceRun < 0) rep.notes.push_back("the run at the surface's minimum failed: the answer is the best run the fit made");
  // every evaluation's chi-square with the model's scatter added (the final surface's): the objective the
  // answer is chosen by
  const FitComponents& tc = fit.traceComponents();
  for (FitEvaluation& e : rep.evaluations)
    if (e.error.empty()) e.objective = chiSquareOf(e.sim, tc.trace, totalCovariance(surface, tc.cov));
  // the answer: never worse than a run the fit made; its goodness against the trace's uncertainty alone
  // the goodness: the shape's against the covariance a trace of the answer's run would have (its points'
  // noise propagated through the sampling: the null hypothesis that the run is the root), the observables'
  // against their uncertainties
  chooseAnswer(rep, target, tc, surface.noiseVar().cwiseSqrt(), bm, sceneFileKeys(o.scene), [&](const FitEvaluation& e) {
    if (o.objective != "shape") return e.chi2Trace;
    const Model em = fit.sceneAt(e.x).model;
    const SimRoot sim = simRootOf(em, comparedSnapshot(em, loadSnapshots(e.dir), target, lapse), target);
    return chiSquareOf(e.sim, tc.trace, shapeNoiseCovariance(tracedLike(sim.plateMm, target.plateMm), target.sigmaMm, kShapeSamples));
  });
  // the answer's run against the trace's uncertainty alone fits worse than that uncertainty allows (chi2 /
  // dof above 1, beyond the surface's scale the sigmas already carry): every sigma widens by the square
  // root of the rest (the Birge ratio), so a fit the model follows less closely than the data's noise
  // claims no more than its data (docs/experiments.md, "What a fit may claim")
  if (rep.goodness.dof > 0) {
    rep.answerScale = std::max(1.0, rep.goodness.chi2 / rep.goodness.dof / std::max(1.0, surfaceScale));
    for (double& s : rep.sigma) s *= std::sqrt(rep.answerScale);
  }
  rep.covariance = reportedCovariance(unc.covariance, rep.sigma);
  if (lapse) growthAgainstTrace(rep, lapseTrace, bm);
  const FitEvaluation& best = rep.evaluations[static_cast<std::size_t>(rep.best)];
  if (rep.surfaceRun >= 0 && rep.best != rep.surfaceRun) {
    char line[240];
    std::snprintf(line, sizeof line, "the answer is the run %s (objective %.4g), better than the surface minimum's run (%.4g)",
                  fs::path(best.dir).filename().string().c_str(), best.objective, rep.evaluations[static_cast<std::size_t>(rep.surfaceRun)].objective);
    rep.notes.push_back(line);
  }
  return bx;
}

}  // namespace

// the fit in its steps: the input checked, the folder's base scene and start design written, the start
// design run, the trust regions, the answer's uncertainty, the answer, the outputs
FitReport runFitOn(const FitOptions& given, const GroupSide* group, const std::function<void(const std::string&)>& log) {
  const FitSetup setup = checkFit(given, group, log);
  const std::string baseText = writeBaseAndDesign(setup, group);
  if (setup.o.designOnly) {
    // its runs made elsewhere (rootsim sweep DESIGN --out DIR/runs --shard K/N), found complete on rerun
    FitReport only;
    only.keys = setup.keys;
    only.out = setup.out.string();
    only.design = (setup.out / "design.toml").string();
    return only;
  }
  Fit fit(setup.o, setup.keys, setup.out, baseText, setup.target, log, group);
  runStartDesign(setup, group, fit, log);
  TrustRegions tr = runTrustRegions(setup, fit, log);
  covarianceAtAnswer(fit, tr);
  FitReport rep;
  rep.keys = setup.keys;
  rep.out = setup.out.string();
  rep.evaluations = fit.evaluations();
  const AnswerUncertainty au = answerUncertainty(setup, fit, tr);
  const std::vector<double> bx = chooseFitAnswer(rep, setup, fit, tr, au);

  // 5. the outputs
  FitOutcome f;
  f.options = &setup.o;
  f.target = &setup.target;
  f.out = setup.out;
  f.steps = setup.steps;
  f.levels = setup.size.levels;
  f.regionPoints = setup.size.regionPoints;
  f.regions = tr.regions;
  f.rho = tr.rho;
  f.surface = tr.surface;
  f.unc = tr.unc;
  f.ustar = au.ustar;
  f.surfaceX = bx;
  f.bootSigma = au.bootSigma;
  f.trace = fit.traceComponents();
  rep.trace = f.trace;
  writeFitOutputs(f, rep, fit.sceneAt(rep.evaluations[static_cast<std::size_t>(rep.best)].x));
  return rep;
}

std::string designOnlyText(const std::vector<std::string>& designs) {
  std::string t = "the start design, nothing run: run ";
  for (std::size_t i = 0; i < designs.size(); ++i) {
    const fs::path d = designs[i];
    t += (i ? "; " : "") + std::string("rootsim sweep ") + d.string() + " --out " + (d.parent_path() / "runs").string() + " [--shard K/N]";
  }
  return t + "; then this fit again without --design-only: it finds those runs complete";
}

int fitCommand(const FitOptions& o) {
  if (!o.groups.empty()) return groupFitCommand(o);
  if (!o.more.empty())
    throw SceneError("fit: " + std::to_string(o.more.size() + 1) + " RSML files: several files are a plate fitted by group; give --groups SHEET.csv");
  const FitReport r = runFit(o, [&](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
  if (o.designOnly) {
    std::printf("%s\n", designOnlyText({r.design}).c_str());
    return 0;
  }
  const FitEvaluation& b = r.evaluations[static_cast<std::size_t>(r.best)];
  for (std::size_t i = 0; i < r.keys.size(); ++i) {
    if (std::isfinite(r.sigma[i]))
      std::printf("%s = %.6g +- %.3g\n", r.keys[i].key.c_str(), b.x[i], r.sigma[i]);
    else
      std::printf("%s = %.6g (no uncertainty: see the notes)\n", r.keys[i].key.c_str(), b.x[i]);
  }
  std::printf("fixed: %s\n", fixedKeysText(r.fixed).c_str());
  std::printf("%zu runs; the answer's run (%s): distance %.3g mm to the trace\n", r.evaluations.size(),
              r.best == r.surfaceRun ? "the surface's minimum" : "the best run the fit made", b.distanceMm);
  std::printf("goodness: %s%s\n", goodnessText(r.goodness).c_str(), r.growthMismatch.empty() ? "" : ("; " + r.growthMismatch).c_str());
  if (!r.misfit.empty()) std::printf("poor fit: %s\n", r.misfit.c_str());
  for (const std::string& n : r.notes) std::printf("note: %s\n", n.c_str());
  if (!o.quiet) std::fprintf(stderr, "wrote %s (fit.json, evaluations.csv, best.toml, compare.*%s)\n", r.out.c_str(),
                             r.keys.size() == 2 ? ", landscape.*" : "");
  return 0;
}

}  // namespace rootsim::app
