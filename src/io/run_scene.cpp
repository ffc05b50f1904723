// One scene -> one run directory (used by `rootsim run` and by sweeps). A plate's roots and a scene of one
// root alone run through the same steps: a root alone is a plate of one seedling (plateOfOne), whose folder
// is the run directory itself; a plate's roots each have a folder roots/NAME and the plate writes its own
// files beside them (run_plate.hpp; docs/plate.md, Outputs). The directory, the roots' streams and watches,
// checkpoints, --resume and failures are RunOutputs'.
#include "rootsim/run_scene.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

#include "rootsim/checkpoint.hpp"
#include "rootsim/plate.hpp"
#include "plate_scene.hpp"
#include "run_outputs.hpp"
#include "run_plate.hpp"
#include "run_resume.hpp"

namespace fs = std::filesystem;

namespace rootsim {

using namespace detail;

double runSceneToDir(const Scene& sc, const std::string& outDir, const RunDirOptions& dirOptions,
                     const std::function<void(const StepRecord&, int total)>& progress) {
  const bool isPlate = sc.isPlate();
  const RunLayout layout = isPlate ? RunLayout::Plate : RunLayout::OneRoot;
  const PlateSpec one = isPlate ? PlateSpec{} : plateOfOne(sc.model);
  const PlateSpec& spec = isPlate ? sc.plate : one;
  const std::uint64_t hash = sceneHash(sc.resolvedToml);
  std::vector<std::string> seedlingNames;
  for (const Seedling& sd : spec.seedlings) seedlingNames.push_back(sd.name);
  // a root's folder in the run directory w: the directory itself for a scene of one root
  auto folderOf = [&](const fs::path& w, const std::string& name) { return isPlate ? w / "roots" / name : w; };
  // an interrupted run (DIR.partial) continues from its checkpoint
  std::optional<RunCheckpoint> ck;
  RunOutputs run(sc, outDir, dirOptions, (isPlate ? "the plate run of " : "the run of ") + sc.model.name,
                 [&](const fs::path& file) {
                   ck.reset();
                   ck = readCheckpoint(file, layout, seedlingNames);
                   checkSceneHash(file, ck->sceneHash, hash);
                   const fs::path w = file.parent_path();
                   if (isPlate) checkStreamLength(w / "plate_timeseries.csv", ck->acc.seriesBytes);
                   std::vector<std::string> names = seedlingNames;
                   for (const LateralBirth& b : ck->plate.laterals)
                     names.push_back(lateralName(names[static_cast<size_t>(b.parent)], b.site));
                   for (size_t r = 0; r < names.size(); ++r)
                     checkStreamLengths(folderOf(w, names[r]), sc.output, ck->roots[r].writers);
                   return CheckpointSeen{ck->step, ck->acc.wallBefore};
                 });
  if (!run.resumed()) ck.reset();
  const int steps = sc.model.growth.enabled ? sc.model.growth.steps : 0;
  return run.runMarkingFailure([&] {
    const fs::path w = run.work();
    std::unique_ptr<PlateSimulation> platep;
    AtomicFile* series = nullptr;  // plate_timeseries.csv (a plate's)
    RunAccumulators acc;
    if (ck) {
      // resumed: every root where the checkpoint saw it, its streams cut back to their positions; the
      // folders of laterals that emerged after the checkpoint go (they emerge again, the same)
      platep = std::make_unique<PlateSimulation>(spec.params, spec.seedlings, ck->plate);
      if (isPlate) {
        std::set<std::string> kept;
        for (int r = 0; r < platep->size(); ++r) kept.insert(platep->seedling(r).name);
        std::error_code ec;
        std::vector<fs::path> later;
        for (const auto& e : fs::directory_iterator(w / "roots", ec))
          if (!kept.count(e.path().filename().string()) && fs::is_regular_file(e.path() / kRunMarker, ec))
            later.push_back(e.path());
        for (const fs::path& d : later) fs::remove_all(d, ec);
      }
      for (int r = 0; r < platep->size(); ++r)
        run.addRoot(folderOf(w, platep->seedling(r).name), platep->seedling(r).model, platep->offset(r),
                    &ck->roots[static_cast<size_t>(r)]);
      if (isPlate) series = &run.addStream("plate_timeseries.csv", ck->acc.seriesBytes);
      acc = ck->acc;
    } else {
      run.write("scene.toml", sc.resolvedToml);
      std::vector<fs::path> dirs;
      for (size_t r = 0; r < spec.seedlings.size(); ++r)
        dirs.push_back(isPlate ? run.rootFolder(spec.seedlings[r].name, sc.rootToml[r]) : w);
      platep = std::make_unique<PlateSimulation>(spec.params, spec.seedlings);
      for (int r = 0; r < platep->size(); ++r)
        run.addRoot(dirs[static_cast<size_t>(r)], platep->seedling(r).model, platep->offset(r));
      if (isPlate) {
        series = &run.addStream("plate_timeseries.csv");
        series->stream() << plateSeriesHeader();
      }
    }
    PlateSimulation& plate = *platep;
    // the plate's roots, those of its laterals included, are the run's roots in the same order
    auto record = [&] {
      for (int r = 0; r < plate.size(); ++r) run.root(static_cast<size_t>(r)).add(plate.root(r));
      if (series) {
        series->stream() << plateSeriesRow(plate.last());
        series->flush();
      }
    };
    if (!ck) {
      record();
      for (int r = 0; r < plate.size(); ++r) run.root(static_cast<size_t>(r)).start(plate.root(r).last());
    }
    // a lateral root that emerged (a plate's): its folder, its scene (the plate with it alone), its streams
    // (its first snapshot at the next output step, so that every root's snapshots fall on the plate's output
    // steps)
    auto open = [&](int r) {
      const Seedling& sd = plate.seedling(r);
      const fs::path d = run.rootFolder(sd.name, spec.headToml + plateTableToml(spec.params) + seedlingToml(sd, spec.base));
      run.addRoot(d, sd.model, plate.offset(r)).start(plate.root(r).last());
    };
    // a checkpoint: the plate's carry, each root's accumulators and where its files stand, the run's own
    auto checkpoint = [&](int k) {
      RunCheckpoint c;
      c.sceneHash = hash;
      c.step = k;
      c.layout = layout;
      c.plate = plate.carry();
      for (int r = 0; r < plate.size(); ++r) c.roots.push_back(run.root(static_cast<size_t>(r)).checkpointed());
      c.acc = acc;
      c.acc.wallBefore = run.wall();
      c.acc.seriesBytes = series ? series->size() : 0;
      writeCheckpoint(run.checkpointFile(), c);
    };
    const OutputParams& output = sc.output;
    run.growthSteps(steps, output.checkpointEvery, RunSteps{
        [&](int) {
          const PlateStepRecord& pr = plate.growthStep();
          acc.maxSweeps = std::max(acc.maxSweeps, pr.sweeps);
          if (!std::isnan(pr.minGap) && !(pr.minGap >= acc.minGap)) acc.minGap = pr.minGap;
        },
        [&](int k) {
          const std::vector<int>& emerged = plate.emerged();
          for (int r : emerged) open(r);
          for (int r = 0; r < plate.size(); ++r)
            if (std::find(emerged.begin(), emerged.end(), r) == emerged.end())
              run.root(static_cast<size_t>(r)).see(plate.root(r).last());
          if (k % output.everySteps == 0 || k == steps) record();
        },
        checkpoint,
        [&](int) {
          if (progress) progress(plate.root(0).last(), steps);
        }});
    const double wall = run.endSteps();
    // a root alone: its folder, the run directory, is the run's whole; a plate: its own files besides
    if (isPlate)
      finishPlate(run, sc, plate, acc, wall);
    else
      run.root(0).finish(plate.seedling(0).model, plate.root(0), wall);
    run.commit();
    return wall;
  });
}

}  // namespace rootsim
