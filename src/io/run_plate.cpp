// The files a plate run writes of itself (run_plate.hpp; docs/plate.md, Outputs): its time series, and at
// the end each root's folder finished, plate.csv, plate.pvd and the plate's summary.json. The run itself
// (its directory, roots' folders, steps, checkpoints, --resume and failures) is runSceneToDir's, the same
// for a plate and a scene of one root.
#include "run_plate.hpp"

#include <cmath>
#include <vector>

#include "rootsim/csv.hpp"
#include "rootsim/json.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"
#include "rootsim/version.hpp"
#include "rootsim/vtk.hpp"

namespace rootsim::detail {

// the plate's time series: one row per output step
std::string plateSeriesHeader() { return "step,time_h,touching_pairs,min_gap_over_contact,sweeps\n"; }
std::string plateSeriesRow(const PlateStepRecord& r) {
  return std::to_string(r.step) + "," + shortestNumber(r.timeH) + "," + std::to_string(r.touchingPairs) + "," +
         (std::isnan(r.minGap) ? std::string("") : shortestNumber(r.minGap)) + "," + std::to_string(r.sweeps) + "\n";
}

namespace {
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

void finishPlate(RunOutputs& run, const Scene& sc, const PlateSimulation& plate, const RunAccumulators& acc,
                 double wall) {
  const PlateSpec& spec = sc.plate;
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
  if (sc.output.vtk) run.write("plate.pvd", partsPvdText(parts));

  const int n = static_cast<int>(spec.seedlings.size());
  const int steps = sc.model.growth.enabled ? sc.model.growth.steps : 0;
  Json j;
  j.str("rootsim_version", kVersion).str("scene", sc.model.name).str("status", "complete");
  j.str("kind", "plate").integer("seedlings", n).integer("laterals", plate.size() - n).integer("steps", steps);
  j.num("time_h", plate.last().timeH);
  j.num("plate_width_mm", spec.params.width / units::mm).num("plate_length_mm", spec.params.length / units::mm);
  j.integer("max_sweeps_per_step", acc.maxSweeps).num("min_root_distance_r", acc.minGap);
  j.array("roots", roots);
  j.num("wall_time_s", wall);
  run.write("summary.json", j.dump() + "\n");
}

}  // namespace rootsim::detail
