// `rootsim render` and `rootsim run --movie`: validate the flags and the run directory (SceneError,
// exit 2), then hand the snapshots to the renderer library (RenderError, exit 1)
#include "rootsim/render_run.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <tuple>
#include <vector>

#include "flags.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/png.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"
#include "rootsim/write_rule.hpp"
#include "run_files.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

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
  job.video = parseVideo(o.fps, o.crf);
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

}  // namespace rootsim::app
