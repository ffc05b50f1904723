// `rootsim render` and `rootsim run --movie`: validate the flags and the run directory (SceneError,
// exit 2), then hand the snapshots to the renderer library (RenderError, exit 1)
#include "render_glue.hpp"

#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/png.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/renderer.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim::cli {

namespace {

constexpr int kMinSide = 64;     // [px] room for the overlays
constexpr int kMaxSide = 7680;   // [px] 8K; the 4x multisampled buffers then take ~0.5 GB

// "WxH" -> (W, H), both even and within [kMinSide, kMaxSide]
std::pair<int, int> parseSize(const std::string& s) {
  const std::size_t x = s.find('x');
  auto number = [&](const std::string& part) {
    if (part.empty() || part.size() > 5 || part.find_first_not_of("0123456789") != std::string::npos)
      throw SceneError("--size " + s + ": expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
    return std::stoi(part);
  };
  if (x == std::string::npos) throw SceneError("--size " + s + ": expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
  const int w = number(s.substr(0, x)), h = number(s.substr(x + 1));
  if (w < kMinSide || h < kMinSide || w > kMaxSide || h > kMaxSide)
    throw SceneError("--size " + s + ": width and height must be in " + std::to_string(kMinSide) + ".." +
                     std::to_string(kMaxSide) + " px");
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

SceneInfo sceneInfoOf(const Model& m) {
  SceneInfo si;
  si.alphaDeg = m.env.plane.alpha / units::deg;
  si.beta = m.tropism.beta;
  si.gamma = m.tropism.gamma;
  si.rTau = m.tropism.rTau;
  si.radius = m.rod.radius;
  si.plate = m.env.plane.enabled;
  si.title = m.name;
  return si;
}

std::vector<Snapshot> loadSnapshots(const fs::path& runDir) {
  const fs::path traj = runDir / "trajectory.csv";
  if (!fs::is_regular_file(traj))
    throw SceneError(traj.string() + ": not found (a run directory written with output.trajectory = true)");
  std::vector<Snapshot> snaps = readTrajectory(traj);
  if (snaps.empty()) throw SceneError(traj.string() + ": no snapshots to render");
  return snaps;
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
  const Framing framing = frameFor(snaps, info, top);
  GlRenderer renderer(top.width, top.height);
  writePng(path.string(), renderer.render(buildRenderScene(snaps.back(), info, top, framing)));
}

// the movie and, when asked for, the final picture (always the top view, framed like a top-view movie)
void renderRun(const std::vector<Snapshot>& snaps, const SceneInfo& info, MovieJob job,
               const fs::path& finalTop, bool quiet) {
  const bool top = job.view.kind == View::Kind::Top;
  if (top && !finalTop.empty()) job.finalPng = finalTop.string();
  renderMovie(snaps, info, job, progressLines(quiet, "render " + info.title));
  if (!top && !finalTop.empty()) writeFinalTop(snaps, info, job.view, finalTop);
  if (!quiet) {
    if (!job.mp4.empty()) std::fprintf(stderr, "wrote %s\n", job.mp4.c_str());
    if (!job.pngDir.empty()) std::fprintf(stderr, "wrote %zu frames to %s\n", snaps.size(), job.pngDir.c_str());
    if (!finalTop.empty()) std::fprintf(stderr, "wrote %s\n", finalTop.string().c_str());
  }
}

}  // namespace

int renderRunCommand(const RenderOptions& o) {
  // every input check first, so a bad flag exits 2 before anything is drawn
  const fs::path runDir(o.runDir);
  if (!fs::is_directory(runDir)) throw SceneError(o.runDir + ": run directory not found");
  MovieJob job;
  if (o.view == "top")
    job.view.kind = View::Kind::Top;
  else if (o.view == "3d")
    job.view.kind = View::Kind::Perspective;
  else
    throw SceneError("--view " + o.view + ": expected top or 3d");
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
  auto checkFolder = [](const char* flag, const fs::path& file) {
    const fs::path dir = fs::absolute(file).parent_path();
    if (!fs::is_directory(dir)) throw SceneError(std::string(flag) + " " + file.string() + ": folder " + dir.string() + " not found");
  };
  if (!job.mp4.empty()) checkFolder("--mp4", job.mp4);
  if (!finalTop.empty()) checkFolder("--final-png", finalTop);
  job.pngDir = o.pngDir;
  job.view.whiskers = o.whiskers;
  if (o.transparent) {
    // PNG frames only: MP4 has no alpha channel
    if (o.pngDir.empty()) throw SceneError("--transparent: applies to PNG frames; add --png-dir DIR");
    if (!o.mp4.empty()) throw SceneError("--transparent: MP4 has no alpha channel; drop --mp4 " + o.mp4);
    job.view.transparent = true;
  }
  if (o.noOverlays) job.view.overlays = false;
  if (!o.shaderDir.empty()) {
    for (const char* f : {"tube.vert", "tube.frag", "plane.vert", "plane.frag"})
      if (!fs::is_regular_file(fs::path(o.shaderDir) / f))
        throw SceneError("--shader-dir " + o.shaderDir + ": " + f + " not found");
    job.renderer.shaderDir = o.shaderDir;
  }
  const fs::path sceneFile = runDir / "scene.toml";
  if (!fs::is_regular_file(sceneFile)) throw SceneError(sceneFile.string() + ": not found (not a run directory?)");
  const SceneInfo info = sceneInfoOf(loadScene(sceneFile.string()).model);
  const std::vector<Snapshot> snaps = loadSnapshots(runDir);
  if (autoSized) std::tie(job.view.width, job.view.height) = autoSize(snaps, info);

  renderRun(snaps, info, job, finalTop, o.quiet);
  return 0;
}

void renderRunMovie(const fs::path& runDir, bool quiet) {
  const SceneInfo info = sceneInfoOf(loadScene((runDir / "scene.toml").string()).model);
  MovieJob job;
  job.mp4 = (runDir / "movie.mp4").string();
  const std::vector<Snapshot> snaps = loadSnapshots(runDir);
  std::tie(job.view.width, job.view.height) = autoSize(snaps, info);
  renderRun(snaps, info, job, runDir / "final_top.png", quiet);
}

}  // namespace rootsim::cli
