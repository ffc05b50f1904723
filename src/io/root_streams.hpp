#pragma once
// internal: the files one root streams while it grows (docs/outputs.md), in its folder: a run of one
// root's and each of a plate's roots' (RootOutputs)
#include <filesystem>
#include <memory>

#include "rootsim/checkpoint.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/model.hpp"
#include "rootsim/output_params.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/trajectory.hpp"
#include "rootsim/vtk.hpp"

namespace rootsim::detail {

// the files a root streams while it grows: its time series, its trajectory (CSV and/or binary) and
// its ParaView series, as output.* asks; opened new, or where a checkpoint saw them
class RootStreams {
 public:
  // vtkOffset: added to the ParaView snapshots' positions (a plate's roots write theirs in plate
  // coordinates, so that they open together); the trajectory stays in the root's own frame
  RootStreams(const std::filesystem::path& dir, const Model& m, const OutputParams& o, const WriterPositions* resume = nullptr,
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

}  // namespace rootsim::detail
