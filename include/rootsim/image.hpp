#pragma once
// An RGBA picture in memory: what the renderer produces and what the PNG and video writers consume.
// Also home of RenderError, the one exception type of the rendering layer.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <cstdint>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"

namespace rootsim {

// a failure anywhere in rendering or encoding; the message names the failing call and its code
// (e.g. "avcodec_open2(libx264): Invalid argument (-22)") or the rejected input. A kind of RunError:
// the CLI exits 1 on it; its own input checks (flags, run directory) throw SceneError instead.
class RenderError : public RunError {
 public:
  using RunError::RunError;
};

struct Image {
  int width = 0;                  // [px]
  int height = 0;                 // [px]
  std::vector<std::uint8_t> rgba; // 8-bit sRGB RGBA, straight (not premultiplied) alpha,
                                  // rows top first, no padding               (4 * width * height)

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(4) * w * h, 0) {}

  std::size_t index(int x, int y) const { return (static_cast<std::size_t>(y) * width + x) * 4; }
  // pointer to the 4 bytes of pixel (x, y); (0, 0) is the top-left corner
  std::uint8_t* at(int x, int y) { return rgba.data() + index(x, y); }
  const std::uint8_t* at(int x, int y) const { return rgba.data() + index(x, y); }
};

// copies src into dst with src's top-left corner at (x, y) of dst, clipped to dst
inline void blit(const Image& src, Image& dst, int x, int y) {
  for (int r = 0; r < src.height; ++r) {
    const int yy = y + r;
    if (yy < 0 || yy >= dst.height) continue;
    const int x0 = std::max(0, x), x1 = std::min(dst.width, x + src.width);
    if (x0 >= x1) continue;
    std::memcpy(dst.at(x0, yy), src.at(x0 - x, r), static_cast<std::size_t>(4) * (x1 - x0));
  }
}

}  // namespace rootsim
