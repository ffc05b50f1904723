// One growing root's folder (root_outputs.hpp): its streams and watch, continued from a checkpoint, and
// the files it writes last
#include "root_outputs.hpp"

#include <optional>

#include "rootsim/json.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/units.hpp"
#include "rootsim/version.hpp"
#include "run_resume.hpp"

namespace fs = std::filesystem;

namespace rootsim::detail {

namespace {
// the folder's leftovers of a killed run's atomic writes go before its streams are continued
const fs::path& cleaned(const fs::path& dir, bool resumed) {
  if (resumed) removeStaleTemps(dir, kRootStreams);
  return dir;
}
}  // namespace

RootOutputs::RootOutputs(fs::path dir, const Model& m, const OutputParams& o, bool ownFolder, const Vec3& vtkOffset,
                         const PlateRootRun* at)
    : dir_(std::move(dir)),
      ownFolder_(ownFolder),
      streams_(cleaned(dir_, at != nullptr), m, o, at ? &at->writers : nullptr, vtkOffset),
      watch_(at ? at->watch : RunWatch{}) {}

void RootOutputs::close() {
  vtkEntries_ = streams_.positions().vtkEntries;
  streams_.close();
}

RootOutputs::Final RootOutputs::finish(const Model& m, const Simulation& sim, double wall) const {
  const RunWatch& watch = watch_;
  Final f;
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
  writeFileAtomic(dir_ / "shape.csv", f.shape);
  writeFileAtomic(dir_ / "summary.json", f.summary);
  writeFileAtomic(dir_ / "result.csv", f.result);
  if (ownFolder_) markRunFolder(dir_);
  return f;
}

}  // namespace rootsim::detail
