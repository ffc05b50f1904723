// snapshots -> composed pictures -> MP4 / PNG files. This thread builds the scenes and draws (llvmpipe);
// a second thread (frame_sink.cpp) converts and encodes and writes PNG frames.
#include "rootsim/movie.hpp"

#include <algorithm>
#include <cmath>

#include "frame_sink.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/png.hpp"

namespace rootsim {

namespace {
void checkJob(const MovieJob& job) {
  if (job.view.transparent && !job.mp4.empty())
    throw RenderError("movie " + job.mp4 + ": a transparent background is for PNG only (MP4 has no alpha)");
}
}  // namespace

struct MovieRecorder::Impl {
  FrameComposer composer;
  detail::FrameSink sink;
  Image drawn;  // this thread's picture

  Impl(const SceneInfo& info, const MovieJob& job, FramePlan plan)
      : composer(info, (checkJob(job), job), std::move(plan)),
        sink(job.mp4, job.pngDir, job.finalPng, job.view.width, job.view.height, job.video) {}

  void add(const Snapshot& snap) {
    composer.compose(snap, sink.frames(), drawn);
    sink.push(drawn);
  }
};

MovieRecorder::MovieRecorder(const SceneInfo& info, const MovieJob& job, const Framing& framing)
    : impl_(std::make_unique<Impl>(info, job, [&] {
        FramePlan p;
        p.view = {framing};
        return p;
      }())) {}
MovieRecorder::MovieRecorder(const SceneInfo& info, const MovieJob& job, FramePlan plan)
    : impl_(std::make_unique<Impl>(info, job, std::move(plan))) {}
MovieRecorder::~MovieRecorder() = default;
void MovieRecorder::add(const Snapshot& snap) { impl_->add(snap); }
void MovieRecorder::finish() { impl_->sink.finish(); }
int MovieRecorder::frames() const { return impl_->sink.frames(); }

void renderMovie(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job,
                 const MovieProgress& progress) {
  MovieJob j = job;
  // one colour range for the whole movie
  if (j.view.colourBy != ColourField::None) j.view.colourRange = fieldRange(snaps, info, j.view.colourBy);
  MovieRecorder rec(info, j, planFrames(snaps, info, j));
  const int total = static_cast<int>(snaps.size());
  for (int i = 0; i < total; ++i) {
    rec.add(snaps[static_cast<std::size_t>(i)]);
    if (progress) progress(i + 1, total);
  }
  rec.finish();
}

void renderStill(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job, int frame,
                 const std::string& path) {
  if (frame < 0 || frame >= static_cast<int>(snaps.size()))
    throw RenderError("still: frame " + std::to_string(frame) + " outside the movie's 0.." + std::to_string(snaps.size() - 1));
  // what renderMovie and MovieRecorder do, for one frame
  MovieJob j = job;
  j.mp4.clear();
  j.pngDir.clear();
  j.finalPng.clear();
  checkJob(j);
  if (j.view.colourBy != ColourField::None) j.view.colourRange = fieldRange(snaps, info, j.view.colourBy);
  FrameComposer composer(info, j, planFrames(snaps, info, j));
  Image img;
  composer.compose(snaps[static_cast<std::size_t>(frame)], frame, img);
  writePng(path, img);
}

int nearestSnapshot(const std::vector<double>& timesH, double timeH) {
  if (timesH.empty()) throw RenderError("movie: no snapshots");
  // the first at or after timeH, then the earlier neighbour when it is as near or nearer
  const auto it = std::lower_bound(timesH.begin(), timesH.end(), timeH);
  if (it == timesH.end()) return static_cast<int>(timesH.size()) - 1;
  const int i = static_cast<int>(it - timesH.begin());
  if (i > 0 && timeH - timesH[static_cast<std::size_t>(i - 1)] <= *it - timeH) return i - 1;
  return i;
}

std::vector<int> movieFrames(const std::vector<double>& timesH, double fromH, double toH, double hoursPerSecond,
                             int fps) {
  std::vector<int> window;
  for (std::size_t i = 0; i < timesH.size(); ++i)
    if (timesH[i] >= fromH && timesH[i] <= toH) window.push_back(static_cast<int>(i));
  if (window.empty() || !(hoursPerSecond > 0)) return window;
  std::vector<double> wt;
  for (int i : window) wt.push_back(timesH[static_cast<std::size_t>(i)]);
  const double ta = wt.front(), tb = wt.back(), dt = hoursPerSecond / fps;
  // a relative tolerance, so a window of exactly k frame steps gives k + 1 frames
  const long n = static_cast<long>(std::floor((tb - ta) / dt * (1.0 + 1e-12) + 1e-9)) + 1;
  std::vector<int> frames;
  frames.reserve(static_cast<std::size_t>(n));
  for (long f = 0; f < n; ++f)
    frames.push_back(window[static_cast<std::size_t>(nearestSnapshot(wt, ta + static_cast<double>(f) * dt))]);
  return frames;
}

void renderPng(const Snapshot& snap, const SceneInfo& info, const View& view, const std::string& path) {
  const Framing framing = frameFor({snap}, info, view);
  GlRenderer renderer(view.width, view.height);
  writePng(path, renderer.render(buildRenderScene(snap, info, view, framing)));
}

}  // namespace rootsim
