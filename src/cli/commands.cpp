#include "commands.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numbers>

#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/theory.hpp"
#include "rootsim/version.hpp"

#ifdef ROOTSIM_HAVE_RENDER
#include "render_glue.hpp"
#endif

namespace fs = std::filesystem;

namespace rootsim::cli {

namespace {
double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
constexpr double kDeg = 180.0 / std::numbers::pi;

SceneInfo sceneInfo(const Model& m) {
  SceneInfo si;
  si.alphaDeg = m.env.plane.alpha * kDeg;
  si.beta = m.tropism.beta;
  si.gamma = m.tropism.gamma;
  si.rTau = m.tropism.rTau;
  si.radius = m.rod.radius;
  si.plate = m.env.plane.enabled;
  si.title = m.name;
  return si;
}

Json summaryJson(const Scene& sc, const Simulation& sim, double wall, long maxSub) {
  const Model& m = sc.model;
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
  if (m.growth.enabled) {
    const ShapeAnalysis a = analyseShape(m, sim.state());
    j.str("pattern", a.pattern)
        .num("wavelength_mm", a.peaks >= 3 ? a.wavelength * 1e3 : NAN)
        .num("amplitude_mm", a.peaks >= 2 ? a.amplitude * 1e3 : NAN)
        .integer("lateral_peaks", a.peaks)
        .num("skew_deg", a.skew * kDeg)
        .num("max_kappa_per_mm", a.maxKappa / 1e3)
        .num("theta_min_deg", a.thetaMin * kDeg)
        .num("theta_max_deg", a.thetaMax * kDeg);
    j.object("theory", theoryJson(theoryFor(m)));
  } else {
    const StepRecord& s = sim.last();
    j.num("residual_force_n", s.residualForce);
  }
  j.num("wall_time_s", wall);
  return j;
}
}  // namespace

Progress::Progress(int total, bool quiet, std::string what)
    : total_(std::max(total, 1)), quiet_(quiet), tty_(isatty(2) != 0), what_(std::move(what)), start_(now()) {}

void Progress::update(int done, const std::string& detail) {
  if (quiet_) return;
  const int pct = static_cast<int>(100.0 * done / total_);
  if (pct == lastPercent_ && !tty_) return;
  if (tty_ && pct == lastPercent_ && done % 10 != 0) return;
  lastPercent_ = pct;
  const double el = now() - start_;
  const double left = done > 0 ? el * (total_ - done) / done : 0.0;
  if (tty_) {
    const int w = 30, fill = w * done / total_;
    std::fprintf(stderr, "\r%s [%s%s] %3d%% %s  %.0f s left   ", what_.c_str(), std::string(fill, '#').c_str(),
                 std::string(w - fill, ' ').c_str(), pct, detail.c_str(), left);
  } else {
    std::fprintf(stderr, "%s %3d%% %s (%.0f s elapsed, %.0f s left)\n", what_.c_str(), pct, detail.c_str(), el, left);
  }
  std::fflush(stderr);
}

void Progress::finish(const std::string& detail) {
  if (quiet_) return;
  std::fprintf(stderr, "%s%s done: %s (%.1f s)\n", tty_ ? "\r" : "", what_.c_str(), detail.c_str(), now() - start_);
}

int runCommand(const RunOptions& o) {
  const Scene sc = loadScene(o.scene, o.sets);
  const Model& m = sc.model;
  const fs::path out = o.out.empty() ? fs::path("runs") / m.name : fs::path(o.out);
#ifndef ROOTSIM_HAVE_RENDER
  if (o.movie) throw SceneError("--movie: this rootsim was built without the renderer (ROOTSIM_BUILD_RENDER=OFF)");
#endif
  RunDir rd(out);
  try {
    rd.write("scene.toml", sc.resolvedToml);
    const double t0 = now();
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
    long maxSub = sim.last().substeps;
    const int steps = m.growth.enabled ? m.growth.steps : 0;
    Progress pr(steps, o.quiet || steps == 0, m.name);
    for (int k = 1; k <= steps; ++k) {
      const StepRecord& r = sim.growthStep();
      maxSub = std::max(maxSub, r.substeps);
      if (k % m.output.everySteps == 0 || k == steps) record();
      char buf[160];
      std::snprintf(buf, sizeof buf, "step %d/%d  t=%.1f h  L=%.2f mm  theta_tip=%.0f deg  %ld sub-steps", k, steps,
                    r.timeH, r.length * 1e3, r.thetaTip * kDeg, r.substeps);
      pr.update(k, buf);
    }
    ts.close();
    if (tr) tr->close();
    if (vtk) vtk->close();
    rd.write("shape.csv", shapeCsv(m, sim.state(), sim.strains()));
    const double wall = now() - t0;
    rd.write("summary.json", summaryJson(sc, sim, wall, maxSub).dump() + "\n");
    if (steps > 0) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%d steps, %ld sub-steps", steps, sim.totalSubsteps());
      pr.finish(buf);
    }
#ifdef ROOTSIM_HAVE_RENDER
    if (o.movie) renderRunMovie(w, sceneInfo(m), o.quiet);
#endif
    rd.commit();
  } catch (const std::exception& e) {
    rd.fail(e.what());
    throw;
  }
  if (!o.quiet) std::fprintf(stderr, "wrote %s\n", out.string().c_str());
  return 0;
}

int checkCommand(const CheckOptions& o) {
  const Scene sc = loadScene(o.scene, o.sets);
  std::cout << sc.resolvedToml << "\n# theory (MODEL.md section 9)\n";
  if (sc.model.growth.enabled) {
    std::cout << theoryJson(theoryFor(sc.model)).dump() << "\n";
  } else {
    std::cout << "# mechanics-only scene: no growth predictions\n";
  }
  std::cout << "# scene is valid\n";
  return 0;
}

int renderCommand(const RenderOptions& o) {
#ifdef ROOTSIM_HAVE_RENDER
  return renderRunCommand(o);
#else
  (void)o;
  throw SceneError("render: this rootsim was built without the renderer (ROOTSIM_BUILD_RENDER=OFF)");
#endif
}

}  // namespace rootsim::cli
