#pragma once
// H.264 MP4 writer: libavcodec's libx264, yuv420p, BT.709 limited range, one frame per add().
#include <memory>
#include <string>

#include "rootsim/image.hpp"

namespace rootsim {

// "" when path is an MP4 rootsim wrote: it opens with libavformat as MP4, its "comment" tag holds
// rootsim's signature and the sha256 of its packets' data, which they still hash to; else why not. The
// write rule (write_rule.hpp) calls it through the check the app registers (rootsim_io links no libav).
std::string whyNotSignedMovie(const std::string& path);

struct VideoOptions {
  int fps = 30;                    // frames per second
  int crf = 18;                    // x264 constant rate factor, 0 (lossless) .. 51; 18 looks lossless
  std::string preset = "veryfast"; // x264 preset: ultrafast .. veryslow
};

// Streams frames into "<path>.partial" and renames it to path in finish(); a writer destroyed
// without finish() closes the partial file playable and leaves it under the .partial name.
// width and height must be positive and even (yuv420p); every added image must have that size.
class VideoWriter {
 public:
  VideoWriter(const std::string& path, int width, int height, const VideoOptions& opt = {});
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  void add(const Image& img);      // encode one frame; throws RenderError
  void finish();                   // flush the encoder, write the trailer, rename; idempotent
  int frames() const;              // frames added so far

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rootsim
