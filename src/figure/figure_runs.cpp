#include "figure_runs.hpp"

#include <filesystem>

#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/sweep.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

void runCases(const Ctx& c, const std::vector<Case>& cases) {
  SweepPlan plan;
  for (const auto& k : cases) {
    SweepPoint p;
    p.index = static_cast<int>(plan.points.size());
    p.dirName = dirOf(c, k);
    bool dup = false;
    for (const auto& q : plan.points) dup |= q.dirName == p.dirName;
    if (dup) continue;
    p.scene = sceneOf(modelOf(c, k));
    p.grows = p.scene->model.growth.enabled;
    plan.points.push_back(std::move(p));
  }
  SweepOptions so;
  so.jobs = c.opt.jobs;
  so.out = c.runs().string();
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
