// One scene -> one run directory (used by `rootsim run` and by sweeps); a plate's: run_plate.cpp
#include "rootsim/run_scene.hpp"

#include <memory>
#include <optional>

#include "rootsim/checkpoint.hpp"
#include "rootsim/run_watch.hpp"
#include "run_outputs.hpp"
#include "run_resume.hpp"

namespace fs = std::filesystem;

namespace rootsim {

using namespace detail;

double runSceneToDir(const Scene& sc, const std::string& outDir, const RunDirOptions& dirOptions,
                     const std::function<void(const StepRecord&, int total)>& progress) {
  if (sc.isPlate()) return runPlateToDir(sc, outDir, dirOptions, progress);
  const Model& m = sc.model;
  const std::uint64_t hash = sceneHash(sc.resolvedToml);
  std::optional<RunCheckpoint> ck;
  RunOutputs run(sc, outDir, dirOptions, "the run of " + m.name, [&](const fs::path& file) {
    ck.reset();
    ck = readCheckpoint(file);
    checkSceneHash(file, ck->sceneHash, hash);
    checkStreamLengths(file.parent_path(), sc.output, ck->writers);
    return CheckpointSeen{ck->step, ck->acc.wallBefore};
  });
  if (!run.resumed()) ck.reset();
  return run.runMarkingFailure([&] {
    // resumed: the state, the solvers' memory, the watch and the files where the checkpoint saw them
    if (!ck) run.write("scene.toml", sc.resolvedToml);
    const std::unique_ptr<Simulation> simp = ck ? std::make_unique<Simulation>(m, ck->state, ck->carry)
                                                : std::make_unique<Simulation>(m);
    Simulation& sim = *simp;
    const PlateRootRun at = ck ? PlateRootRun{ck->acc.watch, ck->writers} : PlateRootRun{};
    RootOutputs& out = run.addRoot(run.work(), m, Vec3::Zero(), ck ? &at : nullptr);
    if (!ck) {
      out.add(sim);
      out.start(sim.last());
    }
    // a checkpoint: everything carried to the next step, and where the files stand (each add() flushed)
    auto checkpoint = [&](int k) {
      RunCheckpoint c;
      c.sceneHash = hash;
      c.step = k;
      c.state = sim.state();
      c.carry = sim.carry();
      const PlateRootRun seen = out.checkpointed();
      c.acc = {seen.watch, run.wall()};
      c.writers = seen.writers;
      writeCheckpoint(run.checkpointFile(), c);
    };
    const int steps = m.growth.enabled ? m.growth.steps : 0;
    const StepRecord* r = nullptr;
    run.growthSteps(steps, sc.output.checkpointEvery, RunSteps{
        [&](int) {
          r = &sim.growthStep();
          out.see(*r);
        },
        [&](int k) {
          if (k % sc.output.everySteps == 0 || k == steps) out.add(sim);
        },
        checkpoint,
        [&](int) {
          if (progress) progress(*r, steps);
        }});
    const double wall = run.endSteps();
    out.finish(m, sim, wall);
    run.commit();
    return wall;
  });
}

}  // namespace rootsim
