// What embedding rootsim (the Python package, python/) relies on in the library: run files read back
// as the doubles written (readCsvColumns), a run stopped on purpose stays DIR.partial (RunInterrupted),
// and a sweep reports its points as they finish and stops when cancelled (SweepOptions hooks)
#include <doctest/doctest.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/sweep.hpp"
#include "rootsim/units.hpp"
#include "test_files.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("hooks", name); }
const std::string kScene = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml";
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace

TEST_CASE("timeseries.csv reads back as the very doubles of the run's step records") {
  const fs::path d = scratch("csv");
  const Scene sc = loadScene(kScene, {"growth.steps=60"});
  std::vector<StepRecord> seen;
  runSceneToDir(sc, (d / "run").string(), {}, [&](const StepRecord& r, int) { seen.push_back(r); });
  const CsvColumns t = readCsvColumns(d / "run" / "timeseries.csv");
  REQUIRE(t.names.size() > 20);
  CHECK(t.names[0] == "step");
  CHECK(t.names[2] == "length_mm");
  REQUIRE(t.values[0].size() == 7);  // step 0 and every 10th
  for (size_t row = 1; row < t.values[0].size(); ++row) {
    const StepRecord& r = seen[static_cast<size_t>(t.values[0][row]) - 1];
    CHECK(sameBits(t.values[2][row], r.length / units::mm));
    CHECK(sameBits(t.values[4][row], r.thetaTip / units::deg));
  }
  // a malformed cell is named with file and line
  { std::ofstream(d / "bad.csv") << "a,b\n1,2\n3,x4\n"; }
  CHECK_THROWS_WITH_AS(readCsvColumns(d / "bad.csv"), doctest::Contains("bad.csv:3: b: expected a number (got \"x4\")"),
                       SceneError);
  fs::remove_all(d);
}

TEST_CASE("a progress hook throwing RunInterrupted stops the run and leaves DIR.partial, not DIR.incomplete") {
  const fs::path d = scratch("interrupt");
  const Scene sc = loadScene(kScene, {"growth.steps=50"});
  int last = 0;
  CHECK_THROWS_AS(runSceneToDir(sc, (d / "run").string(), {},
                                [&](const StepRecord& r, int) {
                                  last = r.step;
                                  if (r.step == 7) throw RunInterrupted("stop");
                                }),
                  RunInterrupted);
  CHECK(last == 7);
  CHECK(fs::is_regular_file(d / "run.partial" / kRunMarker));
  CHECK(!fs::exists(d / "run"));
  CHECK(!fs::exists(d / "run.incomplete"));
  fs::remove_all(d);
}

TEST_CASE("a sweep reports every point through onPoint, skipped ones too, and stops when cancelled") {
  const fs::path d = scratch("sweep");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << kScene
                                << "\"\n[grid]\n\"plane.alpha_deg\" = [20, 40, 60]\n[set]\n\"growth.steps\" = 20\n";
  }
  const SweepPlan plan = loadSweep((d / "s.toml").string());
  std::mutex mu;
  std::vector<SweepPointDone> done;
  SweepOptions o;
  o.out = (d / "out").string();
  o.jobs = 2;
  o.onPoint = [&](const SweepPointDone& p) {
    std::lock_guard<std::mutex> lock(mu);
    done.push_back(p);
  };
  SweepResult r = runSweep(plan, o, nullptr);
  CHECK(r.ran == 3);
  CHECK(!r.interrupted);
  REQUIRE(done.size() == 3);
  std::set<int> indices;
  for (const auto& p : done) {
    indices.insert(p.point->index);
    CHECK(p.error.empty());
    CHECK(!p.skipped);
    CHECK(fs::is_regular_file(fs::path(p.dir) / "result.csv"));
  }
  CHECK(indices == std::set<int>{0, 1, 2});
  // again: every point complete, reported as skipped
  done.clear();
  r = runSweep(plan, o, nullptr);
  CHECK(r.skipped == 3);
  CHECK(done.size() == 3);
  for (const auto& p : done) CHECK(p.skipped);
  // cancelled before it starts: nothing runs, nothing is reported, the result says so
  done.clear();
  o.out = (d / "cancelled").string();
  o.cancelled = [] { return true; };
  r = runSweep(plan, o, nullptr);
  CHECK(r.interrupted);
  CHECK(r.ran == 0);
  CHECK(done.empty());
  // cancelled during a point: it stops between growth steps and stays DIR.partial
  done.clear();
  o.out = (d / "midway").string();
  o.jobs = 1;
  std::atomic<int> polls{0};
  o.cancelled = [&] { return ++polls > 5; };  // the check before the point, then four growth steps
  r = runSweep(plan, o, nullptr);
  CHECK(r.interrupted);
  CHECK(r.ran == 0);
  CHECK(r.failed == 0);
  CHECK(done.empty());
  CHECK(fs::is_directory(fs::path(o.out) / (plan.points[0].dirName + ".partial")));
  CHECK(!fs::exists(fs::path(o.out) / (plan.points[0].dirName + ".incomplete")));
  fs::remove_all(d);
}
