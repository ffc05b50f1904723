// One scene -> one run directory (used by `rootsim run` and by sweeps).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "rootsim/outputs.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/version.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;

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
    if (std::isnan(first) && std::abs(r.thetaTip) > 30.0 / kDeg && r.step > 0) first = r.timeH;
    if (std::isnan(vertical) && r.thetaTip >= 0.0 && r.step > 0)
      vertical = std::isfinite(prevTheta) && prevTheta < 0.0
                     ? prevTime + (r.timeH - prevTime) * (-prevTheta) / (r.thetaTip - prevTheta)
                     : r.timeH;
    prevTheta = r.thetaTip;
    prevTime = r.timeH;
  }
};

std::string csvNum(double x) {
  if (!std::isfinite(x)) return "";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", x);
  return b;
}
}  // namespace

namespace {
const std::string kMechanicsHeader = "scene,status,steps,time_h,length_mm,elements,theta_tip_deg,total_substeps";
}

const std::string& resultHeader(bool grows) {
  static const std::string h =
      "scene,status,steps,time_h,length_mm,elements,theta_tip_deg,total_substeps,pattern,wavelength_mm,"
      "amplitude_mm,amplitude_half_mm,lateral_peaks,skew_deg,max_kappa_per_mm,theta_min_deg,theta_max_deg,first_snap_or_turning_h,"
      "alpha_deg,beta,gamma,r_tau,sensing,effective_gain,T0_h,max_kappa_eq8_per_mm,wavelength_eq9_mm,"
      "amplitude_eq10_mm,alpha_s_to_w_eq12_deg,alpha_w_to_c_eq13_deg,omega_T0";
  return grows ? h : kMechanicsHeader;
}

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
    const int steps = m.growth.enabled ? m.growth.steps : 0;
    for (int k = 1; k <= steps; ++k) {
      const StepRecord& r = sim.growthStep();
      maxSub = std::max(maxSub, r.substeps);
      snap.see(r);
      if (k % m.output.everySteps == 0 || k == steps) record();
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
    j.integer("steps", sim.step()).num("time_h", r.timeH).num("length_mm", r.length * 1e3);
    j.integer("elements", r.elements).integer("total_substeps", sim.totalSubsteps());
    j.integer("max_substeps_per_step", maxSub);
    j.num("theta_tip_deg", r.thetaTip * kDeg);
    Json tip;
    tip.num("x_mm", r.tip.x() * 1e3).num("y_mm", r.tip.y() * 1e3).num("z_mm", r.tip.z() * 1e3);
    j.object("tip", tip);
    std::string header = kMechanicsHeader;
    std::string row = m.name + ",complete," + std::to_string(sim.step()) + "," + csvNum(r.timeH) + "," +
                      csvNum(r.length * 1e3) + "," + std::to_string(r.elements) + "," +
                      csvNum(r.thetaTip * kDeg) + "," + std::to_string(sim.totalSubsteps());
    if (m.growth.enabled) {
      const ShapeAnalysis a = analyseShape(m, sim.state());
      const Theory t = theoryFor(m);
      const double lambda = a.peaks >= 3 ? a.wavelength * 1e3 : NAN;
      // A: the peak-to-peak excursion (MODEL.md section 8), and half of it beside it
      const double amp = a.peaks >= 2 ? a.amplitude * 1e3 : NAN;
      const double ampHalf = a.peaks >= 2 ? a.amplitudeHalf * 1e3 : NAN;
      j.str("pattern", a.pattern)
          .num("wavelength_mm", lambda)
          .num("amplitude_mm", amp)
          .num("amplitude_half_mm", ampHalf)
          .integer("lateral_peaks", a.peaks)
          .num("skew_deg", a.skew * kDeg)
          .num("max_kappa_per_mm", a.maxKappa / 1e3)
          .num("theta_min_deg", a.thetaMin * kDeg)
          .num("theta_max_deg", a.thetaMax * kDeg)
          .num(m.env.plane.enabled ? "first_snap_h" : "turning_time_h", m.env.plane.enabled ? snap.first : snap.vertical);
      j.object("theory", theoryJson(t));
      header = resultHeader(true);
      row += "," + a.pattern + "," + csvNum(lambda) + "," + csvNum(amp) + "," + csvNum(ampHalf) + "," + std::to_string(a.peaks) + "," +
             csvNum(a.skew * kDeg) + "," + csvNum(a.maxKappa / 1e3) + "," + csvNum(a.thetaMin * kDeg) + "," +
             csvNum(a.thetaMax * kDeg) + "," + csvNum(m.env.plane.enabled ? snap.first : snap.vertical) + "," + csvNum(m.env.plane.alpha * kDeg) + "," +
             csvNum(m.tropism.beta) + "," + csvNum(m.tropism.gamma) + "," + csvNum(m.tropism.rTau) + "," +
             (m.tropism.sensing == Sensing::Apical ? "apical" : "local") + "," + csvNum(t.effectiveGain) + "," +
             csvNum(t.T0 / 3600) + "," + csvNum(t.maxKappa / 1e3) + "," + csvNum(t.wavelength * 1e3) + "," +
             csvNum(t.amplitude * 1e3) + "," + csvNum(t.alphaStraightToWave * kDeg) + "," +
             csvNum(t.alphaWaveToCoil * kDeg) + "," + csvNum(t.omegaT0);
    } else {
      j.num("residual_force_n", r.residualForce);
    }
    j.num("wall_time_s", wall);
    rd.write("summary.json", j.dump() + "\n");
    rd.write("result.csv", header + "\n" + row + "\n");
    rd.commit();
  } catch (const std::exception& e) {
    rd.fail(e.what());
    throw;
  }
  return now() - t0;
}

}  // namespace rootsim
