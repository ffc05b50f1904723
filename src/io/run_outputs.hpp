#pragma once
// internal: a run's outputs from start to end, the same for a run of one root and a plate
// (run_scene.cpp): the run directory claimed, locked and marked (RunDir), continued from
// its checkpoint with --resume, each root's folder with its streams and watch (RootOutputs), the run's own
// streams, the growth steps with their checkpoint cadence, and the end: committed whole, or marked as a
// failed run (DIR.incomplete with ERROR.txt) saying why
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rootsim/checkpoint.hpp"
#include "rootsim/model.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "root_outputs.hpp"

namespace rootsim::detail {

// a monotonic clock [s], for a run's wall time
inline double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// what a run does in its growth steps: grow(k), then write(k) (what step k writes) and, at the run's
// cadence, checkpoint(k); then progress(k) (RunOutputs::growthSteps)
struct RunSteps {
  std::function<void(int)> grow, write, checkpoint, progress;
};

// what a checkpoint read for a resumed run says of the run
struct CheckpointSeen {
  int step = 0;           // the last growth step it holds
  double wallBefore = 0;  // the wall time of the attempts before [s]
};

class RunOutputs {
 public:
  // the run directory of `scene` at outDir (RunDir: claimed, locked, marked; SceneError before anything
  // is written). With o.resume an interrupted DIR.partial is continued when load(its checkpoint file) reads
  // a checkpoint it can use (it throws SceneError otherwise; resumePlan), and o.note says so. `what` names
  // the run in a failure's text ("the run of NAME").
  RunOutputs(const Scene& scene, const std::string& outDir, const RunDirOptions& o, std::string what,
             const std::function<CheckpointSeen(const std::filesystem::path&)>& load);
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  // continuing from a checkpoint (load's), rather than a new run
  bool resumed() const { return resumed_; }
  // the first growth step this process runs
  int firstStep() const { return seen_.step + 1; }
  const std::filesystem::path& work() const { return dir_.work(); }
  std::filesystem::path checkpointFile() const { return dir_.work() / kCheckpointFile; }
  // the run's wall time so far: the attempts before a resume and this one [s]
  double wall() const { return seen_.wallBefore + (now() - t0_); }

  // runs the whole run; a failure other than a stop on purpose (RunInterrupted: DIR.partial stays, as a
  // kill leaves it) marks the directory as a failed run saying why, then goes on
  double runMarkingFailure(const std::function<double()>& body);

  // writes a file of the run directory atomically; throws RunError
  void write(const std::string& name, const std::string& content) { dir_.write(name, content); }
  // a plate root's folder roots/NAME: created, marked first as every run directory is, its scene written;
  // throws RunError naming the folder
  std::filesystem::path rootFolder(const std::string& name, const std::string& sceneToml);
  // a root's outputs in its folder (the run directory itself, or rootFolder's), the files the scene's
  // [output] asks for, opened new or (at: the checkpoint's) continued
  RootOutputs& addRoot(const std::filesystem::path& dir, const Model& m, const Vec3& vtkOffset = Vec3::Zero(),
                       const PlateRootRun* at = nullptr);
  RootOutputs& root(std::size_t r) { return *roots_[r]; }
  std::size_t roots() const { return roots_.size(); }
  // a stream of the run itself in its directory (a plate's plate_timeseries.csv), opened new or, resumed,
  // continued at the checkpoint's length, the directory's other leftovers of atomic writes removed
  AtomicFile& addStream(const std::string& name, std::uint64_t resumeBytes = 0);

  // the growth steps firstStep()..steps: a checkpoint after step k (k < steps) every checkpointEvery
  // seconds of wall time (the test binary's seams: run_seams.hpp); a writer's RunError names the step
  // ("at growth step k of N"). On a failure every stream is closed whole (what the failed run keeps).
  void growthSteps(int steps, double checkpointEvery, const RunSteps& f);
  // the end of the steps: every stream closed, the checkpoint removed (a finished run is the same as one
  // never interrupted); returns the run's wall time
  double endSteps();
  // DIR.partial -> DIR
  void commit() { dir_.commit(); }

 private:
  PartialRun plan(const Scene& scene, const std::string& outDir, const RunDirOptions& o,
                  const std::function<CheckpointSeen(const std::filesystem::path&)>& load);
  void closeQuietly();
  void dropWriters();

  std::string what_;
  OutputParams output_;  // the scene's: what every root writes
  CheckpointSeen seen_;
  PartialRun partial_ = PartialRun::Refuse;
  bool resumed_ = false;
  RunDir dir_;  // after seen_, partial_ and resumed_: its constructor's argument sets them (plan)
  double t0_ = 0;
  std::vector<std::unique_ptr<RootOutputs>> roots_;
  std::vector<std::unique_ptr<AtomicFile>> streams_;
};

}  // namespace rootsim::detail
