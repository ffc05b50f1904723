#include "figure_runs.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/sweep.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

void runCases(const Ctx& c, const std::vector<Case>& cases) {
  std::error_code ec;
  fs::create_directories(c.runs(), ec);
  const fs::path base = c.runs() / "base.toml";
  if (!fs::exists(base)) writeFileAtomic(base, "# figure runs: defaults of MODEL.md section 2, overridden per run\n");
  SweepPlan plan;
  plan.scenePath = base.string();
  for (const auto& k : cases) {
    SweepPoint p;
    p.index = static_cast<int>(plan.points.size());
    p.overrides = setsOf(c, k);
    p.dirName = dirOf(c, k);
    bool dup = false;
    for (const auto& q : plan.points) dup |= q.dirName == p.dirName;
    if (!dup) plan.points.push_back(p);
  }
  SweepOptions so;
  so.jobs = c.opt.jobs;
  so.out = c.runs().string();
  const SweepResult r = runSweep(plan, so, c.opt.quiet ? std::function<void(const std::string&)>() : c.log);
  if (r.failed > 0) throw RunError(std::to_string(r.failed) + " figure run(s) failed; see " + c.runs().string());
}


std::vector<Row> readCsv(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw RunError("cannot read " + p.string());
  std::string line;
  std::getline(in, line);
  std::vector<std::string> head;
  {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) head.push_back(cell);
  }
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row r;
    std::stringstream ss(line);
    std::string cell;
    for (size_t i = 0; i < head.size() && std::getline(ss, cell, ','); ++i) r[head[i]] = cell;
    rows.push_back(r);
  }
  return rows;
}

double val(const Row& r, const std::string& k) {
  auto it = r.find(k);
  if (it == r.end() || it->second.empty()) return NAN;
  return std::stod(it->second);
}

RunResult result(const Ctx& c, const Case& k) { return readResult(c.runs() / dirOf(c, k) / "result.csv"); }
double val(const RunResult& r, const std::string& k) { return r.number(k); }
std::vector<Row> series(const Ctx& c, const Case& k) { return readCsv(c.runs() / dirOf(c, k) / "timeseries.csv"); }

std::vector<Snapshot> trajectory(const Ctx& c, const Case& k) {
  return readTrajectory(trajectoryPath(c.runs() / dirOf(c, k)));
}

}  // namespace rootsim::fig
