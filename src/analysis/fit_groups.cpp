// `rootsim fit PLATE.rsml --groups SHEET.csv`: the free keys fitted per group of a traced plate's
// seedlings, and every key's contrast between every two groups (docs/experiments.md, "A plate by group").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "rootsim/analyze_traces.hpp"
#include "rootsim/compare_panel.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/run_snapshots.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/json.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/units.hpp"
#include "rootsim/write_rule.hpp"
#include "fit_parts.hpp"
#include "analysis_numbers.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

// the covariance of a group's mean of values measured per seedling (v: seedlings x outputs, an output's
// entries read on the seedlings that measure it): S / n from their sample covariance S about their mean,
// each variance at least g.floor (the mean of the seedlings' own tracing variances / n: a few seedlings
// that happen to agree do not claim more than their traces can). Two outputs measured on different
// seedlings, or on fewer seedlings than it takes to estimate their covariance (n - 1 below the outputs
// measured on them), have none between them. scatter: S itself
Eigen::MatrixXd groupMeanCovariance(const GroupSide& g, const Eigen::MatrixXd& v, Eigen::MatrixXd* scatter) {
  const int m = static_cast<int>(g.users.size());
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < v.rows(); ++i)
      if (g.users[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)]) mean(j) += v(i, j) / g.userCount(static_cast<std::size_t>(j));
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(m, m), cov = Eigen::MatrixXd::Zero(m, m);
  for (int j = 0; j < m; ++j)
    for (int k = 0; k < m; ++k) {
      const auto& uj = g.users[static_cast<std::size_t>(j)];
      if (uj != g.users[static_cast<std::size_t>(k)]) continue;
      const double nj = g.userCount(static_cast<std::size_t>(j));
      const auto block = std::count(g.users.begin(), g.users.end(), uj);
      if (j != k && nj - 1 < static_cast<double>(block)) continue;
      double sjk = 0;
      for (int i = 0; i < v.rows(); ++i)
        if (uj[static_cast<std::size_t>(i)]) sjk += (v(i, j) - mean(j)) * (v(i, k) - mean(k)) / (nj - 1);
      s(j, k) = sjk;
      cov(j, k) = j == k ? std::max(sjk / nj, g.floor(j)) : sjk / nj;
    }
  if (scatter) *scatter = s;
  return cov;
}

// the group's outputs of a run: the mean over seedlings of each one's run measured as that seedling is,
// and the covariance of the group's mean about it from each seedling's residual (its trace's observables
// less those of its own run): the part of the seedlings' spread the runs reproduce (each sown at its own
// angle) is not counted again as noise
void seedlingOutputs(const GroupSide& g, const std::vector<SimRoot>& sims, Eigen::MatrixXd& trace, Eigen::MatrixXd& sim) {
  const int m = static_cast<int>(g.trace.names.size()), n = static_cast<int>(g.seedlings.size());
  trace = sim = Eigen::MatrixXd::Zero(n, m);
  for (std::size_t i = 0; i < g.seedlings.size(); ++i) {
    const TraceTarget& t = g.seedlings[i];
    const std::vector<Observation> obs = observeBoth(t.traits, sims[i].traits, t.sigmaMm);
    for (std::size_t j = 0; j < g.trace.names.size(); ++j) {
      if (!g.users[j][i]) continue;
      for (const Observation& o : obs)
        if (o.name == g.trace.names[j]) {
          // a run without the waves the trace has: its missing value counts as 0 (observableComponents)
          sim(static_cast<int>(i), static_cast<int>(j)) = std::isfinite(o.sim) ? o.sim : 0.0;
          trace(static_cast<int>(i), static_cast<int>(j)) = o.trace;
        }
    }
  }
}

Eigen::MatrixXd groupSurfaceCovariance(const GroupSide& g, const Eigen::MatrixXd& trace, const std::vector<Eigen::VectorXd>& us,
                                       const std::vector<Eigen::MatrixXd>& sims, const Eigen::VectorXd& u, double scale) {
  // one surface per seedling's output: fitResponseSurface fits every output on its own, so the seedlings'
  // outputs side by side (column-major) are that many surfaces over the same runs
  std::vector<Eigen::VectorXd> ys;
  for (const Eigen::MatrixXd& s : sims) ys.push_back(Eigen::Map<const Eigen::VectorXd>(s.data(), s.size()));
  const ResponseSurface rs = fitResponseSurface(us, ys, u, scale);
  const Eigen::VectorXd at = rs.value(u);
  const Eigen::MatrixXd smooth = Eigen::Map<const Eigen::MatrixXd>(at.data(), trace.rows(), trace.cols());
  Eigen::MatrixXd residual = trace - smooth;
  for (int j = 0; j < trace.cols(); ++j)
    for (int i = 0; i < trace.rows(); ++i)
      if (!g.users[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)]) residual(i, j) = 0.0;
  return groupMeanCovariance(g, residual, nullptr);
}

FitComponents groupComponents(const GroupSide& g, const std::vector<SimRoot>& sims) {
  FitComponents c = g.trace;
  const int m = static_cast<int>(c.names.size());
  Eigen::MatrixXd trace, sim;
  seedlingOutputs(g, sims, trace, sim);
  c.sim = Eigen::VectorXd::Zero(m);
  for (std::size_t j = 0; j < c.names.size(); ++j)
    for (std::size_t i = 0; i < g.seedlings.size(); ++i)
      if (g.users[j][i]) c.sim(static_cast<int>(j)) += sim(static_cast<int>(i), static_cast<int>(j)) / g.userCount(j);
  c.cov = groupMeanCovariance(g, trace - sim, nullptr);
  c.sigma = c.cov.diagonal().cwiseSqrt();
  c.covName = kGroupResidualCovName;
  return c;
}

// a traced root's start angle [deg]: the direction from its base to its point at arc length overMm (the
// scene's initial root, straight as sown), from downhill, positive towards +lateral as
// root.initial_angle_deg; its last point on a trace shorter than that
double sowingAngleDeg(const Eigen::Matrix3Xd& plateMm, double overMm) {
  double s = 0;
  int at = static_cast<int>(plateMm.cols()) - 1;
  for (int i = 1; i < plateMm.cols(); ++i) {
    s += (plateMm.col(i).head<2>() - plateMm.col(i - 1).head<2>()).norm();
    if (s >= overMm) {
      at = i;
      break;
    }
  }
  const Eigen::Vector2d c = plateMm.col(at).head<2>() - plateMm.col(0).head<2>();
  return std::atan2(c.x(), c.y()) / units::deg;
}

namespace {

// the group's outputs: each observable two or more of its seedlings' traces use (a trace without a wave
// train has no wavelength), the mean over those seedlings, the floor of the mean's variances (their
// tracing variances' mean / n), and the covariance the fit starts from: the mean's from the seedlings'
// observables themselves (groupMeanCovariance), replaced by their residuals' once runs are made
void groupTraceSide(GroupSide& g, const std::string& sheet) {
  const std::size_t n = g.seedlings.size();
  std::vector<std::vector<Observation>> own;
  for (const TraceTarget& t : g.seedlings) own.push_back(observeBoth(t.traits, t.traits, t.sigmaMm));
  const auto find = [&](std::size_t i, const std::string& name) -> const Observation* {
    for (const Observation& o : own[i])
      if (o.name == name && o.used) return &o;
    return nullptr;
  };
  g.trace = FitComponents{};
  g.users.clear();
  for (const Observation& o : own.front()) {
    std::vector<bool> users(n, false);
    int count = 0;
    for (std::size_t i = 0; i < n; ++i) count += (users[i] = find(i, o.name) != nullptr) ? 1 : 0;
    if (count >= 2) {
      g.trace.names.push_back(o.name);
      g.users.push_back(users);
    }
  }
  if (g.trace.names.empty())
    throw SceneError(sheet + ": group " + g.name + ": no observable is measured on two of its seedlings' traces (skew, wavelength, amplitude)");
  const int m = static_cast<int>(g.trace.names.size());
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(m);
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(static_cast<int>(n), m);
  g.floor = Eigen::VectorXd::Zero(m);
  for (int j = 0; j < m; ++j) {
    const double nj = g.userCount(static_cast<std::size_t>(j));
    for (std::size_t i = 0; i < n; ++i)
      if (const Observation* o = g.users[static_cast<std::size_t>(j)][i] ? find(i, g.trace.names[static_cast<std::size_t>(j)]) : nullptr) {
        v(static_cast<int>(i), j) = o->trace;
        mean(j) += o->trace / nj;
        g.floor(j) += o->sigma * o->sigma / nj / nj;
      }
  }
  g.trace.trace = mean;
  g.trace.cov = groupMeanCovariance(g, v, &g.scatter);
  g.trace.covName = "the group mean's covariance from its seedlings' observables (their scatter / n, each variance at least their tracing noise / n)";
  g.trace.sigma = g.trace.cov.diagonal().cwiseSqrt();
}

bool isPlateKey(const std::string& key) {
  const std::string section = key.substr(0, key.find('.'));
  for (const char* s : {"plate", "population", "seedling", "laterals"})
    if (section == s) return true;
  const std::vector<std::string> seedlingKeys = plateKeys("seedling");  // a seedling's own, by its bare name
  return std::find(seedlingKeys.begin(), seedlingKeys.end(), key) != seedlingKeys.end();
}

bool goodGroupName(const std::string& s) {
  if (s.empty() || s == "." || s == ".." || s.size() > 64) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.'; });
}

// "+0.2 +- 0.03, p < 0.001" (the values to the sigma's second significant digit)
std::string contrastText(const GroupContrast& c) {
  if (c.flat) return "flat (" + c.why + ")";
  char b[160];
  const int digits = c.sigma > 0 ? std::max(0, 1 - static_cast<int>(std::floor(std::log10(c.sigma)))) : 3;
  std::snprintf(b, sizeof b, "%+.*f +- %.*f, ", digits, c.difference, digits, c.sigma);
  std::string t = b;
  if (c.pValue < 0.001)
    t += "p < 0.001";
  else {
    std::snprintf(b, sizeof b, "p = %.2g", c.pValue);
    t += b;
  }
  return t;
}

}  // namespace

std::vector<GroupContrast> groupContrasts(const std::vector<FreeKey>& keys, const std::vector<GroupFit>& groups) {
  std::vector<GroupContrast> out;
  for (std::size_t a = 0; a < groups.size(); ++a)
    for (std::size_t b = a + 1; b < groups.size(); ++b)
      for (std::size_t i = 0; i < keys.size(); ++i) {
        GroupContrast c;
        c.key = keys[i].key;
        c.a = groups[a].name;
        c.b = groups[b].name;
        const double sa = groups[a].sigma[i], sb = groups[b].sigma[i];
        c.difference = groups[a].value[i] - groups[b].value[i];
        if (!std::isfinite(sa) || !std::isfinite(sb)) {
          // a key a group's seedlings do not determine (or whose best value lies at a bound of the box)
          c.flat = true;
          c.difference = c.sigma = c.pValue = kNaN;
          c.why = "not determined in " + (!std::isfinite(sa) ? c.a : c.b) + ": see its notes";
          out.push_back(c);
          continue;
        }
        c.sigma = std::hypot(sa, sb);
        // Wald: the two groups' estimates are independent (their own seedlings, their own runs)
        c.pValue = c.sigma > 0 ? std::erfc(std::abs(c.difference) / c.sigma / std::sqrt(2.0)) : (c.difference == 0 ? 1.0 : 0.0);
        out.push_back(c);
      }
  return out;
}

std::string contrastsTable(const std::vector<GroupContrast>& contrasts) {
  std::string out, pair;
  for (const GroupContrast& c : contrasts) {
    const std::string p = c.a + " - " + c.b;
    if (p != pair) {
      out += (pair.empty() ? "" : "\n") + p + ": ";
      pair = p;
    } else {
      out += "; ";
    }
    out += c.key + " " + contrastText(c);
  }
  return out.empty() ? out : out + "\n";
}

GroupFitReport runGroupFit(const FitOptions& o, const std::function<void(const std::string&)>& log) {
  // bad input first, before anything is written
  if (o.scene.empty()) throw SceneError("--scene: give the base scene (a TOML file)");
  if (o.out.empty()) throw SceneError("--out: give the fit's folder");
  if (!o.objective.empty() && o.objective != "observables")
    throw SceneError("--objective " + o.objective +
                     ": a fit by group (--groups) compares each group's mean observables; use --objective observables or leave it out");
  if (!o.trace.root.empty()) throw SceneError("--root " + o.trace.root + ": a fit by group takes each plant's primary root; leave --root out");
  for (const std::string& item : splitCommas(o.free)) {
    const std::string key = item.substr(0, item.find('='));
    if (isPlateKey(key))
      throw SceneError("--free " + item + ": " + key + " is a plate's key ([plate], [population], [[seedling]], [laterals]); " +
                       "a fit by group runs the root of the base scene per group: free a key of the root (tropism.*, rod.*, growth.rate_per_h, ...)");
    if (key == kSowingKey)
      throw SceneError("--free " + item + ": " + key + " is each seedling's own: a fit by group sows each seedling's runs at its trace's start angle");
    if (key.rfind("plane.", 0) == 0)
      throw SceneError("--free " + item + ": " + key + " is the plate's tilt, the same for every group: set it in the scene");
  }
  const Scene base = loadScene(o.scene);
  if (base.isPlate())
    throw SceneError("--scene " + o.scene + ": a plate's scene; fit --groups takes the scene of one root, run once per group");
  const std::vector<FreeKey> keys = parseFreeKeys(o.free, o.scene);
  if (o.jobs < 1 || o.jobs > 256) throw SceneError("-j " + std::to_string(o.jobs) + ": must be in [1, 256]");
  {
    FitOptions oo = o;
    oo.objective = "observables";
    fitSize(oo, static_cast<int>(keys.size()));  // the budget, checked before anything is written
  }
  std::vector<std::string> files = {o.trace.trace};
  files.insert(files.end(), o.more.begin(), o.more.end());
  AnalyzeOptions a;
  a.pxPerMm = o.trace.pxPerMm;
  a.downhill = o.trace.downhill;
  a.excludeTipMm = base.model.growth.zoneLength / units::mm;
  a.radiusMm = base.model.rod.radius / units::mm;
  a.flagPrefix = o.trace.flagPrefix;
  checkTraceFlags(a);
  std::vector<TracedPlant> plants;
  std::vector<std::string> rootKeys;
  for (const std::string& f : files) {
    const TraceFile tf = readTraceFile(f, a);
    for (const TracedPlant& p : tracedPlants(tf, f)) {
      plants.push_back(p);
      rootKeys.push_back(tf.roots[static_cast<std::size_t>(p.root)].key);
    }
  }
  const std::vector<SheetRow> rows = readSampleSheet(o.groups, "group", plants, kSheetSowingColumn);
  {
    std::vector<bool> named(plants.size(), false);
    for (const SheetRow& r : rows) named[static_cast<std::size_t>(r.plant)] = true;
    for (std::size_t p = 0; p < plants.size(); ++p)
      if (!named[p])
        throw SceneError(o.groups + ": plant " + plants[p].id + (plants[p].label.empty() ? "" : " (" + plants[p].label + ")") + " of " +
                         plants[p].file + " has no line; add \"" + plants[p].id + ",GROUP\" for it (every traced plant belongs to a group)");
  }
  // the groups in the order the sheet first names them
  std::vector<GroupSide> groups;
  std::map<std::string, int> firstLine;
  for (const SheetRow& r : rows) {
    if (!goodGroupName(r.value))
      throw SceneError(o.groups + ":" + std::to_string(r.line) + ": group " + r.value +
                       ": letters, digits, '-', '_' and '.' only (it names the group's folder)");
    auto it = std::find_if(groups.begin(), groups.end(), [&](const GroupSide& g) { return g.name == r.value; });
    if (it == groups.end()) {
      groups.push_back(GroupSide{});
      groups.back().name = r.value;
      firstLine[r.value] = r.line;
      it = groups.end() - 1;
    }
    const TracedPlant& p = plants[static_cast<std::size_t>(r.plant)];
    // its label where no other plant has it (the plants of a scan may all be labelled alike), else its id
    const bool unique = !p.label.empty() && std::count_if(plants.begin(), plants.end(), [&](const TracedPlant& q) { return q.label == p.label; }) == 1;
    it->plants.push_back(unique ? p.label : p.id);
    TraceFlags f = o.trace;
    f.trace = p.file;
    f.root = rootKeys[static_cast<std::size_t>(r.plant)];
    it->seedlings.push_back(loadTarget(f, base.model));
    // its sowing angle: the sheet's, else its trace's start
    double deg = sowingAngleDeg(it->seedlings.back().plateMm, base.model.initial.length / units::mm);
    if (!r.optional.empty()) {
      char* end = nullptr;
      deg = std::strtod(r.optional.c_str(), &end);
      if (end == r.optional.c_str() || *end != '\0' || !std::isfinite(deg) || std::abs(deg) > 90)
        throw SceneError(o.groups + ":" + std::to_string(r.line) + ": " + kSheetSowingColumn + " " + r.optional +
                         ": expected the plant's sowing angle in degrees from downhill, in [-90, 90] (or an empty cell: its trace's start)");
    }
    // to a tenth of a degree (a run per distinct angle)
    deg = std::round(deg * 10.0) / 10.0;
    it->sowingDeg.push_back(deg == 0.0 ? 0.0 : deg);
  }
  for (GroupSide& g : groups) {
    if (g.seedlings.size() < 2)
      throw SceneError(o.groups + ":" + std::to_string(firstLine[g.name]) + ": group " + g.name + " has one seedling (" + g.plants.front() +
                       "); a group's fit needs at least two: add the group's other plants or put this one in another group");
    groupTraceSide(g, o.groups);
    // each seedling sown at its own angle: a run per distinct angle
    for (const double deg : g.sowingDeg) {
      const std::string text = numberText(deg);
      auto it = std::find(g.angles.begin(), g.angles.end(), text);
      if (it == g.angles.end()) it = g.angles.insert(g.angles.end(), text);
      g.angleOf.push_back(static_cast<int>(it - g.angles.begin()));
    }
    g.target = g.seedlings.front();
    double longest = 0;
    for (const TraceTarget& t : g.seedlings) longest = std::max(longest, t.rootLengthMm);
    // the runs grow to the longest seedling's length; each seedling is compared at its own (comparedSnapshot)
    g.target.rootLengthMm = longest;
    g.inputs = files;
    g.inputs.push_back(o.groups);
    g.settings = "--groups " + o.groups + " group " + g.name + " plants";
    for (const std::string& p : g.plants) g.settings += " " + p;
  }

  const fs::path out = checkOutputName(o.out, "--out");
  const OutputLock lock = lockOutput(out, "--out");
  WriteRule rule;
  rule.force = o.force;
  rule.inputs.push_back(WriteInput{o.scene, {}, true});
  for (const std::string& f : groups.front().inputs) rule.inputs.push_back(WriteInput{f, {}, true});
  rule.inputs.push_back(workingFolder());
  claimFolder(out, fitFolder(), rule, "--out", false);
  createOwnFolder(out, fitFolder());

  GroupFitReport rep;
  rep.keys = keys;
  rep.out = out.string();
  for (const GroupSide& g : groups) {
    FitOptions go = o;
    go.objective = "observables";
    go.out = (out / "groups" / g.name).string();
    if (!o.quiet) {
      std::string line = "fit: group " + g.name + " (" + std::to_string(g.seedlings.size()) + " seedlings):";
      for (int j = 0; j < g.trace.trace.size(); ++j)
        line += " " + g.trace.names[static_cast<std::size_t>(j)] + " " + numberText(std::round(g.trace.trace(j) * 1e4) / 1e4) + " +- " +
                numberText(std::round(g.trace.sigma(j) * 1e4) / 1e4) + " (" +
                std::to_string(static_cast<int>(g.userCount(static_cast<std::size_t>(j)))) + " seedlings)";
      log(line);
    }
    GroupFit gf;
    gf.name = g.name;
    gf.plants = g.plants;
    gf.sowingDeg = g.sowingDeg;
    gf.report = runFitOn(go, &g, [&](const std::string& l) { log("[" + g.name + "] " + l); });
    if (o.designOnly) {
      rep.designs.push_back(gf.report.design);
      continue;
    }
    gf.outputs = gf.report.trace;  // the mean, and its covariance at the answer
    gf.scatter = g.scatter;
    const FitEvaluation& b = gf.report.evaluations[static_cast<std::size_t>(gf.report.best)];
    gf.value = b.x;
    gf.sigma = gf.report.sigma;
    gf.answerSim = b.sim;
    // each seedling's own answer among the group's runs: a single fit of it would cost a fit per seedling;
    // its best run of the group's shows where its own observables point, within the box the group searched
    for (std::size_t i = 0; i < g.seedlings.size(); ++i) {
      int at = -1;
      for (std::size_t e = 0; e < gf.report.evaluations.size(); ++e) {
        const FitEvaluation& ev = gf.report.evaluations[e];
        if (ev.error.empty() && i < ev.seedlingChi2.size() && std::isfinite(ev.seedlingChi2[i]) &&
            (at < 0 || ev.seedlingChi2[i] < gf.report.evaluations[static_cast<std::size_t>(at)].seedlingChi2[i]))
          at = static_cast<int>(e);
      }
      gf.seedlingValue.push_back(at < 0 ? std::vector<double>(keys.size(), kNaN) : gf.report.evaluations[static_cast<std::size_t>(at)].x);
      gf.seedlingChi2.push_back(at < 0 ? kNaN : gf.report.evaluations[static_cast<std::size_t>(at)].seedlingChi2[i]);
    }
    // the group's compare picture: every traced seedling over the answer's run
    {
      const Scene best = loadScene((fs::path(go.out) / "best.toml").string());
      std::vector<Eigen::Matrix3Xd> traces;
      for (const TraceTarget& t : g.seedlings) traces.push_back(t.plateMm);
      std::string title = "group " + literalLabel(g.name) + " (" + std::to_string(g.seedlings.size()) + " seedlings):";
      for (std::size_t i = 0; i < keys.size(); ++i) {
        title += (i ? ", " : " ") + literalLabel(keys[i].key) + " = " + numberText(std::round(gf.value[i] * 1e4) / 1e4);
        if (std::isfinite(gf.sigma[i])) title += " ± " + numberText(std::round(gf.sigma[i] * 1e4) / 1e4);
      }
      // each seedling's own run of the answer (its sowing angle's), as long as its trace
      std::vector<Snapshot> sims;
      for (std::size_t i = 0; i < g.seedlings.size(); ++i) {
        const std::vector<Snapshot> snaps = loadSnapshots(b.dirs[static_cast<std::size_t>(g.angleOf[i])]);
        sims.push_back(comparedSnapshot(best.model, snaps, g.seedlings[i], false));
      }
      saveGroupComparePanel(best.model, sims, traces, g.plants, title,
                            "every seedling's trace over its own run of the answer (sown at its own angle); " +
                                goodnessText(gf.report.goodness, "χ²"),
                            (out / ("compare_" + g.name)).string());
    }
    rep.groups.push_back(gf);
  }
  if (o.designOnly) return rep;
  rep.contrasts = groupContrasts(keys, rep.groups);
  // each key per group: its value and sigma, and each seedling's own answer as a dot
  {
    std::vector<std::string> names;
    std::vector<double> lo, hi;
    std::vector<std::vector<GroupKeyValue>> perKey(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
      names.push_back(keys[i].key);
      lo.push_back(keys[i].lo);
      hi.push_back(keys[i].hi);
      for (const GroupFit& g : rep.groups) {
        GroupKeyValue v;
        v.group = g.name;
        v.value = g.value[i];
        v.sigma = g.sigma[i];
        for (const std::vector<double>& sv : g.seedlingValue) v.seedlings.push_back(sv[i]);
        perKey[i].push_back(v);
      }
    }
    saveGroupKeysPanel(names, lo, hi, perKey, "the free keys per group: the group's fit and each seedling's own",
                       "a seedling's best run of its group's", (out / "keys").string());
  }

  // fit.json: each group's answer and goodness, and the contrasts
  Json js;
  js.str("software", outputSignatureText()).str("sheet", o.groups).str("scene", o.scene).strings("traces", files);
  {
    std::vector<std::string> names;
    for (const FreeKey& k : keys) names.push_back(k.key);
    js.strings("keys", names);
  }
  js.str("method", "each group's mean observables against the group's values run once per seedling's sowing angle (the sheet's "
                   "angle_deg, else its trace's start angle), each seedling's run measured as that seedling is, at its own length; "
                   "covariance: the mean's at the answer, from the scatter of each seedling's residual against a quadratic surface "
                   "of its own runs' outputs over the trust region's runs, or against its own run before a trust region or "
                   "with too few runs in it for a surface (each group's goodness says which), its diagonal at least their "
                   "tracing noise, / n");
  Json gj;
  for (const GroupFit& g : rep.groups) {
    Json one;
    one.strings("plants", g.plants).integer("seedlings", static_cast<long long>(g.plants.size())).str("folder", "groups/" + g.name);
    Json best;
    for (std::size_t i = 0; i < keys.size(); ++i) best.object(keys[i].key, Json().num("value", g.value[i]).num("sigma", g.sigma[i]));
    one.object("best", best);
    one.object("goodness", goodnessJson(g.report.goodness));
    if (!g.report.misfit.empty()) one.str("misfit", g.report.misfit);
    std::vector<std::string> flat;
    std::vector<Json> obs;
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (!std::isfinite(g.sigma[i])) flat.push_back(keys[i].key);
    for (std::size_t j = 0; j < g.outputs.names.size(); ++j) {
      const int jj = static_cast<int>(j);
      obs.push_back(Json()
                        .str("name", g.outputs.names[j])
                        .num("mean", g.outputs.trace(jj))
                        .num("sigma_of_mean", g.outputs.sigma(jj))
                        .num("scatter_sd", std::sqrt(g.scatter(jj, jj)))
                        .num("answer", g.answerSim.size() > jj ? g.answerSim(jj) : kNaN));
    }
    std::vector<Json> own;
    for (std::size_t p = 0; p < g.plants.size(); ++p) {
      Json values;
      for (std::size_t i = 0; i < keys.size(); ++i) values.num(keys[i].key, g.seedlingValue[p][i]);
      own.push_back(Json().str("plant", g.plants[p]).num("sowing_angle_deg", g.sowingDeg[p]).object("values", values).num("chi2", g.seedlingChi2[p]));
    }
    one.strings("flat", flat).strings("notes", g.report.notes).array("observables", obs).array("seedlings_own", own);
    gj.object(g.name, one);
  }
  js.object("groups", gj);
  std::vector<Json> cj;
  for (const GroupContrast& c : rep.contrasts) {
    Json one;
    one.str("key", c.key).strings("groups", {c.a, c.b});
    if (c.flat)
      one.str("difference", "flat").str("why", c.why);
    else
      one.num("difference", c.difference).num("sigma", c.sigma).num("p_value", c.pValue);
    cj.push_back(one);
  }
  js.array("contrasts", cj);
  writeFileAtomic(out / "fit.json", js.dump(2) + "\n");
  recordWritten({out / "fit.json"});
  return rep;
}

int groupFitCommand(const FitOptions& o) {
  const GroupFitReport r = runGroupFit(o, [&](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
  if (o.designOnly) {
    std::printf("%s\n", designOnlyText(r.designs).c_str());
    return 0;
  }
  for (const GroupFit& g : r.groups) {
    std::printf("%s (%zu seedlings):", g.name.c_str(), g.plants.size());
    for (std::size_t i = 0; i < r.keys.size(); ++i) {
      if (std::isfinite(g.sigma[i]))
        std::printf(" %s = %.6g +- %.3g%s", r.keys[i].key.c_str(), g.value[i], g.sigma[i], i + 1 < r.keys.size() ? "," : "");
      else
        std::printf(" %s = %.6g (flat)%s", r.keys[i].key.c_str(), g.value[i], i + 1 < r.keys.size() ? "," : "");
    }
    std::printf("; goodness: %s\n", goodnessText(g.report.goodness).c_str());
    if (!g.report.misfit.empty()) std::printf("  poor fit: %s\n", g.report.misfit.c_str());
  }
  std::printf("%s", contrastsTable(r.contrasts).c_str());
  if (!o.quiet) std::fprintf(stderr, "wrote %s (fit.json, groups/NAME: each group's fit folder)\n", r.out.c_str());
  return 0;
}

}  // namespace rootsim::app
