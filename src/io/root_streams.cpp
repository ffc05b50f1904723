// The files a root streams while it grows (root_streams.hpp)
#include "root_streams.hpp"

#include <exception>

#include "rootsim/outputs.hpp"

namespace fs = std::filesystem;

namespace rootsim::detail {

RootStreams::RootStreams(const fs::path& w, const Model& m, const OutputParams& o, const WriterPositions* p,
                         const Vec3& vtkOffset)
    : vtkOffset_(vtkOffset) {
  const bool traj = o.trajectory;
  const bool csv = traj && o.trajectoryFormat != TrajectoryFormat::Binary;
  const bool bin = traj && o.trajectoryFormat != TrajectoryFormat::Csv;
  // a root that had written nothing when the checkpoint saw it (a plate's lateral that emerged after the
  // last output step: its writers had not handed even their headers to the system) starts its files anew
  if (p && p->timeseriesBytes == 0) p = nullptr;
  if (p) {
    ts_ = std::make_unique<TimeseriesWriter>(w / "timeseries.csv", p->timeseriesBytes);
    if (csv) tr_ = std::make_unique<TrajectoryWriter>(w / "trajectory.csv", p->trajectoryBytes, p->trajectoryFrames);
    if (bin) tb_ = std::make_unique<TrajectoryBinaryWriter>(w / "trajectory.bin", p->trajectoryBinaryBytes, p->trajectoryFrames);
    if (o.vtk) vtk_ = std::make_unique<VtkSeriesWriter>(w, sceneInfoOf(m), p->vtkEntries);
  } else {
    ts_ = std::make_unique<TimeseriesWriter>(w / "timeseries.csv");
    if (csv) tr_ = std::make_unique<TrajectoryWriter>(w / "trajectory.csv");
    if (bin) tb_ = std::make_unique<TrajectoryBinaryWriter>(w / "trajectory.bin");
    if (o.vtk) vtk_ = std::make_unique<VtkSeriesWriter>(w, sceneInfoOf(m));
  }
}

void RootStreams::add(const Simulation& sim) {
  ts_->add(sim.last());
  if (tr_ || tb_ || vtk_) {
    const Snapshot sn = sim.snapshot();
    if (tr_) tr_->add(sn);
    if (tb_) tb_->add(sn);
    if (vtk_ && vtkOffset_.isZero(0.0)) {
      vtk_->add(sn);
    } else if (vtk_) {
      Snapshot moved = sn;
      moved.x.colwise() += vtkOffset_;
      vtk_->add(moved);
    }
  }
}

WriterPositions RootStreams::positions() const {
  WriterPositions p;
  p.timeseriesBytes = ts_->bytes();
  if (tr_) p.trajectoryBytes = tr_->bytes();
  if (tb_) p.trajectoryBinaryBytes = tb_->bytes();
  p.trajectoryFrames = tr_ ? tr_->frames() : (tb_ ? tb_->frames() : 0);
  if (vtk_) p.vtkEntries = vtk_->entries();
  return p;
}

void RootStreams::close() {
  ts_->close();
  if (tr_) tr_->close();
  if (tb_) tb_->close();
  if (vtk_) vtk_->close();
}

void RootStreams::closeQuietly() {
  auto quietly = [](auto&& close) {
    try {
      close();
    } catch (const std::exception&) {
      // a writer that cannot close (the disk that failed the run) keeps nothing; the others still do
    }
  };
  quietly([&] { ts_->close(); });
  if (tr_) quietly([&] { tr_->close(); });
  if (tb_) quietly([&] { tb_->close(); });
  if (vtk_) quietly([&] { vtk_->close(); });
}

}  // namespace rootsim::detail
