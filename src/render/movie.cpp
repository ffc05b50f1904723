// snapshots -> pictures -> MP4 / PNG files. This thread builds the scene and draws (llvmpipe); a second
// thread converts and encodes (swscale + x264) and writes PNG frames. They meet at a one-slot queue, so
// drawing frame k+1 overlaps encoding frame k and at most three frames exist at any time.
#include "rootsim/movie.hpp"

#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <system_error>
#include <thread>

#include "rootsim/png.hpp"
#include "rootsim/renderer.hpp"

namespace rootsim {

namespace {

std::string framePath(const std::string& dir, int index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d.png", index);
  return (std::filesystem::path(dir) / name).string();
}

void checkJob(const MovieJob& job) {
  if (job.view.transparent && !job.mp4.empty())
    throw RenderError("movie " + job.mp4 + ": a transparent background is for PNG only (MP4 has no alpha)");
  if (!job.pngDir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(job.pngDir, ec);
    if (ec || !std::filesystem::is_directory(job.pngDir))
      throw RenderError("movie: cannot create the PNG folder " + job.pngDir + ": " +
                        (ec ? ec.message() : std::string("not a directory")));
  }
}

}  // namespace

struct MovieRecorder::Impl {
  SceneInfo info;
  MovieJob job;
  Framing framing;
  GlRenderer renderer;
  std::unique_ptr<VideoWriter> video;
  int added = 0;      // frames handed to the encoder thread
  Image drawn;        // this thread's picture

  // the one-slot queue
  std::mutex mutex;
  std::condition_variable cv;
  Image slot;
  bool full = false, stop = false;
  std::exception_ptr error;   // first failure of the encoder thread
  Image work;                 // the encoder thread's picture; after join(): the last frame
  std::thread encoder;

  Impl(const SceneInfo& i, const MovieJob& j, const Framing& f)
      : info(i), job(j), framing(f), renderer(j.view.width, j.view.height, j.renderer) {
    checkJob(job);
    if (!job.mp4.empty()) video = std::make_unique<VideoWriter>(job.mp4, job.view.width, job.view.height, job.video);
    encoder = std::thread([this] { encodeLoop(); });
  }

  ~Impl() { stopEncoder(); }

  void stopEncoder() {
    if (!encoder.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    cv.notify_all();
    encoder.join();
  }

  // frames in arrival order: PNG file, then the video encoder
  void encodeLoop() {
    int index = 0;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex);
        cv.wait(lock, [&] { return full || stop; });
        if (!full) return;
        std::swap(slot, work);
        full = false;
      }
      cv.notify_all();
      try {
        if (!job.pngDir.empty()) writePng(framePath(job.pngDir, index), work);
        if (video) video->add(work);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        error = std::current_exception();
        cv.notify_all();
        return;
      }
      ++index;
    }
  }

  void add(const Snapshot& snap) {
    const RenderScene scene = buildRenderScene(snap, info, job.view, framing);
    renderer.render(scene, drawn);
    std::unique_lock<std::mutex> lock(mutex);
    cv.wait(lock, [&] { return !full || error; });
    if (error) std::rethrow_exception(error);
    std::swap(slot, drawn);
    full = true;
    ++added;
    lock.unlock();
    cv.notify_all();
  }

  void finish() {
    stopEncoder();
    if (error) std::rethrow_exception(error);
    if (video) video->finish();
    if (!job.finalPng.empty()) {
      if (added == 0) throw RenderError("movie: no frames, so no final picture " + job.finalPng);
      writePng(job.finalPng, work);
    }
  }
};

MovieRecorder::MovieRecorder(const SceneInfo& info, const MovieJob& job, const Framing& framing)
    : impl_(std::make_unique<Impl>(info, job, framing)) {}
MovieRecorder::~MovieRecorder() = default;
void MovieRecorder::add(const Snapshot& snap) { impl_->add(snap); }
void MovieRecorder::finish() { impl_->finish(); }
int MovieRecorder::frames() const { return impl_->added; }

void renderMovie(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job,
                 const MovieProgress& progress) {
  const Framing framing = frameFor(snaps, info, job.view);
  MovieRecorder rec(info, job, framing);
  const int total = static_cast<int>(snaps.size());
  for (int i = 0; i < total; ++i) {
    rec.add(snaps[static_cast<std::size_t>(i)]);
    if (progress) progress(i + 1, total);
  }
  rec.finish();
}

void renderPng(const Snapshot& snap, const SceneInfo& info, const View& view, const std::string& path) {
  const Framing framing = frameFor({snap}, info, view);
  GlRenderer renderer(view.width, view.height);
  writePng(path, renderer.render(buildRenderScene(snap, info, view, framing)));
}

}  // namespace rootsim
