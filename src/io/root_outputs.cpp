// What one growing root writes into its folder (root_outputs.hpp): its streams, its final files, and
// what a resumed run does with an interrupted folder
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include <optional>

#include "rootsim/checkpoint.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/results.hpp"
#include "rootsim/units.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/run_seams.hpp"
#include "rootsim/run_watch.hpp"
#include "rootsim/version.hpp"
#include "root_outputs.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace detail {

RootStreams::RootStreams(const fs::path& w, const Model& m, const WriterPositions* p, const Vec3& vtkOffset)
    : vtkOffset_(vtkOffset) {
  const bool traj = m.output.trajectory;
  const bool csv = traj && m.output.trajectoryFormat != TrajectoryFormat::Binary;
  const bool bin = traj && m.output.trajectoryFormat != TrajectoryFormat::Csv;
  // a root that had written nothing when the checkpoint saw it (a plate's lateral that emerged after the
  // last output step: its writers had not handed even their headers to the system) starts its files anew
  if (p && p->timeseriesBytes == 0) p = nullptr;
  if (p) {
    ts_ = std::make_unique<TimeseriesWriter>(w / "timeseries.csv", p->timeseriesBytes);
    if (csv) tr_ = std::make_unique<TrajectoryWriter>(w / "trajectory.csv", p->trajectoryBytes, p->trajectoryFrames);
    if (bin) tb_ = std::make_unique<TrajectoryBinaryWriter>(w / "trajectory.bin", p->trajectoryBinaryBytes, p->trajectoryFrames);
    if (m.output.vtk) vtk_ = std::make_unique<VtkSeriesWriter>(w, sceneInfoOf(m), p->vtkEntries);
  } else {
    ts_ = std::make_unique<TimeseriesWriter>(w / "timeseries.csv");
    if (csv) tr_ = std::make_unique<TrajectoryWriter>(w / "trajectory.csv");
    if (bin) tb_ = std::make_unique<TrajectoryBinaryWriter>(w / "trajectory.bin");
    if (m.output.vtk) vtk_ = std::make_unique<VtkSeriesWriter>(w, sceneInfoOf(m));
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

RootFinal finishRoot(const Model& m, const Simulation& sim, const RunWatch& watch, double wall) {
  RootFinal f;
  f.shape = shapeCsv(m, sim.state(), sim.strains());
  // summary.json and the one-row result.csv (what sweep tables are made of)
  const StepRecord& r = sim.last();
  Json j;
  j.str("rootsim_version", kVersion).str("scene", m.name).str("status", "complete");
  j.integer("steps", sim.step()).num("time_h", r.timeH).num("length_mm", r.length / units::mm);
  j.integer("elements", r.elements).integer("total_substeps", sim.totalSubsteps());
  j.integer("max_substeps_per_step", watch.maxSubsteps);
  j.num("theta_tip_deg", r.thetaTip / units::deg);
  Json tip;
  tip.num("x_mm", r.tip.x() / units::mm).num("y_mm", r.tip.y() / units::mm).num("z_mm", r.tip.z() / units::mm);
  j.object("tip", tip);
  // contact (docs/model.md, Contact and friction): zero when self-contact, friction and obstacles are off
  Json contact;
  contact.integer("self_contacts", r.selfContacts)
      .integer("max_self_contacts", watch.maxSelfContacts)
      .num("min_self_distance_r", watch.minSelfDistance)
      .integer("obstacle_contacts", r.obstacleContacts)
      .integer("slip_events", r.slipEvents)
      .num("frictional_work_j", r.frictionWork);
  j.object("contact", contact);
  const double snapOrTurn = m.env.plane.enabled ? watch.snapFirst : watch.snapVertical;
  std::optional<ShapeAnalysis> shape;
  if (m.growth.enabled) shape = analyseShape(m, sim.state());
  f.res = makeResult(m, sim, shape ? &*shape : nullptr, snapOrTurn);
  const RunResult& res = f.res;
  if (shape) {
    j.str("pattern", res.pattern)
        .num("wavelength_mm", res.wavelengthMm)
        .num("amplitude_mm", res.amplitudeMm)
        .num("amplitude_half_mm", res.amplitudeHalfMm)
        .integer("lateral_peaks", static_cast<long>(res.lateralPeaks))
        .num("skew_deg", res.skewDeg)
        .num("max_kappa_per_mm", res.maxKappaPerMm)
        .num("theta_min_deg", res.thetaMinDeg)
        .num("theta_max_deg", res.thetaMaxDeg)
        .num(m.env.plane.enabled ? "first_snap_h" : "turning_time_h", snapOrTurn);
    j.object("theory", theoryJson(theoryFor(m)));
  } else {
    j.num("residual_force_n", r.residualForce);
  }
  j.num("wall_time_s", wall);
  f.summary = j.dump() + "\n";
  f.result = resultCsv(res);
  return f;
}

// what to do with an interrupted run DIR.partial when resuming: continue it from its checkpoint (load
// read it), discard it (killed before its first checkpoint: nothing to lose), or refuse (another scene,
// a corrupt checkpoint; with force those are discarded too)
PartialRun resumePlan(const Scene& sc, const std::string& outDir, bool force,
                      const std::function<void(const fs::path&)>& load) {
  fs::path work = normaliseOutDir(outDir);
  work += ".partial";
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(work, ec))) return PartialRun::Refuse;  // nothing to resume: a new run
  if (std::string why = whyNotOurs(work, runFolder()); !why.empty()) throw SceneError("--out " + outDir + ": " + why);
  // the first file a run writes is its resolved scene
  std::ifstream in(work / "scene.toml", std::ios::binary);
  if (!in) return PartialRun::Discard;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text != sc.resolvedToml) {
    if (force) return PartialRun::Discard;
    throw SceneError("--resume: " + work.string() + " was written by another scene (" +
                     sceneDifference((work / "scene.toml").string(), text, sc.resolvedToml, sc.path) +
                     "); pass the same scene and --set values, or --force to discard it and start again");
  }
  if (!fs::exists(work / kCheckpointFile, ec)) {
    // killed before its first checkpoint: nothing to lose. But a run that finished there (its
    // summary.json written: renamed by hand, or a commit that failed) is never discarded without --force
    if (!force && fs::exists(work / "summary.json", ec))
      throw SceneError("--resume: " + work.string() + " holds a finished run without a checkpoint (it has summary.json); "
                       "move it away, or pass --force to discard it and start again");
    return PartialRun::Discard;
  }
  try {
    load(work / kCheckpointFile);
  } catch (const SceneError&) {
    if (force) return PartialRun::Discard;
    throw;
  }
  return PartialRun::Continue;
}

void noteResume(const RunDirOptions& o, const RunDir& rd, PartialRun partial, int step, int steps) {
  if (!o.note) return;
  if (partial == PartialRun::Continue)
    o.note("resuming " + rd.final().string() + " from the checkpoint of growth step " + std::to_string(step) + " of " +
           std::to_string(steps));
  else if (partial == PartialRun::Discard)
    o.note("no usable checkpoint in " + rd.work().string() + ": starting " + rd.final().string() + " again");
}

void checkStreamLengths(const fs::path& dir, const Model& m, const WriterPositions& w) {
  const bool traj = m.output.trajectory;
  const std::pair<const char*, std::uint64_t> streams[] = {
      {"timeseries.csv", w.timeseriesBytes},
      {"trajectory.csv", traj && m.output.trajectoryFormat != TrajectoryFormat::Binary ? w.trajectoryBytes : 0},
      {"trajectory.bin", traj && m.output.trajectoryFormat != TrajectoryFormat::Csv ? w.trajectoryBinaryBytes : 0}};
  for (const auto& [name, bytes] : streams) checkStreamLength(dir / name, bytes);
}

void checkStreamLength(const fs::path& file, std::uint64_t bytes) {
  if (bytes == 0) return;
  std::error_code ec;
  fs::path f = file;
  f += ".tmp";
  if (!fs::is_regular_file(f, ec)) f = file;  // killed after it was closed
  const std::uintmax_t have = fs::is_regular_file(f, ec) ? fs::file_size(f, ec) : 0;
  if (have < bytes)
    throw SceneError(f.string() + ": missing or shorter (" + std::to_string(have) + " bytes) than its checkpoint says (" +
                     std::to_string(bytes) + " bytes); pass --force to discard the interrupted run and start again");
}

void runGrowthSteps(int first, int steps, double checkpointEvery, const RunSteps& f) {
  const StepSeams seams = stepSeams();
  double lastCheckpoint = now();
  // A run that fails keeps what its writers hold, closed so that the files are whole and readable: the
  // time series and trajectory up to the last output step before the failure, the ParaView series. The
  // directory becomes DIR.incomplete with ERROR.txt (RunDir::fail), which marks it. (A stop on purpose
  // leaves DIR.partial as a kill does, its files where the checkpoint expects them.)
  try {
    for (int k = first; k <= steps; ++k) {
      f.grow(k);
      try {
        f.write(k);
        const bool due = seams.checkpointAfter ? seams.checkpointAfter(k) : now() - lastCheckpoint >= checkpointEvery;
        if (k < steps && due) {
          f.checkpoint(k);
          lastCheckpoint = now();
        }
      } catch (const RunError& e) {
        throw RunError(std::string(e.what()) + " (at growth step " + std::to_string(k) + " of " + std::to_string(steps) + ")");
      }
      if (seams.afterStep) seams.afterStep(k);
      f.progress(k);
    }
  } catch (const RunInterrupted&) {
    throw;
  } catch (const std::exception&) {
    f.closeQuietly();
    throw;
  }
}

void checkSceneHash(const fs::path& file, std::uint64_t found, std::uint64_t expected) {
  if (found != expected)
    throw SceneError(file.string() + ": written by another scene (scene hash differs); pass --force to discard it and "
                     "start again");
}
}  // namespace detail

}  // namespace rootsim
