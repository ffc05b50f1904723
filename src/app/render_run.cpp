// `rootsim render` and `rootsim run --movie`: validate the flags and the run directory (SceneError,
// exit 2), then hand the snapshots to the renderer library (RenderError, exit 1)
#include "rootsim/render_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>
#include <vector>

#include "flags.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"
#include "rootsim/write_rule.hpp"
#include "run_files.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

// --plate-view's margin around the sown area [mm]
constexpr double kPlateViewMarginMm = 3.0;

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

// auto size for a look: the follow camera shows a window, landscape 1280x720 (the reference:
// at --field-mm 2 the tube is ~100 px wide); otherwise the root's shape decides
std::pair<int, int> autoSizeFor(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieLook& look) {
  if (look.camera == CameraMode::Follow) return {1280, 720};
  return autoSize(snaps, info);
}

// the movie and, when asked for, the final picture: the movie's last frame (the same look, the same
// framing); with no movie to render, that one frame alone (a still)
void renderRun(const std::vector<Snapshot>& snaps, const SceneInfo& info, MovieJob job,
               const fs::path& finalTop, bool quiet) {
  if (!job.mp4.empty() || !job.pngDir.empty()) {
    if (!finalTop.empty()) job.finalPng = finalTop.string();
    renderMovie(snaps, info, job, progressLines(quiet, "render " + info.title));
  } else if (!finalTop.empty()) {
    renderStill(snaps, info, job, static_cast<int>(snaps.size()) - 1, finalTop.string());
  }
  if (!quiet) {
    if (!job.mp4.empty()) std::fprintf(stderr, "wrote %s\n", job.mp4.c_str());
    if (!finalTop.empty()) std::fprintf(stderr, "wrote %s\n", finalTop.string().c_str());
  }
}

// the fit view's plate width for this job [mm], in the top view
double fitPlateMm(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job) {
  const FrameLayout l = frameLayout(job.view.width, job.view.height, !job.plots.empty(), false);
  View v = job.view;
  v.width = l.viewW;
  v.height = l.viewH;
  v.kind = View::Kind::Top;  // the plate's width as the top view frames it (the 3-D fit zooms to the root)
  return frameFor(snaps, info, v).widthMm;
}

// the plate view's right-hand share of the picture kept for the legend of the seedlings' values
constexpr double kSeedLegendShare = 0.22;

// the flags of a still and of a time window, checked before anything is read
// (scan: --scan's picture, the last snapshot unless --at-h or --frame says)
void checkTimeFlags(const RenderOptions& o, bool scan) {
  const bool still = !o.png.empty() || flagGiven(o.atH) || o.frameGiven;
  if (flagGiven(o.atH) && o.frameGiven) throw SceneError("--at-h " + significantText(o.atH) + ": give --at-h or --frame, not both");
  if (still) {
    if (o.png.empty())
      throw SceneError(std::string(flagGiven(o.atH) ? "--at-h " + significantText(o.atH) : "--frame " + std::to_string(o.frame)) +
                       ": writes a still; add --png FILE");
    if (!scan && !flagGiven(o.atH) && !o.frameGiven) throw SceneError("--png " + o.png + ": a still; add --at-h H or --frame N");
    if (!o.mp4.empty() || !o.pngDir.empty() || !o.finalPng.empty())
      throw SceneError("--png " + o.png + ": a still is one picture; not with --mp4, --png-dir or --final-png");
    if (flagGiven(o.hoursPerSecond))
      throw SceneError("--hours-per-second " + significantText(o.hoursPerSecond) + ": paces a movie; a still (--png) has no speed");
    if (o.frameGiven && o.frame < 0) throw SceneError("--frame " + std::to_string(o.frame) + ": must be >= 0");
  }
  if (flagGiven(o.atH)) checkedNumber("--at-h", o.atH, kGrowthHours);
  if (flagGiven(o.fromH)) checkedNumber("--from-h", o.fromH, kGrowthHours);
  if (flagGiven(o.toH)) checkedNumber("--to-h", o.toH, kGrowthHours);
  if (flagGiven(o.fromH) && flagGiven(o.toH) && o.fromH > o.toH)
    throw SceneError("--from-h " + significantText(o.fromH) + ": after --to-h " + significantText(o.toH));
  if (flagGiven(o.hoursPerSecond)) checkedNumber("--hours-per-second", o.hoursPerSecond, {0, 1e6, true, false, "h/s"});
}

// the snapshots the movie shows, one per frame (the window and the speed applied)
std::vector<Snapshot> framesOf(const std::vector<Snapshot>& snaps, const RenderOptions& o, int fps) {
  std::vector<double> t;
  for (const Snapshot& s : snaps) t.push_back(s.timeH);
  const double from = flagGiven(o.fromH) ? o.fromH : -1e300, to = flagGiven(o.toH) ? o.toH : 1e300;
  const double hps = flagGiven(o.hoursPerSecond) ? o.hoursPerSecond : 0.0;
  // the frames, counted before they are made (each holds a copy of its snapshot)
  const double lo = std::max(from, t.front()), hi = std::min(to, t.back());
  const double frames = hps > 0 ? std::max(0.0, hi - lo) * fps / hps + 1 : static_cast<double>(t.size());
  checkCount((hps > 0 ? "--hours-per-second " + significantText(hps) + ": " : std::string()) + "a movie of " + significantText(std::max(0.0, hi - lo)) +
                 " h at " + std::to_string(fps) + " fps",
             frames, caps::kMovieFrames, "frames", "caps::kMovieFrames: each frame holds a copy of its snapshot; docs/outputs.md, Caps");
  const std::vector<int> idx = movieFrames(t, from, to, hps, fps);
  if (idx.empty()) {
    std::string flags;
    if (flagGiven(o.fromH)) flags += "--from-h " + significantText(o.fromH);
    if (flagGiven(o.toH)) flags += std::string(flags.empty() ? "" : " ") + "--to-h " + significantText(o.toH);
    throw SceneError(flags + ": no snapshot in [" + significantText(flagGiven(o.fromH) ? o.fromH : t.front()) + ", " +
                     significantText(flagGiven(o.toH) ? o.toH : t.back()) + "] h (the run's snapshots: " + significantText(t.front()) + " .. " +
                     significantText(t.back()) + " h)");
  }
  std::vector<Snapshot> out;
  out.reserve(idx.size());
  for (int i : idx) out.push_back(snaps[static_cast<std::size_t>(i)]);
  return out;
}

// the frame of the movie a still shows (SceneError naming the flag and the range)
int stillFrame(const std::vector<Snapshot>& frames, const RenderOptions& o) {
  const bool window = flagGiven(o.fromH) || flagGiven(o.toH);
  if (o.frameGiven) {
    if (o.frame >= static_cast<int>(frames.size()))
      throw SceneError("--frame " + std::to_string(o.frame) + ": the movie has frames 0 .. " +
                       std::to_string(frames.size() - 1));
    return o.frame;
  }
  return snapshotNear(snapshotTimes(frames), o.atH, window ? "window's" : "run's");
}

}  // namespace

int renderRunCommand(const RenderOptions& o) {
  // every input check first, so a bad flag exits 2 before anything is drawn
  const fs::path runDir(o.runDir);
  if (const std::string why = whyUnfinished(runDir); !why.empty()) throw SceneError(o.runDir + ": " + why);
  if (!fs::is_directory(runDir)) throw SceneError(o.runDir + ": run directory not found");
  MovieJob job;
  job.view.kind = parseViewKind(o.view);
  const bool autoSized = o.size == "auto";
  if (!autoSized) std::tie(job.view.width, job.view.height) = parseSize(o.size);
  job.video = parseVideo(o.fps, o.crf);
  // only what is asked for: with no output flag at all, RUN_DIR/movie.mp4 and RUN_DIR/final_top.png;
  // with any of --mp4, --png-dir, --final-png, exactly those (the run directory stays untouched)
  const bool asked = !o.mp4.empty() || !o.pngDir.empty() || !o.finalPng.empty() || !o.png.empty();
  job.mp4 = asked ? o.mp4 : (runDir / "movie.mp4").string();
  const fs::path finalTop = asked ? fs::path(o.finalPng) : runDir / "final_top.png";
  job.view.whiskers = o.whiskers;
  if (o.transparent) {
    // PNG frames only: MP4 has no alpha channel
    if (o.pngDir.empty() && o.png.empty() && o.finalPng.empty())
      throw SceneError("--transparent: applies to PNG pictures; add --png-dir DIR, --png FILE or --final-png FILE");
    if (!o.mp4.empty()) throw SceneError("--transparent: MP4 has no alpha channel; drop --mp4 " + o.mp4);
    job.view.transparent = true;
  }
  if (o.noOverlays) job.view.overlays = false;
  if (o.trace.trace.empty() && (!o.trace.root.empty() || o.trace.pxPerMm != TraceFlags::kUnset || o.trace.downhill != "+y"))
    throw SceneError("--trace-root, --trace-px-per-mm, --trace-downhill: describe the trace of --trace FILE; give --trace");
  const bool scan = flagGiven(o.scanPxPerMm);
  if (scan) {
    checkedNumber("--scan", o.scanPxPerMm, {0, 200, true, false, "px/mm"});
    if (o.png.empty()) throw SceneError("--scan " + significantText(o.scanPxPerMm) + ": a picture; add --png FILE");
    if (o.plateView) throw SceneError("--scan: shows the whole plate already; drop --plate-view");
  }
  if (o.wholePlate && !o.plateView) throw SceneError("--whole-plate: frames --plate-view's whole plate; add --plate-view");
  checkTimeFlags(o, scan || o.plateView);  // a plate's picture: the last snapshot unless told
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
  const Scene scene = loadScene(sceneFile.string());
  const bool plate = isPlateRun(runDir);
  if (!plate && (o.plateView || scan))
    throw SceneError(std::string(o.plateView ? "--plate-view" : "--scan") + ": " + o.runDir + " is a run of one root, not a plate's");
  // a plate: the plate-wide model (its obstacles in plate coordinates), the followed root's growth zone
  Model model = scene.model;
  for (const Seedling& sd : scene.plate.seedlings)
    if (plate && sd.name == o.root) model.growth.zoneLength = sd.model.growth.zoneLength;
  const SceneInfo info = sceneInfoOf(model);
  if (look.shadows && !info.plate)
    throw SceneError("--shadows: " + sceneFile.string() + " has no plate to cast them on (plane.enabled = false)");
  const std::vector<Snapshot> snaps = framesOf(loadSnapshots(runDir, o.root), o, job.video.fps);
  if (plate && !o.trace.trace.empty()) throw SceneError("--trace: aligns at one root's seed; render the root's folder roots/NAME");
  if (plate && (o.plateView || scan)) {
    // the whole plate: (u, v) = (lateral, -downhill) over [0, width] x [-length, 0]
    const double w = scene.plate.params.width / units::mm, l = scene.plate.params.length / units::mm;
    job.view.plateRectMm = std::array<double, 4>{0.0, -l, w, 0.0};
    job.view.centreMm = std::array<double, 2>{0.5 * w, -0.5 * l};
    if (scan) {
      const auto px = [&](double mm) { return 2 * static_cast<int>(std::lround(0.5 * mm * o.scanPxPerMm)); };
      if (px(w) > 16384 || px(l) > 16384)
        throw SceneError("--scan " + significantText(o.scanPxPerMm) + ": a picture of " + std::to_string(px(w)) + "x" + std::to_string(px(l)) +
                         " px; at most 16384 on a side");
      job.view.width = std::max(2, px(w));
      job.view.height = std::max(2, px(l));
      job.view.widthMm = w;
      job.view.marginMm = 0.0;
      job.view.scanLook = true;
      job.view.overlays = false;
    } else if (o.wholePlate) {
      if (autoSized) {
        job.view.width = 1080;
        job.view.height = 2 * static_cast<int>(std::lround(540.0 * l / w));
      }
      // room for the overlays, and on the right for the legend of the seedlings' own values: the plate on
      // the left of the picture
      const double visible = 1.15 * std::max(w, l * job.view.width / job.view.height);
      job.view.widthMm = visible / (1.0 - kSeedLegendShare);
      (*job.view.centreMm)[0] = 0.5 * w + 0.5 * (*job.view.widthMm - visible);
    } else {
      // the sown area: every root over the movie with a margin (frameFor's box), the plate's outline
      // where it comes into the picture
      job.view.centreMm.reset();
      job.view.marginMm = kPlateViewMarginMm;
      if (autoSized) {
        double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
        const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
        for (const Snapshot& sn : snaps)
          for (long i = 0; i < sn.x.cols(); ++i) {
            const Vec3 q = pf.toPlateMm(sn.x.col(i));
            u0 = std::min(u0, q.x()), u1 = std::max(u1, q.x()), v0 = std::min(v0, q.y()), v1 = std::max(v1, q.y());
          }
        const double aspect = std::clamp((v1 - v0 + 2 * kPlateViewMarginMm) / (u1 - u0 + 2 * kPlateViewMarginMm), 0.5, 1.8);
        job.view.width = 1080;
        job.view.height = std::min(2160, 2 * static_cast<int>(std::lround(540.0 * aspect / 0.8)));  // the roots in the middle 80 %
      }
    }
    if (!scan) {
      // each seedling named on the plate, its own beta and R tau in the legend (docs/plate.md, Pictures)
      for (const Seedling& sd : scene.plate.seedlings) {
        View::SeedLabel sl;
        sl.label = sd.name;
        sl.sub = sd.genotype;
        sl.u = sd.position.x() / units::mm;
        sl.v = -sd.position.y() / units::mm;
        char values[160];
        std::snprintf(values, sizeof values, "%s   \xCE\xB2 %.3g   R\xCF\x84 %.3g", sd.name.c_str(), sd.model.tropism.beta,
                      sd.model.tropism.rTau);
        sl.values = values;
        job.view.seedLabels.push_back(std::move(sl));
      }
    }
  }
  if (!o.trace.trace.empty()) {
    // the trace in plate (u, v): its base on the run's seed, its downhill down the plate (-v)
    const TraceTarget t = loadTarget(o.trace, model);
    const Vec3 seed = model.env.plane.frame().toPlateMm(snaps.front().x.col(0));
    for (int i = 0; i < t.plateMm.cols(); ++i) job.view.traceUvMm.push_back({seed.x() + t.plateMm(0, i), seed.y() - t.plateMm(1, i)});
    job.view.traceTimeH = t.timesH;  // a time-lapse trace grows with the frames
  }
  if (autoSized && !job.view.plateRectMm) std::tie(job.view.width, job.view.height) = autoSizeFor(snaps, info, look);
  applyLook(look, runDir, snaps, job);
  checkFieldAgainstPlate(look, fitPlateMm(snaps, info, job));
  // a plate's picture (--scan, --plate-view) without --at-h or --frame: its last snapshot
  const bool plateStill = plate && (scan || o.plateView);
  const int still = o.png.empty() ? -1 : (plateStill && !flagGiven(o.atH) && !o.frameGiven ? static_cast<int>(snaps.size()) - 1 : stillFrame(snaps, o));
  // the write rule, once the flags and the run are known good: the run directory is read and receives
  // only its own movie.mp4 and final_top.png
  WriteRule rule;
  rule.force = o.force;
  rule.inputs = {WriteInput{runDir, {"movie.mp4", "final_top.png"}}};
  if (still >= 0) {
    const Outputs outs = claimOutputs("", o.png, "", rule, "--png");
    renderStill(snaps, info, job, still, o.png);
    if (!o.quiet)
      std::fprintf(stderr, "wrote %s (frame %d, %g h)\n", o.png.c_str(), still, snaps[static_cast<std::size_t>(still)].timeH);
    return 0;
  }
  // writing into the run directory: it is locked as a whole too (a run --force there must wait)
  const OutputLock runLock = asked ? OutputLock() : lockOutput(runDir, "render");
  const Outputs outs = claimOutputs(job.mp4, finalTop, o.pngDir, rule);

  // every check passed: the frame folder is made now (DIR.partial, renamed to DIR when all are written)
  std::optional<StagedFolder> frames;
  if (!o.pngDir.empty()) {
    frames.emplace(o.pngDir, framesFolder(), rule, "--png-dir");
    job.pngDir = frames->work().string();
  }
  renderRun(snaps, info, job, finalTop, o.quiet);
  recordWritten({fs::path(job.mp4), finalTop});  // into the run directory: its marker records them
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
  MovieLook l = look;
  if (l.defaultCamera && l.camera == CameraMode::Fit && !l.inset) {
    // the first picture must show the twist: a follow window in a corner of the whole root, unless
    // the plate the fit view shows is narrower than that window
    l.inset = true;
    applyLook(l, runDir, snaps, job);
    if (l.fieldMm > fitPlateMm(snaps, info, job)) job.inset = false;
  } else {
    applyLook(l, runDir, snaps, job);
  }
  renderRun(snaps, info, job, runDir / "final_top.png", quiet);
  recordWritten({runDir / "movie.mp4", runDir / "final_top.png"});
}

}  // namespace rootsim::app
