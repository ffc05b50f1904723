// A plate scene -> one run directory (docs/plate.md, Outputs): roots/NAME per root, each a run directory
// of that root alone (its own frame), and the plate's summary, time series and ParaView series; its
// directory, roots' folders, checkpoints, --resume and failures as a run of one root's (RunOutputs).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <set>

#include "rootsim/checkpoint.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/json.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/units.hpp"
#include "rootsim/version.hpp"
#include "rootsim/vtk.hpp"
#include "plate_scene.hpp"
#include "run_outputs.hpp"
#include "run_resume.hpp"

namespace fs = std::filesystem;

namespace rootsim {

using namespace detail;

namespace {

// the plate's time series: one row per output step
std::string plateSeriesHeader() { return "step,time_h,touching_pairs,min_gap_over_contact,sweeps\n"; }
std::string plateSeriesRow(const PlateStepRecord& r) {
  return std::to_string(r.step) + "," + shortestNumber(r.timeH) + "," + std::to_string(r.touchingPairs) + "," +
         (std::isnan(r.minGap) ? std::string("") : shortestNumber(r.minGap)) + "," + std::to_string(r.sweeps) + "\n";
}

std::string overridesText(const Seedling& sd) {
  std::string overrides;
  for (const std::string& o : sd.overrides) overrides += (overrides.empty() ? "" : ";") + o;
  return overrides;
}

// plate.csv's row of a root: the seedling, then its result.csv row (result: that file's text); first: the
// header before it
std::string plateTableRows(const Seedling& sd, const std::string& parent, const std::string& result, bool first) {
  const auto nl = result.find('\n');
  std::string rows;
  if (first)
    rows += "root,genotype,parent,order,emerged_h,position_lateral_mm,position_downhill_mm,angle_deg,set_point_deg,overrides," +
            result.substr(0, nl) + "\n";
  std::string row = result.substr(nl + 1);
  if (!row.empty() && row.back() == '\n') row.pop_back();
  rows += csvField(sd.name) + "," + csvField(sd.genotype) + "," + csvField(parent) + "," + std::to_string(sd.order) + "," +
          shortestNumber(sd.emergedH) + "," + shortestNumber(sd.position.x() / units::mm) + "," +
          shortestNumber(sd.position.y() / units::mm) + "," + shortestNumber(sd.model.initial.angle / units::deg) + "," +
          shortestNumber(sd.model.tropism.setPoint / units::deg) + "," + csvField(overridesText(sd)) + "," + row + "\n";
  return rows;
}

// summary.json's entry of a root
Json plateRootJson(const Seedling& sd, const std::string& parent) {
  Json j;
  j.str("name", sd.name).str("genotype", sd.genotype).str("parent", parent).integer("order", sd.order);
  j.num("emerged_h", sd.emergedH).num("set_point_deg", sd.model.tropism.setPoint / units::deg);
  j.str("folder", "roots/" + sd.name);
  j.num("position_lateral_mm", sd.position.x() / units::mm).num("position_downhill_mm", sd.position.y() / units::mm);
  j.num("angle_deg", sd.model.initial.angle / units::deg).str("overrides", overridesText(sd));
  return j;
}

}  // namespace

double runPlateToDir(const Scene& sc, const std::string& outDir, const RunDirOptions& dirOptions,
                     const std::function<void(const StepRecord&, int total)>& progress) {
  const PlateSpec& spec = sc.plate;
  const std::uint64_t hash = sceneHash(sc.resolvedToml);
  std::vector<std::string> seedlingNames;
  for (const Seedling& sd : spec.seedlings) seedlingNames.push_back(sd.name);
  // an interrupted plate (DIR.partial) continues from its checkpoint, as a run of one root does
  std::optional<PlateCheckpoint> ck;
  RunOutputs run(sc, outDir, dirOptions, "the plate run of " + sc.model.name, [&](const fs::path& file) {
    ck.reset();
    ck = readPlateCheckpoint(file, seedlingNames);
    checkSceneHash(file, ck->sceneHash, hash);
    const fs::path w = file.parent_path();
    checkStreamLength(w / "plate_timeseries.csv", ck->acc.seriesBytes);
    const PlateCarry& pc = ck->plate;
    std::vector<std::string> names = seedlingNames;
    for (const LateralBirth& b : pc.laterals) names.push_back(lateralName(names[static_cast<size_t>(b.parent)], b.site));
    for (size_t r = 0; r < names.size(); ++r) checkStreamLengths(w / "roots" / names[r], sc.output, ck->roots[r].writers);
    return CheckpointSeen{ck->step, ck->acc.wallBefore};
  });
  if (!run.resumed()) ck.reset();
  const int steps = sc.model.growth.enabled ? sc.model.growth.steps : 0;
  return run.runMarkingFailure([&] {
    const fs::path w = run.work();
    std::unique_ptr<PlateSimulation> platep;
    AtomicFile* seriesp = nullptr;
    int maxSweeps = 1;
    double minGap = std::numeric_limits<double>::quiet_NaN();
    if (ck) {
      // resumed: every root where the checkpoint saw it, its streams cut back to their positions; the
      // folders of laterals that emerged after the checkpoint go (they emerge again, the same)
      platep = std::make_unique<PlateSimulation>(spec.params, spec.seedlings, ck->plate);
      std::set<std::string> kept;
      for (int r = 0; r < platep->size(); ++r) kept.insert(platep->seedling(r).name);
      std::error_code ec;
      std::vector<fs::path> later;
      for (const auto& e : fs::directory_iterator(w / "roots", ec))
        if (!kept.count(e.path().filename().string()) && fs::is_regular_file(e.path() / kRunMarker, ec))
          later.push_back(e.path());
      for (const fs::path& d : later) fs::remove_all(d, ec);
      for (int r = 0; r < platep->size(); ++r)
        run.addRoot(w / "roots" / platep->seedling(r).name, platep->seedling(r).model, platep->offset(r),
                    &ck->roots[static_cast<size_t>(r)]);
      seriesp = &run.addStream("plate_timeseries.csv", ck->acc.seriesBytes);
      maxSweeps = ck->acc.maxSweeps;
      minGap = ck->acc.minGap;
    } else {
      run.write("scene.toml", sc.resolvedToml);
      std::vector<fs::path> dirs;
      for (size_t r = 0; r < spec.seedlings.size(); ++r) dirs.push_back(run.rootFolder(spec.seedlings[r].name, sc.rootToml[r]));
      platep = std::make_unique<PlateSimulation>(spec.params, spec.seedlings);
      for (int r = 0; r < platep->size(); ++r)
        run.addRoot(dirs[static_cast<size_t>(r)], platep->seedling(r).model, platep->offset(r));
      seriesp = &run.addStream("plate_timeseries.csv");
      seriesp->stream() << plateSeriesHeader();
    }
    PlateSimulation& plate = *platep;
    // the plate's roots, those of its laterals included, are the run's roots in the same order
    AtomicFile& series = *seriesp;
    auto record = [&] {
      for (int r = 0; r < plate.size(); ++r) run.root(static_cast<size_t>(r)).add(plate.root(r));
      series.stream() << plateSeriesRow(plate.last());
      series.flush();
    };
    if (!ck) {
      record();
      for (int r = 0; r < plate.size(); ++r) run.root(static_cast<size_t>(r)).start(plate.root(r).last());
    }
    // a lateral root that emerged: its folder, its scene (the plate with it alone), its streams (its first
    // snapshot at the next output step, so that every root's snapshots fall on the plate's output steps)
    auto open = [&](int r) {
      const Seedling& sd = plate.seedling(r);
      const fs::path d = run.rootFolder(sd.name, spec.headToml + plateTableToml(spec.params) + seedlingToml(sd, spec.base));
      run.addRoot(d, sd.model, plate.offset(r)).start(plate.root(r).last());
    };
    // a checkpoint: the plate's carry, each root's accumulators and where its files stand, the plate's own
    auto checkpoint = [&](int k) {
      PlateCheckpoint c;
      c.sceneHash = hash;
      c.step = k;
      c.plate = plate.carry();
      for (int r = 0; r < plate.size(); ++r) c.roots.push_back(run.root(static_cast<size_t>(r)).checkpointed());
      c.acc = {maxSweeps, minGap, run.wall(), series.size()};
      writePlateCheckpoint(run.checkpointFile(), c);
    };
    const OutputParams& output = sc.output;
    run.growthSteps(steps, output.checkpointEvery, RunSteps{
        [&](int) {
          const PlateStepRecord& pr = plate.growthStep();
          maxSweeps = std::max(maxSweeps, pr.sweeps);
          if (!std::isnan(pr.minGap) && !(pr.minGap >= minGap)) minGap = pr.minGap;
        },
        [&](int k) {
          for (int r : plate.emerged()) open(r);
          for (int r = 0; r < plate.size(); ++r)
            if (std::find(plate.emerged().begin(), plate.emerged().end(), r) == plate.emerged().end())
              run.root(static_cast<size_t>(r)).see(plate.root(r).last());
          if (k % output.everySteps == 0 || k == steps) record();
        },
        checkpoint,
        [&](int) {
          if (progress) progress(plate.root(0).last(), steps);
        }});
    const double wall = run.endSteps();

    // each root's folder is a finished run directory of that root alone; plate.csv: each seedling, then
    // its result.csv row
    std::string table;
    std::vector<Json> roots;
    std::vector<PvdPart> parts;
    for (int r = 0; r < plate.size(); ++r) {
      const Seedling& sd = plate.seedling(r);
      const RootOutputs& out = run.root(static_cast<size_t>(r));
      const std::string result = out.finish(sd.model, plate.root(r), wall).result;
      const std::string parent = sd.parent >= 0 ? plate.seedling(sd.parent).name : "";
      table += plateTableRows(sd, parent, result, r == 0);
      roots.push_back(plateRootJson(sd, parent));
      parts.push_back({sd.name, "roots/" + sd.name, out.vtkEntries()});
    }
    run.write("plate.csv", table);
    // plate.pvd: every root's ParaView series as the parts of one (their snapshots are in plate coordinates)
    if (output.vtk) run.write("plate.pvd", partsPvdText(parts));

    const int n = static_cast<int>(spec.seedlings.size());
    Json j;
    j.str("rootsim_version", kVersion).str("scene", sc.model.name).str("status", "complete");
    j.str("kind", "plate").integer("seedlings", n).integer("laterals", plate.size() - n).integer("steps", steps);
    j.num("time_h", plate.last().timeH);
    j.num("plate_width_mm", spec.params.width / units::mm).num("plate_length_mm", spec.params.length / units::mm);
    j.integer("max_sweeps_per_step", maxSweeps).num("min_root_distance_r", minGap);
    j.array("roots", roots);
    j.num("wall_time_s", wall);
    run.write("summary.json", j.dump() + "\n");
    run.commit();
    return wall;
  });
}

}  // namespace rootsim
