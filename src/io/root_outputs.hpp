#pragma once
// internal: one growing root's folder (docs/outputs.md): the files it streams, what its run watches, where
// a checkpoint saw both, and the files it writes last. A run of one root has one, in its run directory; a
// plate has one per root, in roots/NAME (RunOutputs opens them).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rootsim/checkpoint.hpp"
#include "rootsim/model.hpp"
#include "rootsim/output_params.hpp"
#include "rootsim/results.hpp"
#include "rootsim/run_watch.hpp"
#include "rootsim/simulation.hpp"
#include "root_streams.hpp"

namespace rootsim::detail {

class RootOutputs {
 public:
  // a root's folder `dir` (existing; its scene.toml already written): its streams (as o asks) opened new, or (at: a
  // checkpoint's) continued where the checkpoint saw them with the watch it had, the leftovers of atomic
  // writes a kill interrupted removed first. ownFolder: a run directory of its own inside the run's (a
  // plate's roots/NAME), marked when it finishes; else it is the run directory, which RunDir marks.
  // vtkOffset as RootStreams'.
  RootOutputs(std::filesystem::path dir, const Model& m, const OutputParams& o, bool ownFolder, const Vec3& vtkOffset,
              const PlateRootRun* at = nullptr);

  const std::filesystem::path& dir() const { return dir_; }
  // the first record of a new root (its watch starts there), then each growth step's
  void start(const StepRecord& r) { watch_.start(r); }
  void see(const StepRecord& r) { watch_.see(r); }
  // a time-series row and a snapshot (an output step)
  void add(const Simulation& sim) { streams_.add(sim); }
  // what a checkpoint keeps of it: its watch and where its files stand
  PlateRootRun checkpointed() const { return {watch_, streams_.positions()}; }
  const RunWatch& watch() const { return watch_; }

  // closes its streams at the end of the growth steps; vtkEntries() then lists its ParaView snapshots
  void close();
  // closes what can be closed on a failure, so that the files are whole; never throws
  void closeQuietly() { streams_.closeQuietly(); }
  const std::vector<std::pair<double, std::string>>& vtkEntries() const { return vtkEntries_; }

  // what a finished root writes last: shape.csv, summary.json and result.csv (what sweep tables are made
  // of), then its own folder's marker listing its files; returns their texts and the result. wallS: the
  // run's wall time [s]
  struct Final {
    std::string shape, summary, result;
    RunResult res;
  };
  Final finish(const Model& m, const Simulation& sim, double wallS) const;

 private:
  std::filesystem::path dir_;
  bool ownFolder_;
  RootStreams streams_;
  RunWatch watch_;
  std::vector<std::pair<double, std::string>> vtkEntries_;
};

}  // namespace rootsim::detail
