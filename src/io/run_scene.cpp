// One scene -> one run directory (used by `rootsim run` and by sweeps).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include <optional>

#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/results.hpp"
#include "rootsim/units.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/version.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// first time the tip leaves the downhill direction by more than 30 degrees (the first sideways snap) [h]
// and, for a free organ (theta_tip measured from gravity, starting at -alpha), the first time the tip
// reaches the vertical: the measured turning time of Eq. 7 [h], interpolated linearly in theta between
// the two growth steps around the crossing (a growth step is 0.05 h; the turning time can be < 1 h)
struct SnapWatch {
  double first = NAN, vertical = NAN;
  double prevTheta = NAN, prevTime = NAN;
  void see(const StepRecord& r) {
    if (std::isnan(first) && std::abs(r.thetaTip) > 30.0 * units::deg && r.step > 0) first = r.timeH;
    if (std::isnan(vertical) && r.thetaTip >= 0.0 && r.step > 0)
      vertical = std::isfinite(prevTheta) && prevTheta < 0.0
                     ? prevTime + (r.timeH - prevTime) * (-prevTheta) / (r.thetaTip - prevTheta)
                     : r.timeH;
    prevTheta = r.thetaTip;
    prevTime = r.timeH;
  }
};

}  // namespace

double runSceneToDir(const Scene& sc, const std::string& outDir, const RunDirOptions& dirOptions,
                     const std::function<void(const StepRecord&, int total)>& progress) {
  const Model& m = sc.model;
  RunDir rd(outDir, dirOptions);
  const double t0 = now();
  try {
    rd.write("scene.toml", sc.resolvedToml);
    Simulation sim(m);
    const fs::path w = rd.work();
    TimeseriesWriter ts(w / "timeseries.csv");
    std::unique_ptr<TrajectoryWriter> tr;
    std::unique_ptr<VtkSeriesWriter> vtk;
    if (m.output.trajectory) tr = std::make_unique<TrajectoryWriter>(w / "trajectory.csv");
    if (m.output.vtk) vtk = std::make_unique<VtkSeriesWriter>(w);
    auto record = [&]() {
      ts.add(sim.last());
      if (tr || vtk) {
        const Snapshot sn = sim.snapshot();
        if (tr) tr->add(sn);
        if (vtk) vtk->add(sn);
      }
    };
    record();
    SnapWatch snap;
    snap.see(sim.last());  // the initial state: only remembered, as the step before the first
    long maxSub = sim.last().substeps;
    int maxSelfContacts = sim.last().selfContacts;
    double minSelfDistance = sim.last().minSelfDistance;  // NaN: never within 3R
    const int steps = m.growth.enabled ? m.growth.steps : 0;
    for (int k = 1; k <= steps; ++k) {
      const StepRecord& r = sim.growthStep();
      maxSub = std::max(maxSub, r.substeps);
      maxSelfContacts = std::max(maxSelfContacts, r.selfContacts);
      if (std::isnan(minSelfDistance) || r.minSelfDistance < minSelfDistance) minSelfDistance = r.minSelfDistance;
      snap.see(r);
      try {
        if (k % m.output.everySteps == 0 || k == steps) record();
      } catch (const RunError& e) {
        throw RunError(std::string(e.what()) + " (at growth step " + std::to_string(k) + " of " +
                       std::to_string(steps) + ")");
      }
      if (progress) progress(r, steps);
    }
    ts.close();
    if (tr) tr->close();
    if (vtk) vtk->close();
    rd.write("shape.csv", shapeCsv(m, sim.state(), sim.strains()));
    const double wall = now() - t0;

    // summary.json and the one-row result.csv (what sweep tables are made of)
    const StepRecord& r = sim.last();
    Json j;
    j.str("rootsim_version", kVersion).str("scene", m.name).str("status", "complete");
    j.integer("steps", sim.step()).num("time_h", r.timeH).num("length_mm", r.length / units::mm);
    j.integer("elements", r.elements).integer("total_substeps", sim.totalSubsteps());
    j.integer("max_substeps_per_step", maxSub);
    j.num("theta_tip_deg", r.thetaTip / units::deg);
    Json tip;
    tip.num("x_mm", r.tip.x() / units::mm).num("y_mm", r.tip.y() / units::mm).num("z_mm", r.tip.z() / units::mm);
    j.object("tip", tip);
    // contact (MODEL.md section 11): zero when self-contact, friction and obstacles are off
    Json contact;
    contact.integer("self_contacts", r.selfContacts)
        .integer("max_self_contacts", maxSelfContacts)
        .num("min_self_distance_r", minSelfDistance)
        .integer("obstacle_contacts", r.obstacleContacts)
        .integer("slip_events", r.slipEvents)
        .num("frictional_work_j", r.frictionWork);
    j.object("contact", contact);
    const double snapOrTurn = m.env.plane.enabled ? snap.first : snap.vertical;
    std::optional<ShapeAnalysis> shape;
    if (m.growth.enabled) shape = analyseShape(m, sim.state());
    const RunResult res = makeResult(m, sim, shape ? &*shape : nullptr, snapOrTurn);
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
    rd.write("summary.json", j.dump() + "\n");
    rd.write("result.csv", resultCsv(res));
    rd.commit();
  } catch (const RunInterrupted&) {
    throw;  // stopped on purpose (a progress callback threw it): DIR.partial stays, like a killed run
  } catch (const std::exception& e) {
    rd.fail(e.what());
    throw;
  }
  return now() - t0;
}

}  // namespace rootsim
