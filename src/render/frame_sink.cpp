// where finished frames go: a second thread converts and encodes (swscale + x264) and writes PNG frames.
// It meets the drawing thread at a one-slot queue, so drawing frame k+1 overlaps encoding frame k and at
// most three frames exist at any time.
#include "frame_sink.hpp"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "rootsim/png.hpp"

namespace rootsim {

namespace detail {

namespace {
std::string framePath(const std::string& dir, int index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d.png", index);
  return (std::filesystem::path(dir) / name).string();
}
}  // namespace

FrameSink::FrameSink(const std::string& mp4, const std::string& pngDir, const std::string& finalPng, int width,
                     int height, const VideoOptions& video)
    : pngDir_(pngDir), finalPng_(finalPng) {
  if (!pngDir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(pngDir, ec);
    if (ec || !std::filesystem::is_directory(pngDir))
      throw RenderError("movie: cannot create the PNG folder " + pngDir + ": " +
                        (ec ? ec.message() : std::string("not a directory")));
  }
  if (!mp4.empty()) video_ = std::make_unique<VideoWriter>(mp4, width, height, video);
  encoder_ = std::thread([this] { encodeLoop(); });
}

FrameSink::~FrameSink() { stopEncoder(); }

void FrameSink::stopEncoder() {
  if (!encoder_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  encoder_.join();
}

// frames in arrival order: PNG file, then the video encoder
void FrameSink::encodeLoop() {
  int index = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      cv_.wait(lock, [&] { return full_ || stop_; });
      if (!full_) return;
      std::swap(slot_, work_);
      full_ = false;
    }
    cv_.notify_all();
    try {
      if (!pngDir_.empty()) writePng(framePath(pngDir_, index), work_);
      if (video_) video_->add(work_);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      cv_.notify_all();
      return;
    }
    ++index;
  }
}

void FrameSink::push(Image& img) {
  std::unique_lock<std::mutex> lock(mutex_);
  cv_.wait(lock, [&] { return !full_ || error_; });
  if (error_) std::rethrow_exception(error_);
  std::swap(slot_, img);
  full_ = true;
  ++added_;
  lock.unlock();
  cv_.notify_all();
}

void FrameSink::finish() {
  stopEncoder();
  if (error_) std::rethrow_exception(error_);
  if (video_) video_->finish();
  if (!finalPng_.empty()) {
    if (added_ == 0) throw RenderError("movie: no frames, so no final picture " + finalPng_);
    writePng(finalPng_, work_);
  }
}

}  // namespace detail

}  // namespace rootsim
