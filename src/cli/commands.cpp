#include "commands.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <numbers>
#include <tuple>

#include "rootsim/errors.hpp"
#include "rootsim/figure.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/stability.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/sweep.hpp"
#include "rootsim/theory.hpp"
#include "rootsim/version.hpp"
#include "rootsim/write_rule.hpp"

#ifdef ROOTSIM_HAVE_RENDER
#include "rootsim/units.hpp"
#endif

namespace fs = std::filesystem;

namespace rootsim::cli {

namespace {
double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
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
  // validate first so a bad scene exits 2 before anything is written
  return runLoaded(loadScene(o.scene, o.sets), o, nullptr);
}

int runLoaded(const Scene& sc, const RunOptions& o, const std::function<void(const StepRecord&, int)>& onStep) {
  const fs::path out = normaliseOutDir(o.out.empty() ? (fs::path("runs") / sc.model.name).string() : o.out);
  // contradictory options are refused before the run, not after it
#ifndef ROOTSIM_HAVE_RENDER
  if (o.movie) throw SceneError("--movie: this rootsim was built without the renderer (ROOTSIM_BUILD_RENDER=OFF)");
#endif
#ifdef ROOTSIM_HAVE_RENDER
  // the movie's flags are checked before the run, so a bad one writes nothing
  const app::MovieLook look = app::parseLook(o.look);
  if (o.movie && look.shadows && !sc.model.env.plane.enabled)
    throw SceneError("--shadows: " + std::string(sc.path) + " has no plate to cast them on (plane.enabled = false)");
  if (o.movie && (look.camera == CameraMode::Follow || look.inset) && sc.model.growth.enabled) {
    // the plate a fit view can show: at most twice the longest root the run can grow (the zone grows
    // at eps0 over at most max(L0, Lgz)) plus margins [mm]
    const Model& m = sc.model;
    const double lMax = m.initial.length + m.growth.rate * std::max(m.initial.length, m.growth.zoneLength) *
                                               m.growth.steps * m.growth.stepTime;
    app::checkFieldAgainstPlate(look, 2e3 * lMax + 2.0);
  }
  if (o.movie) {
    // the movie shows every snapshot: counted before the run, not after it
    const double snapshots = (sc.model.growth.enabled ? sc.model.growth.steps : 0) / std::max(1, sc.output.everySteps) + 1.0;
    checkCount("--movie: " + sc.path + " (growth.steps / output.every_steps + 1 snapshots)", snapshots, caps::kMovieFrames,
               "frames", "caps::kMovieFrames: each frame holds a copy of its snapshot; raise output.every_steps");
  }
  if (!o.movie && (o.look.camera != "fit" || o.look.inset || o.look.fieldGiven || o.look.colorBy != "none" ||
                   !o.look.plot.empty() || o.look.shadows))
    throw SceneError("--camera, --inset, --field-mm, --color-by, --plot and --shadows shape the movie; add --movie");
#endif
  if (o.movie && !sc.output.trajectory)
    throw SceneError("--movie needs the trajectory, but output.trajectory = false (" +
                     std::string(sc.path) + "); drop one of them");
  const int steps = sc.model.growth.enabled ? sc.model.growth.steps : 0;
  // the run directory is locked from here to the end (the movie too): a second process is refused
  const OutputLock lock = lockOutput(out, "--out");
  if (o.resume) {
    // a complete run of this scene: nothing to continue; of another scene: refused
    fs::path partial = out;
    partial += ".partial";
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(partial, ec)) && fs::exists(fs::symlink_status(out, ec))) {
      if (std::string why = whyNotOurs(out, runFolder()); !why.empty()) throw SceneError("--out " + out.string() + ": " + why);
      std::ifstream in(out / "scene.toml", std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (!in.is_open() || text != sc.resolvedToml)
        throw SceneError("--resume: " + out.string() + " holds a complete run of another scene (its scene.toml differs from " +
                         sc.path + " with these --set values)");
      std::fprintf(stderr, "%s is complete: nothing to resume\n", out.string().c_str());
#ifdef ROOTSIM_HAVE_RENDER
      if (o.movie && !fs::exists(out / "movie.mp4", ec)) app::renderRunMovie(out, sc.model, o.quiet, look);
#endif
      return 0;
    }
  }
  RunDirOptions ro;
  ro.force = o.force;
  ro.resume = o.resume;
  ro.note = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  // the run directory may not be (or contain) the scene file or the folder we are working in
  if (!sc.path.empty()) ro.protect.push_back(fs::path(sc.path));
  ro.protect.push_back(fs::current_path());
  Progress pr(steps, o.quiet || steps == 0, sc.model.name);
  runSceneToDir(sc, out.string(), ro, [&](const StepRecord& r, int n) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "step %d/%d  t=%.1f h  L=%.2f mm  theta_tip=%.0f deg  %ld sub-steps", r.step, n,
                  r.timeH, r.length / units::mm, r.thetaTip / units::deg, r.substeps);
    pr.update(r.step, buf);
    if (onStep) onStep(r, n);
  });
  if (steps > 0) pr.finish(std::to_string(steps) + " steps");
#ifdef ROOTSIM_HAVE_RENDER
  if (o.movie) app::renderRunMovie(out, sc.model, o.quiet, look);
#endif
  if (!o.quiet) std::fprintf(stderr, "wrote %s\n", out.string().c_str());
  return 0;
}

int sweepCommand(const SweepCliOptions& o) {
  const SweepPlan plan = loadSweep(o.sweep);
  SweepOptions so;
  so.jobs = o.jobs;
  if (!o.shard.empty()) std::tie(so.shard, so.shards) = parseShard(o.shard);
  so.out = o.out.empty() ? (fs::path("runs") / fs::path(o.sweep).stem()).string() : o.out;
  so.quiet = o.quiet;
  so.force = o.force;
  so.inputs = {fs::path(o.sweep), fs::path(plan.scenePath)};
  if (!o.quiet)
    std::fprintf(stderr, "sweep %s: %zu points, shard %d/%d, %d jobs -> %s\n", o.sweep.c_str(), plan.points.size(),
                 so.shard, so.shards, so.jobs, so.out.c_str());
  const SweepResult r = runSweep(plan, so, [&](const std::string& line) {
    if (!o.quiet) std::fprintf(stderr, "%s\n", line.c_str());
  });
  if (!o.quiet)
    std::fprintf(stderr, "sweep done: %d ran, %d already complete, %d failed; table: %s/table.csv\n", r.ran,
                 r.skipped, r.failed, so.out.c_str());
  return r.failed > 0 ? 1 : 0;
}


int figureCommand(const FigureCliOptions& o) {
  FigureOptions fo;
  fo.quick = o.quick;
  fo.out = o.out;
  fo.jobs = o.jobs;
  fo.force = o.force;
  fo.quiet = o.quiet;
  fo.dpi = o.dpi;
  fo.widthMm = o.widthMm;
  fo.titles = !o.noTitle;
  const double t0 = now();
  makeFigure(o.name, fo, [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
  if (!o.quiet) std::fprintf(stderr, "figure %s: done in %.1f s -> %s\n", o.name.c_str(), now() - t0, o.out.c_str());
  return 0;
}

int modesCommand(const ModesOptions& o) {
  fs::path dir = normaliseOutDir(o.runDir);
  if (const std::string why = whyUnfinished(dir); !why.empty()) throw SceneError(o.runDir + ": " + why);
  // a plate's root (docs/plate.md): PLATE_RUN --root NAME, or its folder PLATE_RUN/roots/NAME; the whole
  // plate is repeated (its roots touch, its laterals emerge) and the root's own folder receives the files
  fs::path plateDir;
  std::string rootName = o.root;
  auto plateRun = [](const fs::path& d) {
    return fs::is_directory(d / "roots") && fs::is_regular_file(d / "scene.toml") &&
           loadScene((d / "scene.toml").string()).isPlate();
  };
  const fs::path abs = fs::absolute(dir).lexically_normal();
  const fs::path up = abs.parent_path();
  if (plateRun(dir)) {
    plateDir = dir;
    if (rootName.empty())
      throw SceneError(o.runDir + ": a plate's run; give --root NAME (a root of its roots/ folder) or pass roots/NAME");
    dir = dir / "roots" / rootName;
    if (!fs::is_directory(dir)) throw SceneError("--root " + rootName + ": " + o.runDir + " has no root folder roots/" + rootName);
  } else if (up.filename() == "roots" && plateRun(up.parent_path())) {
    if (!rootName.empty() && rootName != abs.filename().string())
      throw SceneError("--root " + rootName + ": " + o.runDir + " is the folder of root " + abs.filename().string());
    plateDir = up.parent_path();
    rootName = abs.filename().string();
  } else if (!rootName.empty()) {
    throw SceneError("--root " + rootName + ": " + o.runDir + " is a run of one root (--root picks a root of a plate's run)");
  }
  // the run directory receives modes.csv and modes.vtp, nothing else; it is locked while they are written
  const OutputLock lock = lockOutput(dir, "modes");
  if (!fs::is_regular_file(dir / "scene.toml") || !fs::is_regular_file(dir / "summary.json"))
    throw SceneError(o.runDir + ": not a complete run directory (no scene.toml and summary.json)");
  if (const std::string why = whyNotOurs(dir, runFolder()); !why.empty()) throw SceneError(dir.string() + ": " + why);
  WriteRule rule;
  rule.force = o.force;
  rule.inputs = {WriteInput{dir, {"modes.csv", "modes.vtp"}}};
  claimFile(dir / "modes.csv", rule, "modes", OutputFormat::InFolder);
  claimFile(dir / "modes.vtp", rule, "modes", OutputFormat::InFolder);
  // the final state is not stored; the run is repeated from its resolved scene (same scene, same bytes) as
  // `run` grew it: a plate, a root alone being a plate of one
  const Scene sc = loadScene(((plateDir.empty() ? dir : plateDir) / "scene.toml").string());
  const PlateSpec spec = plateDir.empty() ? plateOfOne(singleRootModel(sc, "modes: " + o.runDir)) : sc.plate;
  PlateSimulation plate(spec.params, spec.seedlings);
  const int steps = sc.model.growth.enabled ? sc.model.growth.steps : 0;
  Progress pr(steps, o.quiet || steps == 0, "modes: repeating " + sc.model.name);
  for (int k = 1; k <= steps; ++k) {
    plate.growthStep();
    pr.update(k, "");
  }
  const Simulation* sim = plateDir.empty() ? &plate.root(0) : nullptr;
  for (int r = 0; !plateDir.empty() && r < plate.size(); ++r)
    if (plate.seedling(r).name == rootName) sim = &plate.root(r);
  if (!sim)
    throw SceneError(o.runDir + ": repeating the plate from scene.toml grows no root " + rootName +
                     " (written by another rootsim version?)");
  // the repeated run must end where the stored one did
  std::ifstream in(dir / "shape.csv");
  std::string header, last, line;
  std::getline(in, header);
  while (std::getline(in, line)) last = line;
  const std::string now = shapeCsv(sim->model(), sim->state(), sim->strains());
  if (now.empty() || now.find(last) == std::string::npos)
    throw SceneError(dir.string() + ": repeating the run from scene.toml does not reproduce shape.csv (written by "
                     "another rootsim version?)");
  // a plate's root: its own stiffness, the other roots held where they are (their contacts are not in it)
  const StiffnessModes m = softestModes(sim->model().rod, sim->model().env, sim->state(), o.count);
  writeFileAtomic(dir / "modes.csv", modesCsv(sim->state(), m));
  writeFileAtomic(dir / "modes.vtp", modesVtp(sim->state(), m));
  recordWritten({dir / "modes.csv", dir / "modes.vtp"});
  if (!o.quiet) {
    std::fprintf(stderr, "%s: %d modes, stiffness eigenvalues [N/m]:", dir.c_str(), static_cast<int>(m.modes.size()));
    for (long q = 0; q < m.eigenvalues.size(); ++q) std::fprintf(stderr, " %.4g", m.eigenvalues[q]);
    std::fprintf(stderr, "\nwrote %s and %s\n", (dir / "modes.csv").c_str(), (dir / "modes.vtp").c_str());
  }
  return 0;
}

int checkCommand(const CheckOptions& o) {
  const Scene sc = loadScene(o.scene, o.sets);
  std::cout << sc.resolvedToml << "\n# theory (docs/model.md, Theory)\n";
  if (sc.model.growth.enabled) {
    std::cout << theoryJson(theoryFor(sc.model)).dump() << "\n";
  } else {
    std::cout << "# mechanics-only scene: no growth predictions\n";
  }
  std::cout << "# scene is valid\n";
  return 0;
}

int montageCommand(const app::MontageOptions& o) {
#ifdef ROOTSIM_HAVE_RENDER
  return app::montageRunsCommand(o);
#else
  (void)o;
  throw SceneError("montage: this rootsim was built without the renderer (ROOTSIM_BUILD_RENDER=OFF)");
#endif
}

int renderCommand(const app::RenderOptions& o) {
#ifdef ROOTSIM_HAVE_RENDER
  return app::renderRunCommand(o);
#else
  (void)o;
  throw SceneError("render: this rootsim was built without the renderer (ROOTSIM_BUILD_RENDER=OFF)");
#endif
}

int exportCommand(const app::ExportOptions& o) {
#ifdef ROOTSIM_HAVE_RENDER
  return app::exportRunCommand(o);
#else
  (void)o;
  throw SceneError("export: this rootsim was built without the renderer and the app library (ROOTSIM_BUILD_RENDER=OFF)");
#endif
}

int analyzeCommand(const app::AnalyzeOptions& o) {
  return app::analyzeCommand(o);
}

int compareCommand(const app::CompareOptions& o) {
  return app::compareCommand(o);
}

int fitCommand(const app::FitOptions& o) {
  return app::fitCommand(o);
}

}  // namespace rootsim::cli
