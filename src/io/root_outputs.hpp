#pragma once
// internal: what one growing root writes into its folder (docs/outputs.md), shared by a run of one root
// (run_scene.cpp) and a plate's roots (run_plate.cpp)
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rootsim/checkpoint.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/results.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/run_watch.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/trajectory.hpp"
#include "rootsim/vtk.hpp"

namespace rootsim::detail {

// a monotonic clock [s], for a run's wall time
inline double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// the files a root streams while it grows: its time series, its trajectory (CSV and/or binary) and
// its ParaView series, as output.* asks; opened new, or where a checkpoint saw them
class RootStreams {
 public:
  // vtkOffset: added to the ParaView snapshots' positions (a plate's roots write theirs in plate
  // coordinates, so that they open together); the trajectory stays in the root's own frame
  RootStreams(const std::filesystem::path& dir, const Model& m, const WriterPositions* resume = nullptr,
              const Vec3& vtkOffset = Vec3::Zero());
  // a time-series row and, when any is written, a snapshot
  void add(const Simulation& sim);
  WriterPositions positions() const;
  void close();
  // closes what can be closed, so that the files are whole (a failed run keeps them); never throws
  void closeQuietly();

 private:
  std::unique_ptr<TimeseriesWriter> ts_;
  std::unique_ptr<TrajectoryWriter> tr_;
  std::unique_ptr<TrajectoryBinaryWriter> tb_;
  std::unique_ptr<VtkSeriesWriter> vtk_;
  Vec3 vtkOffset_;
};

// what a finished root writes last: shape.csv, summary.json (plus `extra` members) and result.csv
struct RootFinal {
  std::string shape, summary, result;
  RunResult res;
};
RootFinal finishRoot(const Model& m, const Simulation& sim, const RunWatch& watch, double wallS);

// the growth steps of a run, one root's or a plate's, from `first` to `steps`: grow(k), then write(k)
// (what step k writes) and, at the run's cadence (checkpointEvery seconds of wall time; the test binary's
// seams: run_seams.hpp) but after the last step, checkpoint(k); a writer's RunError names the step
// ("at growth step k of N"); then progress(k). On a failure (not RunInterrupted) closeQuietly() keeps the
// streams whole before the error goes on.
struct RunSteps {
  std::function<void(int)> grow, write, checkpoint, progress;
  std::function<void()> closeQuietly;
};
void runGrowthSteps(int first, int steps, double checkpointEvery, const RunSteps& f);

// what to do with an interrupted run DIR.partial when resuming (run_scene.cpp): continue it from its
// checkpoint (load(checkpoint file) read it: it throws SceneError when the checkpoint cannot be used),
// discard it, or refuse. The same for a run of one root and a plate.
PartialRun resumePlan(const Scene& sc, const std::string& outDir, bool force,
                      const std::function<void(const std::filesystem::path&)>& load);
// what a resumed run says it does (RunDirOptions::note)
void noteResume(const RunDirOptions& o, const RunDir& rd, PartialRun partial, int step, int steps);
// the streams of a root's folder hold at least what its checkpoint saw (before anything is touched);
// throws SceneError naming the file
void checkStreamLengths(const std::filesystem::path& dir, const Model& m, const WriterPositions& w);
void checkStreamLength(const std::filesystem::path& file, std::uint64_t bytes);
// a checkpoint of this scene (its hash: sceneHash of the resolved scene); throws SceneError naming the file
void checkSceneHash(const std::filesystem::path& file, std::uint64_t found, std::uint64_t expected);
// "FILE:LINE: KEY is A there, B in SCENE" for the first key where two resolved scenes differ (file: where
// `written` was read)
std::string sceneDifference(const std::string& file, const std::string& written, const std::string& current,
                            const std::string& scenePath);
// removes the leftovers of atomic writes a kill interrupted in dir and dir/vtk, but the streams being
// continued (names: their final names)
void removeStaleTemps(const std::filesystem::path& dir, const std::vector<std::string>& streams);
// the streams a root continues (RootStreams)
inline const std::vector<std::string> kRootStreams = {"timeseries.csv", "trajectory.csv", "trajectory.bin"};

}  // namespace rootsim::detail
