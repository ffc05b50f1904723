// The shared runner of the figure panels: cases run through the sweep runner (dearest first), and what
// their runs wrote read back.
#include "figure_runs.hpp"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/sweep.hpp"
#include "rootsim/theory.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

namespace {
// a guess at a case's cost, to start the dearest runs first (longest-processing-time order: the last
// runs of a batch then are short, and neither job waits long for the other at its end). Measured on the
// full figure set: a root that coils (alpha past Eq. 13's alpha_w->c, here with 10 degrees to spare)
// costs 3-10 s against 0.2-1 s for one that waves, as its self-contacts bring the sparse solver in.
double costGuess(const Ctx& c, const Case& k) {
  const Model m = modelOf(c, k);
  const bool coils = k.alpha * units::deg >= theoryFor(m).alphaWaveToCoil - 10.0 * units::deg;
  return k.lengthMm * (coils ? 10.0 : 1.0) * (1.0 + k.alpha / 90.0);
}
}  // namespace

void runCases(const Ctx& c, const std::vector<Case>& given) {
  // the order runs start in; what they compute does not depend on it
  std::vector<std::pair<double, size_t>> order;
  for (size_t i = 0; i < given.size(); ++i) order.emplace_back(-costGuess(c, given[i]), i);
  std::stable_sort(order.begin(), order.end());
  std::vector<Case> cases;
  for (const auto& [cost, i] : order) cases.push_back(given[i]);
  SweepPlan plan;
  for (const auto& k : cases) {
    SweepPoint p;
    p.index = static_cast<int>(plan.points.size());
    p.dirName = dirOf(c, k);
    bool dup = false;
    for (const auto& q : plan.points) dup |= q.dirName == p.dirName;
    if (dup) continue;
    p.scene = sceneOf(modelOf(c, k), outputOf(c));
    p.grows = p.scene->model.growth.enabled;
    plan.points.push_back(std::move(p));
  }
  SweepOptions so;
  so.jobs = c.opt.jobs;
  so.out = c.runs().string();
  so.force = c.opt.force;
  const SweepResult r = runSweep(plan, so, c.opt.quiet ? std::function<void(const std::string&)>() : c.log);
  if (r.failed > 0) throw RunError(std::to_string(r.failed) + " figure run(s) failed; see " + c.runs().string());
}

RunResult result(const Ctx& c, const Case& k) { return readResult(c.runs() / dirOf(c, k) / "result.csv"); }
double val(const RunResult& r, const std::string& k) { return r.number(k); }
CsvColumns series(const Ctx& c, const Case& k) { return readCsvColumns(c.runs() / dirOf(c, k) / "timeseries.csv"); }

const std::vector<double>& column(const CsvColumns& t, const std::string& name) {
  for (std::size_t i = 0; i < t.names.size(); ++i)
    if (t.names[i] == name) return t.values[i];
  throw RunError("timeseries.csv has no column " + name);
}

std::vector<Snapshot> trajectory(const Ctx& c, const Case& k) {
  return readTrajectory(trajectoryPath(c.runs() / dirOf(c, k)));
}

}  // namespace rootsim::fig
