// A run directory's snapshots as the commands that read a run see them (src/io/run_snapshots.cpp): one
// root's trajectory read back, their times, the snapshot at a time within the run and a time outside it
// refused naming --at-h and the range, a missing trajectory and a --root of a run of one root refused.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/run_snapshots.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/trajectory.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

TEST_CASE("run snapshots: one root's run reads back as its trajectory, with its times, and a --root is refused") {
  const fs::path d = rootsim::test::scratchDir("run_snapshots", "one");
  const Scene sc = loadScene(rootsim::test::kScene, {"growth.steps=30", "output.every_steps=10", "output.vtk=false"});
  runSceneToDir(sc, (d / "run").string(), {}, [](const StepRecord&, int) {});
  CHECK_FALSE(isPlateRun(d / "run"));
  const std::vector<Snapshot> snaps = loadSnapshots(d / "run");
  const std::vector<Snapshot> traj = readTrajectory(d / "run" / "trajectory.bin");
  REQUIRE(snaps.size() == 4);  // step 0 and every 10th
  REQUIRE(snaps.size() == traj.size());
  for (std::size_t k = 0; k < snaps.size(); ++k) {
    CHECK(snaps[k].step == traj[k].step);
    CHECK(snaps[k].x == traj[k].x);
    CHECK(snaps[k].rootStarts.empty());
  }
  const std::vector<double> t = snapshotTimes(snaps);
  REQUIRE(t.size() == 4);
  for (std::size_t k = 0; k < t.size(); ++k) CHECK(t[k] == snaps[k].timeH);
  CHECK(t.front() == 0.0);
  const std::string oneRoot =
      "--root r2: " + (d / "run").string() + " is a run of one root (--root picks a root of a plate's run)";
  CHECK_THROWS_WITH_AS(loadSnapshots(d / "run", "r2"), oneRoot.c_str(), SceneError);
  const std::string missing =
      (d / "nothing" / "trajectory.csv").string() + ": not found (a run directory written with output.trajectory = true)";
  CHECK_THROWS_WITH_AS(loadSnapshots(d / "nothing"), missing.c_str(), SceneError);
  fs::remove_all(d);
}

TEST_CASE("run snapshots: the snapshot at a time is the nearest, a time outside the snapshots is refused naming --at-h and the range") {
  const std::vector<double> t{0.0, 0.5, 1.0, 1.5};
  CHECK(snapshotNear(t, 0.0) == 0);
  CHECK(snapshotNear(t, 0.7) == 1);
  CHECK(snapshotNear(t, 0.8) == 2);
  CHECK(snapshotNear(t, 1.5) == 3);
  CHECK_THROWS_WITH_AS(snapshotNear(t, 2.0), "--at-h 2: outside the run's snapshots, 0 .. 1.5 h", SceneError);
  CHECK_THROWS_WITH_AS(snapshotNear(t, -0.25, "window's"), "--at-h -0.25: outside the window's snapshots, 0 .. 1.5 h",
                       SceneError);
  CHECK_THROWS_WITH_AS(snapshotNear({}, 1.0), "--at-h 1: outside the run's snapshots, none", SceneError);
}
