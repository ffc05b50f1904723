// One scene -> one run directory (used by `rootsim run` and by sweeps).
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include <optional>

#include "rootsim/checkpoint.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/results.hpp"
#include "rootsim/units.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/run_seams.hpp"
#include "rootsim/run_watch.hpp"
#include "rootsim/version.hpp"
#include "root_outputs.hpp"

#include <algorithm>
#include <optional>
#include <sstream>

#include <toml++/toml.h>

namespace fs = std::filesystem;

namespace rootsim {

using namespace detail;

namespace detail {

RootStreams::RootStreams(const fs::path& w, const Model& m, const WriterPositions* p, const Vec3& vtkOffset)
    : vtkOffset_(vtkOffset) {
  const bool traj = m.output.trajectory;
  const bool csv = traj && m.output.trajectoryFormat != TrajectoryFormat::Binary;
  const bool bin = traj && m.output.trajectoryFormat != TrajectoryFormat::Csv;
  // a root that had written nothing when the checkpoint saw it (a plate's lateral that emerged after the
  // last output step: its writers had not handed even their headers to the system) starts its files anew
  if (p && p->timeseriesBytes == 0) p = nullptr;
  if (p) {
    ts_ = std::make_unique<TimeseriesWriter>(w / "timeseries.csv", p->timeseriesBytes);
    if (csv) tr_ = std::make_unique<TrajectoryWriter>(w / "trajectory.csv", p->trajectoryBytes, p->trajectoryFrames);
    if (bin) tb_ = std::make_unique<TrajectoryBinaryWriter>(w / "trajectory.bin", p->trajectoryBinaryBytes, p->trajectoryFrames);
    if (m.output.vtk) vtk_ = std::make_unique<VtkSeriesWriter>(w, sceneInfoOf(m), p->vtkEntries);
  } else {
    ts_ = std::make_unique<TimeseriesWriter>(w / "timeseries.csv");
    if (csv) tr_ = std::make_unique<TrajectoryWriter>(w / "trajectory.csv");
    if (bin) tb_ = std::make_unique<TrajectoryBinaryWriter>(w / "trajectory.bin");
    if (m.output.vtk) vtk_ = std::make_unique<VtkSeriesWriter>(w, sceneInfoOf(m));
  }
}

void RootStreams::add(const Simulation& sim) {
  ts_->add(sim.last());
  if (tr_ || tb_ || vtk_) {
    const Snapshot sn = sim.snapshot();
    if (tr_) tr_->add(sn);
    if (tb_) tb_->add(sn);
    if (vtk_ && vtkOffset_.isZero(0.0)) {
      vtk_->add(sn);
    } else if (vtk_) {
      Snapshot moved = sn;
      moved.x.colwise() += vtkOffset_;
      vtk_->add(moved);
    }
  }
}

WriterPositions RootStreams::positions() const {
  WriterPositions p;
  p.timeseriesBytes = ts_->bytes();
  if (tr_) p.trajectoryBytes = tr_->bytes();
  if (tb_) p.trajectoryBinaryBytes = tb_->bytes();
  p.trajectoryFrames = tr_ ? tr_->frames() : (tb_ ? tb_->frames() : 0);
  if (vtk_) p.vtkEntries = vtk_->entries();
  return p;
}

void RootStreams::close() {
  ts_->close();
  if (tr_) tr_->close();
  if (tb_) tb_->close();
  if (vtk_) vtk_->close();
}

void RootStreams::closeQuietly() {
  auto quietly = [](auto&& close) {
    try {
      close();
    } catch (const std::exception&) {
      // a writer that cannot close (the disk that failed the run) keeps nothing; the others still do
    }
  };
  quietly([&] { ts_->close(); });
  if (tr_) quietly([&] { tr_->close(); });
  if (tb_) quietly([&] { tb_->close(); });
  if (vtk_) quietly([&] { vtk_->close(); });
}

RootFinal finishRoot(const Model& m, const Simulation& sim, const RunWatch& watch, double wall) {
  RootFinal f;
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
  return f;
}

// what to do with an interrupted run DIR.partial when resuming: continue it from its checkpoint (load
// read it), discard it (killed before its first checkpoint: nothing to lose), or refuse (another scene,
// a corrupt checkpoint; with force those are discarded too)
PartialRun resumePlan(const Scene& sc, const std::string& outDir, bool force,
                      const std::function<void(const fs::path&)>& load) {
  fs::path work = normaliseOutDir(outDir);
  work += ".partial";
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(work, ec))) return PartialRun::Refuse;  // nothing to resume: a new run
  if (std::string why = whyNotOurs(work, runFolder()); !why.empty()) throw SceneError("--out " + outDir + ": " + why);
  // the first file a run writes is its resolved scene
  std::ifstream in(work / "scene.toml", std::ios::binary);
  if (!in) return PartialRun::Discard;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text != sc.resolvedToml) {
    if (force) return PartialRun::Discard;
    throw SceneError("--resume: " + work.string() + " was written by another scene (" +
                     sceneDifference((work / "scene.toml").string(), text, sc.resolvedToml, sc.path) +
                     "); pass the same scene and --set values, or --force to discard it and start again");
  }
  if (!fs::exists(work / kCheckpointFile, ec)) {
    // killed before its first checkpoint: nothing to lose. But a run that finished there (its
    // summary.json written: renamed by hand, or a commit that failed) is never discarded without --force
    if (!force && fs::exists(work / "summary.json", ec))
      throw SceneError("--resume: " + work.string() + " holds a finished run without a checkpoint (it has summary.json); "
                       "move it away, or pass --force to discard it and start again");
    return PartialRun::Discard;
  }
  try {
    load(work / kCheckpointFile);
  } catch (const SceneError&) {
    if (force) return PartialRun::Discard;
    throw;
  }
  return PartialRun::Continue;
}

void noteResume(const RunDirOptions& o, const RunDir& rd, PartialRun partial, int step, int steps) {
  if (!o.note) return;
  if (partial == PartialRun::Continue)
    o.note("resuming " + rd.final().string() + " from the checkpoint of growth step " + std::to_string(step) + " of " +
           std::to_string(steps));
  else if (partial == PartialRun::Discard)
    o.note("no usable checkpoint in " + rd.work().string() + ": starting " + rd.final().string() + " again");
}

void checkStreamLengths(const fs::path& dir, const Model& m, const WriterPositions& w) {
  const bool traj = m.output.trajectory;
  const std::pair<const char*, std::uint64_t> streams[] = {
      {"timeseries.csv", w.timeseriesBytes},
      {"trajectory.csv", traj && m.output.trajectoryFormat != TrajectoryFormat::Binary ? w.trajectoryBytes : 0},
      {"trajectory.bin", traj && m.output.trajectoryFormat != TrajectoryFormat::Csv ? w.trajectoryBinaryBytes : 0}};
  for (const auto& [name, bytes] : streams) checkStreamLength(dir / name, bytes);
}

void checkStreamLength(const fs::path& file, std::uint64_t bytes) {
  if (bytes == 0) return;
  std::error_code ec;
  fs::path f = file;
  f += ".tmp";
  if (!fs::is_regular_file(f, ec)) f = file;  // killed after it was closed
  const std::uintmax_t have = fs::is_regular_file(f, ec) ? fs::file_size(f, ec) : 0;
  if (have < bytes)
    throw SceneError(f.string() + ": missing or shorter (" + std::to_string(have) + " bytes) than its checkpoint says (" +
                     std::to_string(bytes) + " bytes); pass --force to discard the interrupted run and start again");
}

void runGrowthSteps(int first, int steps, double checkpointEvery, const RunSteps& f) {
  const StepSeams seams = stepSeams();
  double lastCheckpoint = now();
  // A run that fails keeps what its writers hold, closed so that the files are whole and readable: the
  // time series and trajectory up to the last output step before the failure, the ParaView series. The
  // directory becomes DIR.incomplete with ERROR.txt (RunDir::fail), which marks it. (A stop on purpose
  // leaves DIR.partial as a kill does, its files where the checkpoint expects them.)
  try {
    for (int k = first; k <= steps; ++k) {
      f.grow(k);
      try {
        f.write(k);
        const bool due = seams.checkpointAfter ? seams.checkpointAfter(k) : now() - lastCheckpoint >= checkpointEvery;
        if (k < steps && due) {
          f.checkpoint(k);
          lastCheckpoint = now();
        }
      } catch (const RunError& e) {
        throw RunError(std::string(e.what()) + " (at growth step " + std::to_string(k) + " of " + std::to_string(steps) + ")");
      }
      if (seams.afterStep) seams.afterStep(k);
      f.progress(k);
    }
  } catch (const RunInterrupted&) {
    throw;
  } catch (const std::exception&) {
    f.closeQuietly();
    throw;
  }
}

void checkSceneHash(const fs::path& file, std::uint64_t found, std::uint64_t expected) {
  if (found != expected)
    throw SceneError(file.string() + ": written by another scene (scene hash differs); pass --force to discard it and "
                     "start again");
}

namespace {

// the first place where two TOML nodes differ: its dotted key and line in a (0: a's whole node), "" when
// they are the same
// the text of a node's value as its file wrote it (its source region)
std::string sourceText(const std::string& file, const toml::node& n) {
  if (n.is_table()) return "a table";
  const toml::source_region& r = n.source();
  auto offset = [&](const toml::source_position& p) {
    std::size_t pos = 0;
    for (toml::source_index l = 1; l < p.line && pos != std::string::npos; ++l) {
      pos = file.find('\n', pos);
      if (pos != std::string::npos) ++pos;
    }
    return pos == std::string::npos ? file.size() : std::min(file.size(), pos + p.column - 1);
  };
  const std::size_t from = offset(r.begin), to = offset(r.end);
  return to > from ? file.substr(from, to - from) : "?";
}

struct SceneTexts {
  const std::string& a;
  const std::string& b;
};

std::string nodeDifference(const toml::node& a, const toml::node& b, const std::string& key, int& line,
                           std::string& valueA, std::string& valueB, const SceneTexts& texts) {
  auto textA = [&](const toml::node& n) { return sourceText(texts.a, n); };
  auto textB = [&](const toml::node& n) { return sourceText(texts.b, n); };
  if (const toml::table* ta = a.as_table(); ta && b.is_table()) {
    const toml::table& tb = *b.as_table();
    for (const auto& [k, v] : *ta) {
      const std::string sub = key.empty() ? std::string(k.str()) : key + "." + std::string(k.str());
      const toml::node* w = tb.get(k.str());
      if (!w) {
        line = static_cast<int>(v.source().begin.line);
        valueA = textA(v);
        valueB = "not set";
        return sub;
      }
      if (std::string d = nodeDifference(v, *w, sub, line, valueA, valueB, texts); !d.empty()) return d;
    }
    for (const auto& [k, v] : tb)
      if (!ta->get(k.str())) {
        line = static_cast<int>(a.source().begin.line);
        valueA = "not set";
        valueB = textB(v);
        return key.empty() ? std::string(k.str()) : key + "." + std::string(k.str());
      }
    return "";
  }
  if (const toml::array* aa = a.as_array(); aa && b.is_array() && aa->is_array_of_tables() == b.as_array()->is_array_of_tables() &&
                                            aa->is_array_of_tables() && aa->size() == b.as_array()->size()) {
    // [[seedling]] and the like: element by element, named by their name (else their index from 1)
    for (std::size_t i = 0; i < aa->size(); ++i) {
      const toml::table* e = aa->get(i)->as_table();
      const std::optional<std::string> name = e ? e->get("name") ? e->get("name")->value<std::string>() : std::nullopt
                                                : std::nullopt;
      const std::string sub = key + (name ? " \"" + *name + "\"" : " " + std::to_string(i + 1));
      if (std::string d = nodeDifference(*aa->get(i), *b.as_array()->get(i), sub, line, valueA, valueB, texts); !d.empty())
        return d;
    }
    return "";
  }
  auto repr = [](const toml::node& n) {
    std::ostringstream os;
    if (const toml::array* arr = n.as_array()) os << *arr;
    else if (const toml::table* t = n.as_table()) os << *t;
    else n.visit([&](const auto& v) { os << v; });
    return os.str();
  };
  if (a.type() == b.type() && repr(a) == repr(b)) return "";
  valueA = textA(a);
  valueB = textB(b);
  line = static_cast<int>(a.source().begin.line);
  return key;
}

}  // namespace

std::string sceneDifference(const std::string& file, const std::string& written, const std::string& current,
                            const std::string& scenePath) {
  toml::table a, b;
  try {
    a = toml::parse(written, file);
    b = toml::parse(current, scenePath);
  } catch (const toml::parse_error& e) {
    return file + " is not the resolved scene (" + std::string(e.description()) + ")";
  }
  int line = 0;
  std::string va, vb;
  const std::string key = nodeDifference(a, b, "", line, va, vb, SceneTexts{written, current});
  if (key.empty()) return file + " differs from this scene in its text only";
  return file + ":" + std::to_string(std::max(line, 1)) + ": " + key + " is " + va + " there, " + vb + " in " + scenePath +
         " with these --set values";
}

void removeStaleTemps(const fs::path& dir, const std::vector<std::string>& streams) {
  std::error_code ec;
  for (const fs::path& d : {dir, dir / "vtk"}) {
    if (!fs::is_directory(d, ec)) continue;
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(d, ec)) {
      const std::string name = e.path().filename().string();
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0 &&
          std::find(streams.begin(), streams.end(), name.substr(0, name.size() - 4)) == streams.end())
        stale.push_back(e.path());
    }
    for (const auto& f : stale) fs::remove(f, ec);
  }
}

}  // namespace detail

double runSceneToDir(const Scene& sc, const std::string& outDir, const RunDirOptions& dirOptions,
                     const std::function<void(const StepRecord&, int total)>& progress) {
  if (sc.isPlate()) return runPlateToDir(sc, outDir, dirOptions, progress);
  const Model& m = sc.model;
  const std::uint64_t hash = sceneHash(sc.resolvedToml);
  std::optional<RunCheckpoint> ck;
  const PartialRun partial = dirOptions.resume ? resumePlan(sc, outDir, dirOptions.force,
                                                            [&](const fs::path& file) {
                                                              ck.reset();
                                                              ck = readCheckpoint(file);
                                                              checkSceneHash(file, ck->sceneHash, hash);
                                                              checkStreamLengths(file.parent_path(), m, ck->writers);
                                                            })
                                               : PartialRun::Refuse;
  if (partial != PartialRun::Continue) ck.reset();
  RunDir rd(outDir, dirOptions, partial);
  noteResume(dirOptions, rd, partial, ck ? ck->step : 0, m.growth.steps);
  const double t0 = now();
  try {
    const fs::path w = rd.work();
    std::unique_ptr<Simulation> simp;
    std::unique_ptr<RootStreams> out;
    RunWatch watch;
    double wallBefore = 0;         // wall time of earlier attempts (resumed) [s]
    int first = 1;                 // the first growth step this process runs
    if (ck) {
      // resumed: the state, the solvers' memory and the writers where the checkpoint saw them
      removeStaleTemps(w, kRootStreams);
      simp = std::make_unique<Simulation>(m, ck->state, ck->carry);
      out = std::make_unique<RootStreams>(w, m, &ck->writers);
      watch = ck->acc.watch;
      wallBefore = ck->acc.wallBefore;
      first = ck->step + 1;
    } else {
      rd.write("scene.toml", sc.resolvedToml);
      simp = std::make_unique<Simulation>(m);
      out = std::make_unique<RootStreams>(w, m);
    }
    Simulation& sim = *simp;
    if (!ck) {
      out->add(sim);
      watch.start(sim.last());
    }
    // a checkpoint: everything carried to the next step, and where the files stand (each add() flushed)
    auto checkpoint = [&](int k) {
      RunCheckpoint c;
      c.sceneHash = hash;
      c.step = k;
      c.state = sim.state();
      c.carry = sim.carry();
      c.acc = {watch, wallBefore + (now() - t0)};
      c.writers = out->positions();
      writeCheckpoint(w / kCheckpointFile, c);
    };
    const int steps = m.growth.enabled ? m.growth.steps : 0;
    const StepRecord* r = nullptr;
    runGrowthSteps(first, steps, m.output.checkpointEvery, RunSteps{
        [&](int) {
          r = &sim.growthStep();
          watch.see(*r);
        },
        [&](int k) {
          if (k % m.output.everySteps == 0 || k == steps) out->add(sim);
        },
        checkpoint,
        [&](int) {
          if (progress) progress(*r, steps);
        },
        [&] { out->closeQuietly(); }});
    out->close();
    // the finished run holds no checkpoint: it is the same as a run never interrupted
    std::error_code ec;
    fs::remove(w / kCheckpointFile, ec);
    const double wall = wallBefore + (now() - t0);
    const RootFinal f = finishRoot(m, sim, watch, wall);
    rd.write("shape.csv", f.shape);
    rd.write("summary.json", f.summary);
    rd.write("result.csv", f.result);
    rd.commit();
    return wall;
  } catch (const RunInterrupted&) {
    throw;  // stopped on purpose (a progress callback threw it): DIR.partial stays, like a killed run
  } catch (const std::exception& e) {
    rd.fail(failureText(e, "the run of " + sc.model.name + " into " + rd.work().string()));
    throw;
  }
}

}  // namespace rootsim
