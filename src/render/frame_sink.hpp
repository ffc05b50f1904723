#pragma once
// where finished frames go: PNG files and the H.264 encoder, on a second thread behind a one-slot queue
// (used by movie.cpp and montage.cpp)
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "rootsim/image.hpp"
#include "rootsim/video_writer.hpp"

namespace rootsim::detail {

class FrameSink {
 public:
  // mp4 / pngDir / finalPng: empty for none; pngDir is created; throws RenderError
  FrameSink(const std::string& mp4, const std::string& pngDir, const std::string& finalPng, int width, int height,
            const VideoOptions& video);
  ~FrameSink();  // without finish(): stops the encoder, leaves "<mp4>.partial"
  FrameSink(const FrameSink&) = delete;
  FrameSink& operator=(const FrameSink&) = delete;

  // hand img to the encoder thread; img comes back holding a free buffer (no allocation per frame)
  void push(Image& img);
  void finish();       // drain, close the MP4, write finalPng; rethrows the encoder's error
  int frames() const { return added_; }

 private:
  void encodeLoop();
  void stopEncoder();
  std::string pngDir_, finalPng_;
  std::unique_ptr<VideoWriter> video_;
  int added_ = 0;
  std::mutex mutex_;
  std::condition_variable cv_;
  Image slot_, work_;
  bool full_ = false, stop_ = false;
  std::exception_ptr error_;
  std::thread encoder_;
};

}  // namespace rootsim::detail
