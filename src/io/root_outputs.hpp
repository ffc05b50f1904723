#pragma once
// internal: what one growing root writes into its folder (docs/outputs.md; defined in root_outputs.cpp),
// shared by a run of one root
// (run_scene.cpp) and a plate's roots (run_plate.cpp)
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

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

// what to do with an interrupted run DIR.partial when resuming (run_scene.cpp): continue it from its
// checkpoint (ck filled), discard it, or refuse
PartialRun resumePlan(const Scene& sc, const std::string& outDir, std::uint64_t hash, bool force,
                      std::optional<RunCheckpoint>& ck);

}  // namespace rootsim::detail
