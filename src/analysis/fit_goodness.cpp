// `rootsim fit`: the answer among its runs, its goodness of fit, the fixed keys that shape it, and what a
// poor fit could not reproduce (docs/experiments.md, "What a fit claims").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "fit_parts.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"

namespace rootsim::app {

namespace {

// the keys that shape a root's answer when held fixed, in the order printed: the plate's tilt and the
// growth first (a trace does not say them; the experiment does), then the gains and the root's size
const char* const kShapingKeys[] = {"plane.alpha_deg",      "growth.rate_per_h",       "growth.growth_zone_mm",
                                    "tropism.beta",         "tropism.gamma",           "tropism.sensing",
                                    "tropism.twist_r_tau",  "tropism.circumnutation_gain", "root.radius_mm"};

std::string valueOf(const std::vector<SceneValue>& values, const std::string& key) {
  for (const SceneValue& v : values)
    if (v.key == key) return v.text;
  return {};
}

const FixedKey* findFixed(const std::vector<FixedKey>& fixed, const std::string& key) {
  for (const FixedKey& f : fixed)
    if (f.key == key) return &f;
  return nullptr;
}

std::string mm(double v) { return significantText(v, 2); }

}  // namespace

std::vector<FixedKey> sceneFixedKeys(const Model& base, const std::vector<FreeKey>& free, const std::vector<std::string>& fileKeys) {
  const std::vector<SceneValue> values = sceneValues(base, OutputParams{});  // the shaping keys: the model's
  std::vector<FixedKey> fixed;
  for (const char* key : kShapingKeys) {
    if (std::any_of(free.begin(), free.end(), [&](const FreeKey& f) { return f.key == key; })) continue;
    const std::string v = valueOf(values, key);
    if (v.empty()) continue;
    const bool set = std::find(fileKeys.begin(), fileKeys.end(), key) != fileKeys.end();
    fixed.push_back(FixedKey{key, v, set ? "scene" : "default"});
    if (fixed.back().key == "growth.growth_zone_mm") {
      // the tip speed v = rate * Lgz: what a time-lapse measures
      const double speed = base.growth.rate * base.growth.zoneLength / (units::mm / units::hour);
      // a product: to the scene values' own digits
      fixed.push_back(FixedKey{"tip_speed_mm_per_h", significantText(speed, 6), "growth.rate_per_h * growth.growth_zone_mm"});
    }
  }
  return fixed;
}

std::string fixedKeysText(const std::vector<FixedKey>& fixed) {
  std::string s;
  for (const FixedKey& f : fixed)
    s += (s.empty() ? "" : ", ") + f.key + " = " + f.value + " (" + (f.source == "scene" || f.source == "default" ? f.source : "derived") + ")";
  return s;
}

// a miss within this many times the runs' scatter, a scatter of more than this many times the trace's
// uncertainty: the runs' own scatter explains the miss (misfitSentence)
constexpr double kScatterMiss = 3.0;

std::string misfitSentence(const TraceTarget& target, const std::vector<FitEvaluation>& evaluations, const FitEvaluation& answer,
                           const FitComponents& trace, const Eigen::VectorXd& modelSigma, const std::vector<FixedKey>& fixed) {
  // what the runs did: how many wave, their amplitudes, their most common pattern
  int runs = 0, waving = 0;
  double aLo = std::numeric_limits<double>::infinity(), aHi = 0;
  double sLo = std::numeric_limits<double>::infinity(), sHi = 0;  // the runs' straightness
  std::map<std::string, int> patterns;
  for (const FitEvaluation& e : evaluations) {
    if (!e.error.empty()) continue;
    ++runs;
    ++patterns[e.pattern];
    sLo = std::min(sLo, e.straightness);
    sHi = std::max(sHi, e.straightness);
    if (e.pattern == "waving") {
      ++waving;
      aLo = std::min(aLo, e.amplitudeMm);
      aHi = std::max(aHi, e.amplitudeMm);
    }
  }
  std::string common;
  int most = 0;
  for (const auto& [p, c] : patterns)
    if (c > most) {
      most = c;
      common = p;
    }
  const ShapeAnalysis& ts = target.traits.shape;
  const bool traceWaves = ts.pattern == "waving";
  std::string what;
  const char* suggest = "plane.alpha_deg";  // the tilt sets the waves' amplitude (docs/model.md, Eq. 10)
  if (!traceWaves && runs > 0 && waving == runs) {
    what = "the trace is " + ts.pattern + ", every run waves (A " + mm(aLo) + "-" + mm(aHi) + " mm)";
  } else if (traceWaves && waving == 0 && runs > 0) {
    what = "the trace waves (lambda " + mm(ts.wavelength / units::mm) + " mm, A " + mm(ts.amplitude / units::mm) +
           " mm), no run does (" + (most == runs ? "every run is " : "most runs are ") + common + ")";
  } else if (const double st = target.traits.chordMm / target.rootLengthMm; runs > 0 && (st > sHi || st < sLo)) {
    // (the root's length, not its noisy trace's: 0.6 px of noise on points 3 px apart makes a straight
    // root's trace 5 % longer)
    // straighter than every run (or less): the waves' amplitude and the skew do not come out of these keys
    char b[200];
    std::snprintf(b, sizeof b, "the trace is %s than every run (chord / length %.4f; the runs' %.4f-%.4f)",
                  st > sHi ? "straighter" : "less straight", st, sLo, sHi);
    what = b;
  } else {
    // the output the answer's run misses most, in units of the trace's uncertainty
    int worst = -1;
    double z = 0;
    for (int c = 0; c < trace.trace.size(); ++c) {
      const double r = std::abs(answer.sim(c) - trace.trace(c)) / trace.sigma(c);
      if (worst < 0 || r > z) {
        worst = c;
        z = r;
      }
    }
    if (worst >= 0) {
      char b[400];
      // beside it, how far runs near the answer scatter there: a model whose runs scatter by more than the
      // trace's uncertainty cannot reproduce it to that uncertainty, whatever its keys
      const double scatter = worst < modelSigma.size() ? modelSigma(worst) : std::numeric_limits<double>::quiet_NaN();
      std::snprintf(b, sizeof b, "the answer's run misses %s by %.3g sigma (trace %.4g, run %.4g; the runs near the answer scatter by %.2g there)",
                    trace.names[static_cast<std::size_t>(worst)].c_str(), z, trace.trace(worst), answer.sim(worst), scatter);
      what = b;
      const double miss = std::abs(answer.sim(worst) - trace.trace(worst));
      if (std::isfinite(scatter) && scatter > kScatterMiss * trace.sigma(worst) && miss <= kScatterMiss * scatter) {
        // a miss the runs' own scatter explains, itself far above the trace's uncertainty: the runs' shape
        // moves with the free keys more finely than any run the fit makes can follow, and nothing points
        // at a fixed key
        std::snprintf(b, sizeof b,
                      ", a miss within %.0f times that scatter, which is %.3g times the trace's uncertainty: near the answer the "
                      "root's shape changes with the free keys more finely than the fit resolves, so no run reproduces the trace "
                      "to its uncertainty",
                      kScatterMiss, scatter / trace.sigma(worst));
        return "the model with these free keys and this scene does not reproduce the trace: " + what + b;
      }
      // a wavelength: the tip speed sets how far the root grows per swing
      if (trace.names[static_cast<std::size_t>(worst)].find("wavelength") != std::string::npos) suggest = "growth.rate_per_h";
    }
  }
  std::string check;
  for (const char* key : {suggest, "plane.alpha_deg", "growth.rate_per_h"}) {
    const FixedKey* f = findFixed(fixed, key);
    if (!f) continue;
    check = "; check " + f->key + " (" + f->value + ", " + (f->source == "scene" ? "from the scene" : "the default") + ")" +
            (f->key == "plane.alpha_deg" ? " against the plate's tilt, or free it" : " against the trace's growth");
    break;
  }
  return "the model with these free keys and this scene does not reproduce the trace: " + what + check;
}

Eigen::MatrixXd reportedCovariance(const Eigen::MatrixXd& surfaceCov, const std::vector<double>& sigma) {
  const Eigen::Index n = static_cast<Eigen::Index>(sigma.size());
  if (n == 0 || surfaceCov.rows() != n || surfaceCov.cols() != n) return {};
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = sigma[static_cast<std::size_t>(i)], v = surfaceCov(i, i);
    if (!(std::isfinite(s) && s > 0 && std::isfinite(v) && v > 0)) return {};
  }
  // each pair once, mirrored: exactly symmetric
  Eigen::MatrixXd c(n, n);
  for (Eigen::Index r = 0; r < n; ++r)
    for (Eigen::Index k = r; k < n; ++k)
      c(r, k) = c(k, r) = surfaceCov(r, k) / std::sqrt(surfaceCov(r, r) * surfaceCov(k, k)) *
                          (sigma[static_cast<std::size_t>(r)] * sigma[static_cast<std::size_t>(k)]);
  return c;
}

void chooseAnswer(FitReport& rep, const TraceTarget& target, const FitComponents& trace, const Eigen::VectorXd& modelSigma,
                  const Model& base, const std::vector<std::string>& fileKeys,
                  const std::function<double(const FitEvaluation&)>& answerChi2) {
  std::vector<double> objectives;
  for (const FitEvaluation& e : rep.evaluations)
    objectives.push_back(e.error.empty() ? e.objective : std::numeric_limits<double>::quiet_NaN());
  rep.best = answerIndex(objectives, rep.surfaceRun);
  const FitEvaluation& b = rep.evaluations[static_cast<std::size_t>(rep.best)];
  rep.goodness = goodnessOf(answerChi2(b), static_cast<int>(trace.trace.size()), static_cast<int>(rep.keys.size()));
  rep.goodness.against = trace.covName;
  rep.fixed = sceneFixedKeys(base, rep.keys, fileKeys);
  rep.misfit = rep.goodness.verdict == "poor" ? misfitSentence(target, rep.evaluations, b, trace, modelSigma, rep.fixed) : std::string();
}

}  // namespace rootsim::app
