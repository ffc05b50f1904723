// A plate scene -> one run directory (docs/plate.md, Outputs): roots/NAME per root, each a run directory
// of that root alone (its own frame), and the plate's summary, time series and ParaView series; checkpoints
// and --resume as a run of one root's (run_scene.cpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <set>

#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/json.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/checkpoint.hpp"
#include "rootsim/units.hpp"
#include "rootsim/version.hpp"
#include "root_outputs.hpp"
#include "plate_scene.hpp"
#include "scene_schema.hpp"

namespace fs = std::filesystem;

namespace rootsim {

using namespace detail;

namespace {

// the plate's time series: one row per output step
std::string plateSeriesHeader() { return "step,time_h,touching_pairs,min_gap_over_contact,sweeps\n"; }
std::string plateSeriesRow(const PlateStepRecord& r) {
  return std::to_string(r.step) + "," + formatNumber(r.timeH, false) + "," + std::to_string(r.touchingPairs) + "," +
         (std::isnan(r.minGap) ? std::string("") : formatNumber(r.minGap, false)) + "," + std::to_string(r.sweeps) + "\n";
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
  const PartialRun partial =
      dirOptions.resume ? resumePlan(sc, outDir, dirOptions.force,
                                     [&](const fs::path& file) {
                                       ck.reset();
                                       ck = readPlateCheckpoint(file, seedlingNames);
                                       checkSceneHash(file, ck->sceneHash, hash);
                                       const fs::path w = file.parent_path();
                                       checkStreamLength(w / "plate_timeseries.csv", ck->acc.seriesBytes);
                                       const PlateCarry& pc = ck->plate;
                                       std::vector<std::string> names = seedlingNames;
                                       for (const LateralBirth& b : pc.laterals)
                                         names.push_back(lateralName(names[static_cast<size_t>(b.parent)], b.site));
                                       for (size_t r = 0; r < names.size(); ++r)
                                         checkStreamLengths(w / "roots" / names[r], sc.model, ck->roots[r].writers);
                                     })
                        : PartialRun::Refuse;
  if (partial != PartialRun::Continue) ck.reset();
  RunDir rd(outDir, dirOptions, partial);
  const int steps = sc.model.growth.enabled ? sc.model.growth.steps : 0;
  noteResume(dirOptions, rd, partial, ck ? ck->step : 0, steps);
  const double t0 = now();
  try {
    const fs::path w = rd.work();
    std::unique_ptr<PlateSimulation> platep;
    std::unique_ptr<AtomicFile> seriesp;
    std::vector<fs::path> dirs;
    std::vector<std::unique_ptr<RootStreams>> out;
    std::vector<RunWatch> watch;
    int maxSweeps = 1;
    double minGap = std::numeric_limits<double>::quiet_NaN();
    double wallBefore = 0;  // wall time of earlier attempts (resumed) [s]
    int first = 1;          // the first growth step this process runs
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
      removeStaleTemps(w, {"plate_timeseries.csv"});
      for (int r = 0; r < platep->size(); ++r) {
        const fs::path d = w / "roots" / platep->seedling(r).name;
        removeStaleTemps(d, kRootStreams);
        dirs.push_back(d);
        const PlateRootRun& rr = ck->roots[static_cast<size_t>(r)];
        out.push_back(std::make_unique<RootStreams>(d, platep->seedling(r).model, &rr.writers, platep->offset(r)));
        watch.push_back(rr.watch);
      }
      seriesp = std::make_unique<AtomicFile>(w / "plate_timeseries.csv", ck->acc.seriesBytes);
      maxSweeps = ck->acc.maxSweeps;
      minGap = ck->acc.minGap;
      wallBefore = ck->acc.wallBefore;
      first = ck->step + 1;
    } else {
      rd.write("scene.toml", sc.resolvedToml);
      fs::create_directories(w / "roots");
      for (size_t r = 0; r < spec.seedlings.size(); ++r) {
        const fs::path d = w / "roots" / spec.seedlings[r].name;
        fs::create_directories(d);
        markRunFolder(d);  // first, as every run directory's (again at the end, with its files listed)
        writeFileAtomic(d / "scene.toml", sc.rootToml[r]);
        dirs.push_back(d);
      }
      platep = std::make_unique<PlateSimulation>(spec.params, spec.seedlings);
      for (int r = 0; r < platep->size(); ++r)
        out.push_back(std::make_unique<RootStreams>(dirs[static_cast<size_t>(r)], platep->seedling(r).model, nullptr,
                                                    platep->offset(r)));
      seriesp = std::make_unique<AtomicFile>(w / "plate_timeseries.csv");
      seriesp->stream() << plateSeriesHeader();
    }
    PlateSimulation& plate = *platep;
    AtomicFile& series = *seriesp;
    const int n = static_cast<int>(spec.seedlings.size());
    auto record = [&] {
      for (int r = 0; r < plate.size(); ++r) out[static_cast<size_t>(r)]->add(plate.root(r));
      series.stream() << plateSeriesRow(plate.last());
      series.flush();
    };
    if (!ck) {
      record();
      for (int r = 0; r < plate.size(); ++r) watch.emplace_back().start(plate.root(r).last());
    }
    // a lateral root that emerged: its folder, its scene (the plate with it alone), its streams (its first
    // snapshot at the next output step, so that every root's snapshots fall on the plate's output steps)
    auto open = [&](int r) {
      const Seedling& sd = plate.seedling(r);
      const fs::path d = w / "roots" / sd.name;
      fs::create_directories(d);
      markRunFolder(d);
      writeFileAtomic(d / "scene.toml", spec.headToml + plateTableToml(spec.params) + seedlingToml(sd, spec.base));
      dirs.push_back(d);
      out.push_back(std::make_unique<RootStreams>(d, sd.model, nullptr, plate.offset(r)));
      watch.emplace_back();
      watch.back().start(plate.root(r).last());
    };
    // a checkpoint: the plate's carry, each root's accumulators and where its files stand, the plate's own
    auto checkpoint = [&](int k) {
      PlateCheckpoint c;
      c.sceneHash = hash;
      c.step = k;
      c.plate = plate.carry();
      for (int r = 0; r < plate.size(); ++r)
        c.roots.push_back({watch[static_cast<size_t>(r)], out[static_cast<size_t>(r)]->positions()});
      c.acc = {maxSweeps, minGap, wallBefore + (now() - t0), series.size()};
      writePlateCheckpoint(w / kCheckpointFile, c);
    };
    const Model m0 = plate.seedling(0).model;  // a copy: the plate's roots grow as laterals emerge
    runGrowthSteps(first, steps, m0.output.checkpointEvery, RunSteps{
        [&](int) {
          const PlateStepRecord& pr = plate.growthStep();
          maxSweeps = std::max(maxSweeps, pr.sweeps);
          if (!std::isnan(pr.minGap) && !(pr.minGap >= minGap)) minGap = pr.minGap;
        },
        [&](int k) {
          for (int r : plate.emerged()) open(r);
          for (int r = 0; r < plate.size(); ++r)
            if (std::find(plate.emerged().begin(), plate.emerged().end(), r) == plate.emerged().end())
              watch[static_cast<size_t>(r)].see(plate.root(r).last());
          if (k % m0.output.everySteps == 0 || k == steps) record();
        },
        checkpoint,
        [&](int) {
          if (progress) progress(plate.root(0).last(), steps);
        },
        [&] {
          for (auto& o : out) o->closeQuietly();
          try {
            series.close();
          } catch (const std::exception&) {
            // a series that cannot close (the disk that failed the run) keeps nothing; the roots' streams still do
          }
        }});
    std::vector<std::vector<std::pair<double, std::string>>> vtkEntries;
    for (auto& o : out) {
      vtkEntries.push_back(o->positions().vtkEntries);
      o->close();
    }
    series.close();
    // the finished run holds no checkpoint: it is the same as a plate never interrupted
    std::error_code ec;
    fs::remove(w / kCheckpointFile, ec);
    const double wall = wallBefore + (now() - t0);

    // each root's folder is a finished run directory of that root alone
    std::string table;
    std::vector<Json> roots;
    for (int r = 0; r < plate.size(); ++r) {
      const Seedling& sd = plate.seedling(r);
      const fs::path& d = dirs[static_cast<size_t>(r)];
      const RootFinal f = finishRoot(sd.model, plate.root(r), watch[static_cast<size_t>(r)], wall);
      writeFileAtomic(d / "shape.csv", f.shape);
      writeFileAtomic(d / "summary.json", f.summary);
      writeFileAtomic(d / "result.csv", f.result);
      markRunFolder(d);
      // plate.csv: the seedling, then its result.csv row
      std::string overrides;
      for (const std::string& o : sd.overrides) overrides += (overrides.empty() ? "" : ";") + o;
      const std::string res = f.result;
      const auto nl = res.find('\n');
      if (r == 0)
        table += "root,genotype,parent,order,emerged_h,position_lateral_mm,position_downhill_mm,angle_deg,set_point_deg,overrides," +
                 res.substr(0, nl) + "\n";
      std::string row = res.substr(nl + 1);
      if (!row.empty() && row.back() == '\n') row.pop_back();
      const std::string parent = sd.parent >= 0 ? plate.seedling(sd.parent).name : "";
      table += csvField(sd.name) + "," + csvField(sd.genotype) + "," + csvField(parent) + "," + std::to_string(sd.order) + "," +
               formatNumber(sd.emergedH, false) + "," + formatNumber(sd.position.x() / units::mm, false) + "," +
               formatNumber(sd.position.y() / units::mm, false) + "," + formatNumber(sd.model.initial.angle / units::deg, false) +
               "," + formatNumber(sd.model.tropism.setPoint / units::deg, false) + "," + csvField(overrides) + "," + row + "\n";
      Json j;
      j.str("name", sd.name).str("genotype", sd.genotype).str("parent", parent).integer("order", sd.order);
      j.num("emerged_h", sd.emergedH).num("set_point_deg", sd.model.tropism.setPoint / units::deg);
      j.str("folder", "roots/" + sd.name);
      j.num("position_lateral_mm", sd.position.x() / units::mm).num("position_downhill_mm", sd.position.y() / units::mm);
      j.num("angle_deg", sd.model.initial.angle / units::deg).str("overrides", overrides);
      roots.push_back(j);
    }
    rd.write("plate.csv", table);

    // plate.pvd: every root's ParaView series as the parts of one (their snapshots are in plate coordinates)
    if (m0.output.vtk) {
      std::string pvd = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
      for (int r = 0; r < plate.size(); ++r) {
        const std::string& name = plate.seedling(r).name;
        for (const auto& [t, file] : vtkEntries[static_cast<size_t>(r)])
          pvd += "  <DataSet timestep=\"" + formatNumber(t, false) + "\" part=\"" + std::to_string(r) + "\" name=\"" + name +
                 "\" file=\"roots/" + name + "/" + file + "\"/>\n";
      }
      pvd += "</Collection>\n</VTKFile>\n";
      rd.write("plate.pvd", pvd);
    }

    Json j;
    j.str("rootsim_version", kVersion).str("scene", sc.model.name).str("status", "complete");
    j.str("kind", "plate").integer("seedlings", n).integer("laterals", plate.size() - n).integer("steps", steps);
    j.num("time_h", plate.last().timeH);
    j.num("plate_width_mm", spec.params.width / units::mm).num("plate_length_mm", spec.params.length / units::mm);
    j.integer("max_sweeps_per_step", maxSweeps).num("min_root_distance_r", minGap);
    j.array("roots", roots);
    j.num("wall_time_s", wall);
    rd.write("summary.json", j.dump() + "\n");
    rd.commit();
    return wall;
  } catch (const RunInterrupted&) {
    throw;
  } catch (const std::exception& e) {
    rd.fail(failureText(e, "the plate run of " + sc.model.name + " into " + rd.work().string()));
    throw;
  }
}

}  // namespace rootsim
