#pragma once
// A composed frame of a movie: the view (fit or follow camera), optionally a follow inset in its corner
// and a panel of time series beside or below it; the cameras of a whole movie (planFrames).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "rootsim/camera.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/overlay_layout.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/video_writer.hpp"

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
  int insetSide = -1;            // its side [px]; -1: frameLayout's. planFrames puts it in the first
                                 // corner (clear of the overlays' bands) the root's footprint over the
                                 // whole movie leaves free, else the nearest free place, shrunk if need be
  bool insetDropped = false;     // no free place even shrunk: no inset (it would hide the root)
  // the root's footprint in the view over the frames whose overlays hold still: frame f uses
  // footprint[f / footprintFrames] (a fixed camera: one for the movie); empty: each frame its own
  std::vector<std::shared_ptr<const RootFootprint>> footprint;
  int footprintFrames = 1;
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
  // the inset's magnification over the view in the last composed frame (its "x6" label); 0 without
  // an inset or overlays
  double lastInsetMagnification() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rootsim
