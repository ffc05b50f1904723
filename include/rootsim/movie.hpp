#pragma once
// High level: snapshots -> composed frames (compose.hpp) -> MP4 and/or numbered PNG frames. Drawing (this
// thread) and encoding (a second thread) overlap through a one-slot frame queue, so both cores work.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rootsim/compose.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

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

// one frame of the movie renderMovie(snaps, info, job) makes, to the PNG file `path`: the same plan
// (the fit camera framed over all snaps, the follow camera's smoothing over all of them), the same
// colour range, the same pixels as that movie's frame_<frame>.png; costs one frame's drawing. Throws
// RenderError (also on a frame outside 0 .. snaps.size() - 1)
void renderStill(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job, int frame,
                 const std::string& path);

// frame planning in time (docs/rendering.md, "Time windows and speed"):
// nearestSnapshot (the snapshot nearest a time): rootsim/snapshot.hpp
// the snapshots of a movie from fromH to toH at hoursPerSecond growth hours per second of movie at fps:
// the window is the snapshots with fromH <= t <= toH (first t_a, last t_b); with hoursPerSecond <= 0 each
// of them is one frame; otherwise there are floor((t_b - t_a) fps / hoursPerSecond) + 1 frames and frame
// f shows the window's snapshot nearest t_a + f hoursPerSecond / fps (ties to the earlier), so a fast
// movie skips snapshots and a slow one repeats them. Indices into timesH; empty when the window holds
// no snapshot
std::vector<int> movieFrames(const std::vector<double>& timesH, double fromH, double toH, double hoursPerSecond,
                             int fps);

// one picture straight to a PNG file (framing from this snapshot alone unless the view fixes it)
void renderPng(const Snapshot& snap, const SceneInfo& info, const View& view, const std::string& path);

}  // namespace rootsim
