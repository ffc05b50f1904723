// A run's outputs from start to end (src/io/run_outputs.cpp), driven directly: the growth steps and their
// checkpoint cadence, a run committed whole, a failure in a step named and marked with its streams closed
// whole, a stop on purpose left as a kill leaves it, a plate root's folder, and a resumed run continuing
// after its checkpoint with the wall time before it.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "run_outputs.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;
using detail::CheckpointSeen;
using detail::RunOutputs;
using detail::RunSteps;
using rootsim::test::slurp;

namespace {
constexpr int kSteps = 5;
Scene smallScene() {
  return loadScene(rootsim::test::kScene, {"growth.steps=" + std::to_string(kSteps), "output.every_steps=2",
                                           "output.vtk=false", "root.element_length_mm=0.1", "growth.step_h=0.1"});
}
const auto kNoCheckpoint = [](const fs::path&) -> CheckpointSeen {
  FAIL("a new run reads no checkpoint");
  return {};
};
// a new run of smallScene() in a fresh scratch folder: the folder, the scene, where the run goes, its
// outputs (constructed, so the run directory is claimed)
struct NewRun {
  fs::path d;
  Scene sc = smallScene();
  fs::path out;
  RunOutputs run;
  NewRun(const std::string& name, const std::string& what)
      : d(rootsim::test::scratchDir("run_outputs", name)), out(d / "out"),
        run(sc, out.string(), RunDirOptions{}, what, kNoCheckpoint) {}
};
// counts what the step loop calls
struct Calls {
  std::vector<int> grown, written, checkpointed, progressed;
  RunSteps steps(const std::function<void(int)>& write = {}) {
    return RunSteps{[this](int k) { grown.push_back(k); },
                    [this, write](int k) {
                      written.push_back(k);
                      if (write) write(k);
                    },
                    [this](int k) { checkpointed.push_back(k); },
                    [this](int k) { progressed.push_back(k); }};
  }
};
}  // namespace

TEST_CASE("run outputs: a new run steps through every growth step, checkpoints before the last, and commits whole") {
  NewRun fresh("whole", "the run of test");
  const fs::path& out = fresh.out;
  RunOutputs& run = fresh.run;
  CHECK_FALSE(run.resumed());
  CHECK(run.firstStep() == 1);
  CHECK(run.work() == fs::path(out.string() + ".partial"));
  Calls calls;
  const double wall = run.runMarkingFailure([&] {
    run.write("scene.toml", fresh.sc.resolvedToml);
    Simulation sim(fresh.sc.model);
    detail::RootOutputs& root = run.addRoot(run.work(), fresh.sc.model);
    root.add(sim);
    root.start(sim.last());
    AtomicFile& series = run.addStream("plate_timeseries.csv");
    // a checkpoint due after every step (0 s of wall time), but never after the last
    run.growthSteps(kSteps, 0.0, calls.steps([&](int k) {
      sim.growthStep();
      root.see(sim.last());
      root.add(sim);
      series.stream() << k << "\n";
      series.flush();
      writeFileAtomic(run.checkpointFile(), "checkpoint of step " + std::to_string(k));
    }));
    const double w = run.endSteps();
    CHECK_FALSE(fs::exists(run.checkpointFile()));
    root.finish(fresh.sc.model, sim, w);
    run.commit();
    return w;
  });
  CHECK(wall >= 0);
  CHECK(calls.grown == std::vector<int>{1, 2, 3, 4, 5});
  CHECK(calls.written == calls.grown);
  CHECK(calls.progressed == calls.grown);
  CHECK(calls.checkpointed == std::vector<int>{1, 2, 3, 4});
  CHECK_FALSE(fs::exists(out.string() + ".partial"));
  CHECK(whyNotWhole(out) == "");
  CHECK(slurp(out / "plate_timeseries.csv") == "1\n2\n3\n4\n5\n");
  CHECK_FALSE(fs::exists(out / "vtk"));  // the scene's output.vtk = false reaches the root's streams
  for (const char* f : {"scene.toml", "timeseries.csv", "trajectory.bin", "shape.csv", "summary.json", "result.csv"})
    CHECK_MESSAGE(fs::is_regular_file(out / f), f);
  CHECK_FALSE(fs::exists(out / kCheckpointFile));
  fs::remove_all(fresh.d);
}

TEST_CASE("run outputs: a plate root's folder that cannot be made in a step names the step, its streams kept whole, the run marked failed") {
  NewRun fresh("failed", "the plate run of test");
  const fs::path& out = fresh.out;
  RunOutputs& run = fresh.run;
  Calls calls;
  std::string error;
  try {
    run.runMarkingFailure([&] {
      const fs::path a = run.rootFolder("a", "# a's scene\n");
      CHECK(fs::is_regular_file(a / kRunMarker));
      CHECK(slurp(a / "scene.toml") == "# a's scene\n");
      Simulation sim(fresh.sc.model);
      detail::RootOutputs& root = run.addRoot(a, fresh.sc.model);
      root.add(sim);
      AtomicFile& series = run.addStream("plate_timeseries.csv");
      series.stream() << "0\n";
      series.flush();
      // a lateral emerging at step 3 where a file of the same name stands
      writeFileAtomic(run.work() / "roots" / "b", "in the way");
      run.growthSteps(kSteps, 1e9, calls.steps([&](int k) {
        if (k == 3) run.rootFolder("b", "# b's scene\n");
      }));
      return 0.0;
    });
    FAIL("the run went on");
  } catch (const RunError& e) {
    error = e.what();
  }
  CHECK(error.find((run.work() / "roots" / "b").string() + ": cannot create the root's folder") != std::string::npos);
  CHECK(error.find("(at growth step 3 of 5)") != std::string::npos);
  CHECK(calls.progressed == std::vector<int>{1, 2});
  CHECK(calls.checkpointed.empty());
  const fs::path inc = out.string() + ".incomplete";
  REQUIRE(fs::is_directory(inc));
  CHECK_FALSE(fs::exists(out.string() + ".partial"));
  CHECK(slurp(inc / "ERROR.txt") == error + "\n");
  // the streams were closed, not left as temporary files
  CHECK(slurp(inc / "plate_timeseries.csv") == "0\n");
  CHECK(fs::is_regular_file(inc / "roots" / "a" / "timeseries.csv"));
  CHECK_FALSE(fs::exists(inc / "roots" / "a" / "timeseries.csv.tmp"));
  fs::remove_all(fresh.d);
}

TEST_CASE("run outputs: a stop on purpose leaves DIR.partial as a kill does, not a failed run") {
  NewRun fresh("stop", "the run of test");
  const fs::path& out = fresh.out;
  RunOutputs& run = fresh.run;
  Calls calls;
  RunSteps f = calls.steps();
  f.progress = [&](int k) {
    calls.progressed.push_back(k);
    if (k == 3) throw RunInterrupted("stopped");
  };
  CHECK_THROWS_AS(run.runMarkingFailure([&] {
    run.write("scene.toml", fresh.sc.resolvedToml);
    run.growthSteps(kSteps, 1e9, f);
    return 0.0;
  }), RunInterrupted);
  CHECK(calls.progressed == std::vector<int>{1, 2, 3});
  const fs::path partial = out.string() + ".partial";
  CHECK(fs::is_regular_file(partial / kRunMarker));
  CHECK(fs::is_regular_file(partial / "scene.toml"));
  CHECK_FALSE(fs::exists(partial / "ERROR.txt"));
  CHECK_FALSE(fs::exists(out.string() + ".incomplete"));
  CHECK_FALSE(fs::exists(out));
  fs::remove_all(fresh.d);
}

TEST_CASE("run outputs: a resumed run continues after its checkpoint, its streams cut back, with the wall time before it") {
  const fs::path d = rootsim::test::scratchDir("run_outputs", "resume");
  const Scene sc = smallScene();
  const fs::path out = d / "out";
  const fs::path partial = out.string() + ".partial";
  {
    // what a kill leaves: the run's scene, a checkpoint after step 3, a stream with a row written after
    // it, and an atomic write it interrupted
    RunDir killed(out, RunDirOptions{});
    killed.write("scene.toml", sc.resolvedToml);
    killed.write(kCheckpointFile, "3");
    std::ofstream(partial / "plate_timeseries.csv.tmp") << "1\n2\n3\n4\n";
    std::ofstream(partial / "plate.csv.tmp") << "half";
  }
  RunDirOptions o;
  o.resume = true;
  std::vector<std::string> notes;
  o.note = [&](const std::string& s) { notes.push_back(s); };
  RunOutputs run(sc, out.string(), o, "the run of test", [&](const fs::path& file) {
    CHECK(file == partial / kCheckpointFile);
    std::ifstream in(file);
    int step = 0;
    in >> step;
    return CheckpointSeen{step, 100.0};
  });
  CHECK(run.resumed());
  CHECK(run.firstStep() == 4);
  CHECK(run.wall() >= 100.0);
  REQUIRE(notes.size() == 1);
  CHECK(notes[0] == "resuming " + out.string() + " from the checkpoint of growth step 3 of 5");
  Calls calls;
  run.runMarkingFailure([&] {
    AtomicFile& series = run.addStream("plate_timeseries.csv", 6);
    CHECK_FALSE(fs::exists(partial / "plate.csv.tmp"));
    run.growthSteps(kSteps, 1e9, calls.steps([&](int k) {
      series.stream() << k << "\n";
      series.flush();
    }));
    const double w = run.endSteps();
    CHECK(w >= 100.0);
    run.commit();
    return w;
  });
  CHECK(calls.grown == std::vector<int>{4, 5});
  CHECK(slurp(out / "plate_timeseries.csv") == "1\n2\n3\n4\n5\n");
  CHECK_FALSE(fs::exists(out / kCheckpointFile));
  fs::remove_all(d);
}
