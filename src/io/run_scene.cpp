// One scene -> one run directory (used by `rootsim run` and by sweeps).
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

using namespace detail;

namespace {

// leftovers of atomic writes a kill interrupted (the streams being continued excepted)
void removeStaleTemps(const fs::path& work) {
  std::error_code ec;
  for (const fs::path& dir : {work, work / "vtk"}) {
    if (!fs::is_directory(dir, ec)) continue;
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0 && name != "timeseries.csv.tmp" &&
          name != "trajectory.csv.tmp" && name != "trajectory.bin.tmp")
        stale.push_back(e.path());
    }
    for (const auto& f : stale) fs::remove(f, ec);
  }
}

}  // namespace

double runSceneToDir(const Scene& sc, const std::string& outDir, const RunDirOptions& dirOptions,
                     const std::function<void(const StepRecord&, int total)>& progress) {
  if (sc.isPlate()) return runPlateToDir(sc, outDir, dirOptions, progress);
  const Model& m = sc.model;
  const std::uint64_t hash = sceneHash(sc.resolvedToml);
  std::optional<RunCheckpoint> ck;
  const PartialRun partial =
      dirOptions.resume ? resumePlan(sc, outDir, hash, dirOptions.force, ck) : PartialRun::Refuse;
  RunDir rd(outDir, dirOptions, partial);
  if (dirOptions.note && ck)
    dirOptions.note("resuming " + rd.final().string() + " from the checkpoint of growth step " +
                    std::to_string(ck->step) + " of " + std::to_string(m.growth.steps));
  else if (dirOptions.note && partial == PartialRun::Discard)
    dirOptions.note("no usable checkpoint in " + rd.work().string() + ": starting " + rd.final().string() + " again");
  const double t0 = now();
  const StepSeams seams = stepSeams();
  try {
    const fs::path w = rd.work();
    std::unique_ptr<Simulation> simp;
    std::unique_ptr<RootStreams> out;
    RunWatch watch;
    double wallBefore = 0;         // wall time of earlier attempts (resumed) [s]
    int first = 1;                 // the first growth step this process runs
    if (ck) {
      // resumed: the state, the solvers' memory and the writers where the checkpoint saw them
      removeStaleTemps(w);
      simp = std::make_unique<Simulation>(m, ck->state, ck->carry);
      out = std::make_unique<RootStreams>(w, m, &ck->writers);
      watch = ck->acc.watch;
      wallBefore = ck->acc.wallBefore;
      first = ck->step + 1;
    } else {
      rd.write("scene.toml", sc.resolvedToml);
      simp = std::make_unique<Simulation>(m);
      out = std::make_unique<RootStreams>(w, m);
    }
    Simulation& sim = *simp;
    if (!ck) {
      out->add(sim);
      watch.start(sim.last());
    }
    // a checkpoint: everything carried to the next step, and where the files stand (each add() flushed)
    auto checkpoint = [&](int k) {
      RunCheckpoint c;
      c.sceneHash = hash;
      c.step = k;
      c.state = sim.state();
      c.carry = sim.carry();
      c.acc = {watch, wallBefore + (now() - t0)};
      c.writers = out->positions();
      writeCheckpoint(w / kCheckpointFile, c);
    };
    double lastCheckpoint = now();
    const int steps = m.growth.enabled ? m.growth.steps : 0;
    // A run that fails keeps what its writers hold, closed so that the files are whole and readable: the
    // time series and trajectory up to the last output step before the failure, the ParaView series. The
    // directory becomes DIR.incomplete with ERROR.txt (RunDir::fail), which marks it. (A stop on purpose
    // leaves DIR.partial as a kill does, its files where the checkpoint expects them.)
    try {
      for (int k = first; k <= steps; ++k) {
        const StepRecord& r = sim.growthStep();
        watch.see(r);
        try {
          if (k % m.output.everySteps == 0 || k == steps) out->add(sim);
          const bool due = seams.checkpointAfter ? seams.checkpointAfter(k)
                                                 : now() - lastCheckpoint >= m.output.checkpointEvery;
          if (k < steps && due) {
            checkpoint(k);
            lastCheckpoint = now();
          }
        } catch (const RunError& e) {
          throw RunError(std::string(e.what()) + " (at growth step " + std::to_string(k) + " of " +
                         std::to_string(steps) + ")");
        }
        if (seams.afterStep) seams.afterStep(k);
        if (progress) progress(r, steps);
      }
    } catch (const RunInterrupted&) {
      throw;
    } catch (const std::exception&) {
      out->closeQuietly();
      throw;
    }
    out->close();
    // the finished run holds no checkpoint: it is the same as a run never interrupted
    std::error_code ec;
    fs::remove(w / kCheckpointFile, ec);
    const double wall = wallBefore + (now() - t0);
    const RootFinal f = finishRoot(m, sim, watch, wall);
    rd.write("shape.csv", f.shape);
    rd.write("summary.json", f.summary);
    rd.write("result.csv", f.result);
    rd.commit();
    return wall;
  } catch (const RunInterrupted&) {
    throw;  // stopped on purpose (a progress callback threw it): DIR.partial stays, like a killed run
  } catch (const std::exception& e) {
    rd.fail(failureText(e, "the run of " + sc.model.name + " into " + rd.work().string()));
    throw;
  }
}

}  // namespace rootsim
