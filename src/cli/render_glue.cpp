// `rootsim render` and `rootsim run --movie`: validate the flags and the run directory (SceneError,
// exit 2), then hand the snapshots to the renderer library (RenderError, exit 1)
#include "render_glue.hpp"

#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/montage.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/png.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"
#include "rootsim/write_rule.hpp"

namespace fs = std::filesystem;

namespace rootsim::cli {

namespace {

constexpr int kMinSide = 64;     // [px] room for the overlays
constexpr int kMaxLong = 3840;   // [px] 4K UHD: the longer side at most 3840,
constexpr int kMaxShort = 2160;  // [px] the shorter at most 2160 (landscape or portrait)

// "WxH" -> (W, H), both even, at least kMinSide, at most 3840x2160 (or 2160x3840)
// --view: "top" or "3d"
View::Kind parseViewKind(const std::string& v) {
  if (v == "top") return View::Kind::Top;
  if (v == "3d") return View::Kind::Perspective;
  throw SceneError("--view " + v + ": expected top or 3d");
}

std::pair<int, int> parseSize(const std::string& s) {
  const std::size_t x = s.find('x');
  auto number = [&](const std::string& part) {
    if (part.empty() || part.size() > 5 || part.find_first_not_of("0123456789") != std::string::npos)
      throw SceneError("--size " + s + ": expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
    return std::stoi(part);
  };
  if (x == std::string::npos) throw SceneError("--size " + s + ": expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
  const int w = number(s.substr(0, x)), h = number(s.substr(x + 1));
  if (w < kMinSide || h < kMinSide)
    throw SceneError("--size " + s + ": width and height must be at least " + std::to_string(kMinSide) + " px");
  if (std::max(w, h) > kMaxLong || std::min(w, h) > kMaxShort)
    throw SceneError("--size " + s + ": at most 3840x2160 (or 2160x3840)");
  if (w % 2 != 0 || h % 2 != 0)
    throw SceneError("--size " + s + ": width and height must be even (H.264 yuv420p), e.g. " +
                     std::to_string(w + w % 2) + "x" + std::to_string(h + h % 2));
  return {w, h};
}

// "auto": 1280x720 for a root that spreads sideways, 720x1280 for one that grows mostly downhill
// (a long waving root in a landscape frame is a thin line); the top view's bounding box decides
std::pair<int, int> autoSize(const std::vector<Snapshot>& snaps, const SceneInfo& info) {
  const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
  double umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300;
  for (const auto& sn : snaps)
    for (int i = 0; i < sn.x.cols(); ++i) {
      const Eigen::Vector3d p = pf.toPlateMm(sn.x.col(i));
      umin = std::min(umin, p.x());
      umax = std::max(umax, p.x());
      vmin = std::min(vmin, p.y());
      vmax = std::max(vmax, p.y());
    }
  const double w = umax - umin + 2.0, h = vmax - vmin + 2.0;  // with the 1 mm margins
  if (h > 1.2 * w) return {720, 1280};
  return {1280, 720};
}

// auto size for a look: the follow camera shows a window, landscape 1280x720 (the issue's reference:
// at --field-mm 2 the tube is ~100 px wide); otherwise the root's shape decides
std::pair<int, int> autoSizeFor(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieLook& look) {
  if (look.camera == CameraMode::Follow) return {1280, 720};
  return autoSize(snaps, info);
}

std::string fmtNumber(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

SceneInfo sceneInfoOf(const Model& m) {
  SceneInfo si;
  si.alphaDeg = m.env.plane.alpha / units::deg;
  si.beta = m.tropism.beta;
  si.gamma = m.tropism.gamma;
  si.rTau = m.tropism.rTau;
  si.radius = m.rod.radius;
  si.plate = m.env.plane.enabled;
  si.title = m.name;
  for (const Obstacle& o : m.env.obstacles) {
    SceneInfo::ObstacleShape sh;
    sh.peg = o.shape == Obstacle::Shape::Peg;
    sh.fromU = o.from.x() / units::mm, sh.fromV = -o.from.y() / units::mm;  // downhill -> uphill
    sh.toU = o.to.x() / units::mm, sh.toV = -o.to.y() / units::mm;
    sh.radiusMm = o.radius / units::mm;
    si.obstacles.push_back(sh);
  }
  return si;
}

std::vector<Snapshot> loadSnapshots(const fs::path& runDir) {
  const fs::path traj = trajectoryPath(runDir);  // trajectory.bin, or trajectory.csv
  if (!fs::is_regular_file(traj))
    throw SceneError(traj.string() + ": not found (a run directory written with output.trajectory = true)");
  std::vector<Snapshot> snaps = readTrajectory(traj);
  if (snaps.empty()) throw SceneError(traj.string() + ": no snapshots to render");
  return snaps;
}

// the outputs of render and montage, checked by the write rule and locked until they are written
struct Outputs {
  std::vector<OutputLock> locks;
};

Outputs claimOutputs(const std::string& mp4, const fs::path& png, const std::string& pngDir, const WriteRule& rule) {
  Outputs o;
  std::vector<std::pair<const char*, fs::path>> all;
  if (!mp4.empty()) all.emplace_back("--mp4", mp4);
  if (!png.empty()) all.emplace_back("--final-png", png);
  if (!pngDir.empty()) all.emplace_back("--png-dir", pngDir);
  // no output may be another, or lie inside the frame folder (replaced whole)
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = 0; j < all.size(); ++j) {
      if (i == j) continue;
      const fs::path a = fs::absolute(all[i].second).lexically_normal(), b = fs::absolute(all[j].second).lexically_normal();
      const auto rel = a.lexically_relative(b);
      if (a == b || (std::string(all[j].first) == "--png-dir" && !rel.empty() && *rel.begin() != ".."))
        throw SceneError(std::string(all[i].first) + " " + all[i].second.string() + ": the same path as, or inside, " +
                         all[j].first + " " + all[j].second.string());
    }
  for (const auto& [flag, path] : all) {
    // locked first, then checked: a second process cannot slip in between
    if (std::string(flag) == "--png-dir") {
      checkOutputName(path.string(), flag);
      claimFolder(path, framesFolder(), rule, flag, true);
      continue;  // StagedFolder locks it when the frames are written
    }
    checkOutputName(path.string(), flag);
    const fs::path dir = fs::absolute(path).parent_path();
    if (!fs::is_directory(dir)) throw SceneError(std::string(flag) + " " + path.string() + ": folder " + dir.string() + " not found");
    o.locks.emplace_back(path, flag);
    claimFile(path, rule, flag);
  }
  return o;
}

// stderr progress: one line per ~10 % of the frames
MovieProgress progressLines(bool quiet, const std::string& what) {
  if (quiet) return {};
  return [what, next = 0](int done, int total) mutable {
    const int percent = 100 * done / total;
    if (percent < next && done != total) return;
    std::fprintf(stderr, "%s: frame %d/%d (%d %%)\n", what.c_str(), done, total, percent);
    next = percent / 10 * 10 + 10;
  };
}

// the last snapshot seen from the top, framed like a top-view movie of the whole run
void writeFinalTop(const std::vector<Snapshot>& snaps, const SceneInfo& info, const View& like,
                   const fs::path& path) {
  View top = like;
  top.kind = View::Kind::Top;
  if (top.colourBy != ColourField::None) top.colourRange = fieldRange(snaps, info, top.colourBy);
  const Framing framing = frameFor(snaps, info, top);
  GlRenderer renderer(top.width, top.height);
  writePng(path.string(), renderer.render(buildRenderScene(snaps.back(), info, top, framing)));
}

// the movie and, when asked for, the final picture (always the top view, framed like a top-view movie)
void renderRun(const std::vector<Snapshot>& snaps, const SceneInfo& info, MovieJob job,
               const fs::path& finalTop, bool quiet) {
  // the movie's last frame is the final picture when it is a plain fit top view
  const bool same = job.view.kind == View::Kind::Top && job.camera == CameraMode::Fit && !job.inset && job.plots.empty();
  if (same && !finalTop.empty()) job.finalPng = finalTop.string();
  renderMovie(snaps, info, job, progressLines(quiet, "render " + info.title));
  if (!same && !finalTop.empty()) writeFinalTop(snaps, info, job.view, finalTop);
  if (!quiet) {
    if (!job.mp4.empty()) std::fprintf(stderr, "wrote %s\n", job.mp4.c_str());
    if (!finalTop.empty()) std::fprintf(stderr, "wrote %s\n", finalTop.string().c_str());
  }
}


// the plot keys: timeseries.csv column, axis title, unit, SI prefix
struct PlotKey {
  const char* key;
  const char* column;
  const char* name;
  const char* unit;
  bool si;
};
constexpr PlotKey kPlotKeys[] = {
    {"theta_tip", "theta_tip_deg", "\xCE\xB8 tip", "\xC2\xB0", false},
    {"Eb", "Eb", "E_b (growth zone)", "J", true},
    {"Et", "Et", "E_t (growth zone)", "J", true},
    {"Wr", "Wr", "writhe Wr (growth zone)", "", false},
    {"Tw", "Tw", "twist Tw (growth zone)", "turns", false},
};

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  if (!s.empty() && s.back() == ',') out.push_back("");
  return out;
}

// timeseries.csv -> column name -> values (every column numeric)
std::map<std::string, std::vector<double>> readTimeseries(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw SceneError(path.string() + ": not found (needed by --plot)");
  std::string line;
  if (!std::getline(in, line)) throw SceneError(path.string() + ":1: empty");
  const std::vector<std::string> names = splitList(line);
  std::map<std::string, std::vector<double>> cols;
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    const std::vector<std::string> cells = splitList(line);
    if (cells.size() != names.size())
      throw SceneError(path.string() + ":" + std::to_string(lineNo) + ": expected " + std::to_string(names.size()) +
                       " columns, found " + std::to_string(cells.size()));
    for (std::size_t i = 0; i < cells.size(); ++i) {
      double v = 0;
      try {
        std::size_t used = 0;
        v = std::stod(cells[i], &used);
        if (used != cells[i].size()) throw std::invalid_argument("trailing");
      } catch (const std::exception&) {
        throw SceneError(path.string() + ":" + std::to_string(lineNo) + ": malformed number in column " + names[i]);
      }
      cols[names[i]].push_back(v);
    }
  }
  return cols;
}

}  // namespace

MovieLook parseLook(const LookOptions& o) {
  MovieLook l;
  if (o.camera == "fit")
    l.camera = CameraMode::Fit;
  else if (o.camera == "follow")
    l.camera = CameraMode::Follow;
  else
    throw SceneError("--camera " + o.camera + ": expected fit or follow");
  if (!(o.fieldMm > 0)) throw SceneError("--field-mm " + fmtNumber(o.fieldMm) + ": must be > 0 mm");
  l.fieldMm = o.fieldMm;
  if (o.fieldGiven && l.camera != CameraMode::Follow && !o.inset)
    throw SceneError("--field-mm " + fmtNumber(o.fieldMm) + ": sizes the follow window; add --camera follow or --inset");
  if (o.inset && l.camera == CameraMode::Follow)
    throw SceneError("--inset: puts a follow window into the fit view; use it with --camera fit");
  l.inset = o.inset;
  if (!parseColourField(o.colorBy, l.colourBy))
    throw SceneError("--color-by " + o.colorBy + ": expected one of " + colourFieldNames());
  if (!o.plot.empty()) {
    std::set<std::string> seen;
    for (const std::string& k : splitList(o.plot)) {
      bool known = false;
      for (const PlotKey& p : kPlotKeys) known = known || k == p.key;
      if (!known) throw SceneError("--plot " + o.plot + ": unknown key '" + k + "' (expected any of theta_tip,Eb,Et,Wr,Tw)");
      if (!seen.insert(k).second) throw SceneError("--plot " + o.plot + ": '" + k + "' given twice");
      l.plots.push_back(k);
    }
  }
  l.shadows = o.shadows;
  return l;
}

void checkFieldAgainstPlate(const MovieLook& look, double plateMm) {
  if (look.camera == CameraMode::Follow || look.inset)
    if (look.fieldMm > plateMm)
      throw SceneError("--field-mm " + fmtNumber(look.fieldMm) + ": larger than the plate (" + fmtNumber(plateMm) +
                       " mm wide in the fit view)");
}

namespace {

// the look applied to a job: camera, colours, plots (from RUN_DIR/timeseries.csv), shadows
void applyLook(const MovieLook& look, const fs::path& runDir, const std::vector<Snapshot>& snaps, MovieJob& job) {
  job.camera = look.camera;
  job.fieldMm = look.fieldMm;
  job.inset = look.inset;
  job.view.colourBy = look.colourBy;
  job.view.shadows = look.shadows;
  const Snapshot& last = snaps.back();
  if (look.colourBy == ColourField::Kappa0 && last.kappa0.size() == 0)
    throw SceneError("--color-by kappa0: " + trajectoryPath(runDir).string() +
                     " has no kappa0_per_mm column (written by an older rootsim; run the scene again)");
  if (look.colourBy == ColourField::Contact && last.plateForce.size() == 0)
    throw SceneError("--color-by contact: " + trajectoryPath(runDir).string() +
                     " has no plate_force_n column (written by an older rootsim; run the scene again)");
  if (!look.plots.empty()) {
    const fs::path ts = runDir / "timeseries.csv";
    const auto cols = readTimeseries(ts);
    const auto time = cols.find("time_h");
    if (time == cols.end()) throw SceneError(ts.string() + ": no time_h column");
    for (const std::string& k : look.plots) {
      for (const PlotKey& p : kPlotKeys) {
        if (k != p.key) continue;
        const auto c = cols.find(p.column);
        if (c == cols.end()) throw SceneError("--plot " + k + ": " + ts.string() + " has no column " + p.column);
        PlotSeries s;
        s.name = p.name;
        s.unit = p.unit;
        s.siPrefix = p.si;
        s.timeH = time->second;
        s.value = c->second;
        if (s.timeH.empty()) throw SceneError(ts.string() + ": no rows to plot");
        job.plots.push_back(std::move(s));
      }
    }
  }
}

// the fit view's plate width for this job [mm]
double fitPlateMm(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job) {
  const FrameLayout l = frameLayout(job.view.width, job.view.height, !job.plots.empty(), false);
  View v = job.view;
  v.width = l.viewW;
  v.height = l.viewH;
  return frameFor(snaps, info, v).widthMm;
}

}  // namespace

int renderRunCommand(const RenderOptions& o) {
  // every input check first, so a bad flag exits 2 before anything is drawn
  const fs::path runDir(o.runDir);
  if (!fs::is_directory(runDir)) throw SceneError(o.runDir + ": run directory not found");
  MovieJob job;
  job.view.kind = parseViewKind(o.view);
  const bool autoSized = o.size == "auto";
  if (!autoSized) std::tie(job.view.width, job.view.height) = parseSize(o.size);
  if (o.fps < 1 || o.fps > 240) throw SceneError("--fps " + std::to_string(o.fps) + ": expected 1..240");
  if (o.crf < 0 || o.crf > 51) throw SceneError("--crf " + std::to_string(o.crf) + ": expected 0..51");
  job.video.fps = o.fps;
  job.video.crf = o.crf;
  // only what is asked for: with no output flag at all, RUN_DIR/movie.mp4 and RUN_DIR/final_top.png;
  // with any of --mp4, --png-dir, --final-png, exactly those (the run directory stays untouched)
  const bool asked = !o.mp4.empty() || !o.pngDir.empty() || !o.finalPng.empty();
  job.mp4 = asked ? o.mp4 : (runDir / "movie.mp4").string();
  const fs::path finalTop = asked ? fs::path(o.finalPng) : runDir / "final_top.png";
  job.view.whiskers = o.whiskers;
  if (o.transparent) {
    // PNG frames only: MP4 has no alpha channel
    if (o.pngDir.empty()) throw SceneError("--transparent: applies to PNG frames; add --png-dir DIR");
    if (!o.mp4.empty()) throw SceneError("--transparent: MP4 has no alpha channel; drop --mp4 " + o.mp4);
    job.view.transparent = true;
  }
  if (o.noOverlays) job.view.overlays = false;
  const MovieLook look = parseLook(o.look);
  if (o.transparent && (look.inset || !look.plots.empty() || look.shadows))
    throw SceneError("--transparent: frames of the root alone, without a plate; not with --inset, --plot or --shadows");
  if (!o.shaderDir.empty()) {
    for (const char* f : {"tube.vert", "tube.frag", "plane.vert", "plane.frag", "shadow.vert", "shadow.frag", "shade.frag"})
      if (!fs::is_regular_file(fs::path(o.shaderDir) / f))
        throw SceneError("--shader-dir " + o.shaderDir + ": " + f + " not found");
    job.renderer.shaderDir = o.shaderDir;
  }
  const fs::path sceneFile = runDir / "scene.toml";
  if (!fs::is_regular_file(sceneFile)) throw SceneError(sceneFile.string() + ": not found (not a run directory?)");
  const SceneInfo info = sceneInfoOf(loadScene(sceneFile.string()).model);
  if (look.shadows && !info.plate)
    throw SceneError("--shadows: " + sceneFile.string() + " has no plate to cast them on (plane.enabled = false)");
  const std::vector<Snapshot> snaps = loadSnapshots(runDir);
  if (autoSized) std::tie(job.view.width, job.view.height) = autoSizeFor(snaps, info, look);
  applyLook(look, runDir, snaps, job);
  checkFieldAgainstPlate(look, fitPlateMm(snaps, info, job));
  // the write rule, once the flags and the run are known good: the run directory is read and receives
  // only its own movie.mp4 and final_top.png
  WriteRule rule;
  rule.force = o.force;
  rule.inputs = {WriteInput{runDir, {"movie.mp4", "final_top.png"}}};
  const Outputs outs = claimOutputs(job.mp4, finalTop, o.pngDir, rule);

  // every check passed: the frame folder is made now (DIR.partial, renamed to DIR when all are written)
  std::optional<StagedFolder> frames;
  if (!o.pngDir.empty()) {
    frames.emplace(o.pngDir, framesFolder(), rule, "--png-dir");
    job.pngDir = frames->work().string();
  }
  renderRun(snaps, info, job, finalTop, o.quiet);
  if (frames) {
    frames->commit();
    if (!o.quiet) std::fprintf(stderr, "wrote %zu frames to %s\n", snaps.size(), frames->final().c_str());
  }
  return 0;
}

void renderRunMovie(const fs::path& runDir, const Model& model, bool quiet, const MovieLook& look) {
  const SceneInfo info = sceneInfoOf(model);
  MovieJob job;
  job.mp4 = (runDir / "movie.mp4").string();
  const std::vector<Snapshot> snaps = loadSnapshots(runDir);
  std::tie(job.view.width, job.view.height) = autoSizeFor(snaps, info, look);
  applyLook(look, runDir, snaps, job);
  renderRun(snaps, info, job, runDir / "final_top.png", quiet);
}

}  // namespace rootsim::cli

namespace rootsim::cli {

namespace {

// scene.toml -> "section.key" -> value text (the resolved scene a run directory holds)
std::map<std::string, std::string> sceneKeys(const fs::path& file) {
  std::ifstream in(file);
  std::map<std::string, std::string> keys;
  std::string line, section;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    line = line.substr(first);
    if (line[0] == '[') {
      section = line.substr(1, line.find(']') - 1);
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    auto trim = [](std::string t) {
      const auto a = t.find_first_not_of(" \t"), b = t.find_last_not_of(" \t");
      return a == std::string::npos ? std::string() : t.substr(a, b - a + 1);
    };
    std::string value = trim(line.substr(eq + 1));
    const auto hash = value.find(" #");
    if (hash != std::string::npos) value = trim(value.substr(0, hash));
    keys[(section.empty() ? "" : section + ".") + trim(line.substr(0, eq))] = value;
  }
  return keys;
}

// a label per run: the scene keys whose values differ between the runs (not name, title or output)
std::vector<std::string> differingLabels(const std::vector<fs::path>& dirs) {
  std::vector<std::map<std::string, std::string>> keys;
  std::set<std::string> all;
  for (const fs::path& d : dirs) {
    keys.push_back(sceneKeys(d / "scene.toml"));
    for (const auto& [k, v] : keys.back()) all.insert(k);
  }
  std::vector<std::string> differ;
  for (const std::string& k : all) {
    if (k == "name" || k == "title" || k.rfind("output.", 0) == 0) continue;
    std::set<std::string> values;
    for (const auto& m : keys) values.insert(m.count(k) ? m.at(k) : "-");
    if (values.size() > 1) differ.push_back(k);
  }
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    std::string l;
    for (const std::string& k : differ) {
      const std::string shortKey = k.substr(k.find('.') + 1);
      l += (l.empty() ? "" : "  ") + shortKey + " = " + (keys[i].count(k) ? keys[i].at(k) : "-");
    }
    labels.push_back(l.empty() ? fs::absolute(dirs[i]).lexically_normal().filename().string() : l);
  }
  return labels;
}

}  // namespace

int montageRunsCommand(const MontageOptions& o) {
  // every check first: exit 2 before anything is written
  if (o.runDirs.empty()) throw SceneError("montage: no run directories given (rootsim montage RUN_DIR... --mp4 FILE)");
  std::vector<fs::path> dirs;
  for (const std::string& d : o.runDirs) {
    if (!fs::is_directory(d)) throw SceneError("montage: run directory " + d + " not found");
    if (!fs::is_regular_file(fs::path(d) / "scene.toml"))
      throw SceneError("montage: " + d + "/scene.toml not found (not a run directory?)");
    dirs.emplace_back(d);
  }
  if (o.mp4.empty() && o.pngDir.empty()) throw SceneError("montage: nothing to write; give --mp4 FILE and/or --png-dir DIR");
  MontageJob job;
  std::tie(job.view.width, job.view.height) = parseSize(o.size);
  job.view.kind = parseViewKind(o.view);
  if (o.fps < 1 || o.fps > 240) throw SceneError("--fps " + std::to_string(o.fps) + ": expected 1..240");
  if (o.crf < 0 || o.crf > 51) throw SceneError("--crf " + std::to_string(o.crf) + ": expected 0..51");
  job.video.fps = o.fps;
  job.video.crf = o.crf;
  if (!parseColourField(o.colorBy, job.view.colourBy))
    throw SceneError("--color-by " + o.colorBy + ": expected one of " + colourFieldNames());
  job.view.shadows = o.shadows;
  job.mp4 = o.mp4;
  std::vector<std::string> labels;
  if (!o.labels.empty()) {
    labels = splitList(o.labels);
    if (labels.size() != dirs.size())
      throw SceneError("--labels " + o.labels + ": " + std::to_string(labels.size()) + " labels for " +
                       std::to_string(dirs.size()) + " runs");
  } else {
    labels = differingLabels(dirs);
  }
  std::vector<MontageRun> runs;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    MontageRun r;
    r.info = sceneInfoOf(loadScene((dirs[i] / "scene.toml").string()).model);
    if (job.view.shadows && !r.info.plate)
      throw SceneError("--shadows: " + (dirs[i] / "scene.toml").string() + " has no plate to cast them on (plane.enabled = false)");
    r.snaps = loadSnapshots(dirs[i]);
    r.label = labels[i];
    if (job.view.colourBy == ColourField::Kappa0 && r.snaps.back().kappa0.size() == 0)
      throw SceneError("--color-by kappa0: " + trajectoryPath(dirs[i]).string() + " has no kappa0_per_mm column");
    if (job.view.colourBy == ColourField::Contact && r.snaps.back().plateForce.size() == 0)
      throw SceneError("--color-by contact: " + trajectoryPath(dirs[i]).string() + " has no plate_force_n column");
    runs.push_back(std::move(r));
  }
  // the write rule, once the flags and the runs are known good: the run directories are read, never written
  WriteRule rule;
  rule.force = o.force;
  for (const fs::path& d : dirs) rule.inputs.push_back(WriteInput{d, {}});
  const Outputs outs = claimOutputs(o.mp4, fs::path(), o.pngDir, rule);
  std::optional<StagedFolder> frames;
  if (!o.pngDir.empty()) {
    frames.emplace(o.pngDir, framesFolder(), rule, "--png-dir");
    job.pngDir = frames->work().string();
  }
  renderMontage(runs, job, progressLines(o.quiet, "montage"));
  if (frames) frames->commit();
  if (!o.quiet) {
    if (!job.mp4.empty()) std::fprintf(stderr, "wrote %s\n", job.mp4.c_str());
    if (frames) std::fprintf(stderr, "wrote frames to %s\n", frames->final().c_str());
  }
  return 0;
}

}  // namespace rootsim::cli
