#pragma once
// High level: snapshots -> composed frames -> MP4 and/or numbered PNG frames. A frame is the view
// (fit or follow camera), optionally a follow inset in its corner and a panel of time series beside
// or below it. Drawing (this thread) and encoding (a second thread) overlap through a one-slot frame
// queue, so both cores work.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rootsim/camera.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/renderer.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/video.hpp"

namespace rootsim {

// one time series of the plot panel (a column of timeseries.csv)
struct PlotSeries {
  std::string name;             // axis title, e.g. "θ_tip", "E_b" (UTF-8)
  std::string unit;             // e.g. "°", "J"; empty: dimensionless
  bool siPrefix = false;        // scale the unit with an SI prefix (J -> nJ) to readable numbers
  std::vector<double> timeH;    // [h], increasing
  std::vector<double> value;    // in unit                                     (timeH.size())
};

struct MovieJob {
  std::string mp4;        // H.264 MP4 path; empty: none
  std::string pngDir;     // directory for frame_00000.png ...; created if missing; empty: none
  std::string finalPng;   // PNG of the last frame; empty: none
  View view;              // frame size (the whole composed frame), kind, colours, overlays, shadows
  VideoOptions video;     // fps, crf, x264 preset
  RendererOptions renderer;  // MSAA samples; shaders from disk (development)
  CameraMode camera = CameraMode::Fit;  // the main view's camera
  double fieldMm = 2.0;   // follow window width [mm] (camera follow, and the inset)
  bool inset = false;     // a follow window in the lower left corner of the view, its region marked
  std::vector<PlotSeries> plots;  // panel of time series (beside a landscape frame, below a portrait one)
};

// where the parts of a composed frame go [px, from the top-left corner]
struct FrameLayout {
  int width = 0, height = 0;                  // the whole frame
  int viewX = 0, viewY = 0, viewW = 0, viewH = 0;
  bool panel = false;
  int panelX = 0, panelY = 0, panelW = 0, panelH = 0;
  bool inset = false;
  int insetX = 0, insetY = 0, insetW = 0, insetH = 0;
};
// the view takes the whole frame, or 64 % of its width (landscape) / height (portrait) beside a panel;
// the inset is a square of 0.42 x the view's shorter side, by default in its lower left corner
FrameLayout frameLayout(int width, int height, bool plots, bool inset);

// the cameras of a whole movie, fixed before the first frame
struct FramePlan {
  std::vector<Framing> view;   // per snapshot (one entry: the same for all)
  std::vector<Framing> inset;  // per snapshot; empty without an inset
  int insetX = -1, insetY = -1;  // the inset's corner in the frame [px]; -1: frameLayout's default.
                                 // planFrames picks the corner (clear of the overlays) that covers
                                 // the fewest of the root's nodes over the whole movie
};
FramePlan planFrames(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job);

// draws composed frames: view, inset and its mark, plot panel. Owns the GL renderers.
class FrameComposer {
 public:
  FrameComposer(const SceneInfo& info, const MovieJob& job, FramePlan plan);
  ~FrameComposer();
  FrameComposer(const FrameComposer&) = delete;
  FrameComposer& operator=(const FrameComposer&) = delete;

  // frame number `frame` (index into the plan) showing snap; out is resized to the frame
  void compose(const Snapshot& snap, int frame, Image& out);
  const FrameLayout& layout() const;
  // where (timeH, value) of plot series i lands in the frame [px]
  Eigen::Vector2d plotPixel(int series, double timeH, double value) const;
  // the inset's region as drawn on the view in the last composed frame: its 4 corners [px, frame]
  std::vector<Eigen::Vector2d> lastInsetMark() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// progress(done, total) after each frame
using MovieProgress = std::function<void(int done, int total)>;

// render every snapshot (cameras from planFrames; with View::colourBy, View::colourRange is replaced
// by fieldRange over all snapshots). Throws RenderError; an MP4 interrupted by an error is left as
// "<mp4>.partial".
void renderMovie(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job,
                 const MovieProgress& progress = {});

// the same, one snapshot at a time, for rendering while a simulation runs: the framing is given
// up front (e.g. frameFor over the expected extent, or View::centreMm / widthMm; fit camera), or a
// full plan (planFrames). With View::colourBy the caller sets View::colourRange (renderMovie computes
// it with fieldRange over all snapshots)
class MovieRecorder {
 public:
  MovieRecorder(const SceneInfo& info, const MovieJob& job, const Framing& framing);
  MovieRecorder(const SceneInfo& info, const MovieJob& job, FramePlan plan);
  ~MovieRecorder();       // without finish(): stops the encoder, leaves "<mp4>.partial"
  MovieRecorder(const MovieRecorder&) = delete;
  MovieRecorder& operator=(const MovieRecorder&) = delete;

  void add(const Snapshot& snap);  // draw now, encode on the second thread; rethrows its errors
  void finish();                   // drain the queue, close the MP4, write finalPng
  int frames() const;              // frames added

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// one picture straight to a PNG file (framing from this snapshot alone unless the view fixes it)
void renderPng(const Snapshot& snap, const SceneInfo& info, const View& view, const std::string& path);

// several runs side by side on one scale and one clock (`rootsim montage`)
struct MontageRun {
  std::vector<Snapshot> snaps;  // time ordered
  SceneInfo info;
  std::string label;            // drawn under the tile (e.g. the parameters that differ)
};
struct MontageJob {
  std::string mp4;        // empty: none
  std::string pngDir;     // empty: none
  View view;              // the whole frame's size; kind, colours, shadows and overlays of every tile
  VideoOptions video;
  RendererOptions renderer;
};
// the montage's clock: every snapshot time of every run, sorted, equal times (within 1e-9 h) merged
std::vector<double> montageClock(const std::vector<MontageRun>& runs);
// the snapshot a run shows at time tH: the last one at or before tH (the first one before it starts;
// a run that ended holds its last frame)
int snapshotAt(const std::vector<Snapshot>& snaps, double tH);
// tiles: columns x rows chosen for the largest common scale; each tile frames its run around its base
// node with the same width in mm, so bases line up and lengths compare
struct MontageLayout {
  int cols = 1, rows = 1;
  int tileW = 0, tileH = 0;   // [px]
  int headerH = 0;            // [px] band with the time at the top
  std::vector<Framing> framing;  // per run
};
MontageLayout montageLayout(const std::vector<MontageRun>& runs, const View& view);
void renderMontage(const std::vector<MontageRun>& runs, const MontageJob& job, const MovieProgress& progress = {});

}  // namespace rootsim
