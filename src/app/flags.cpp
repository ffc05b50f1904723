// the flags `render` and `montage` share
#include "flags.hpp"

#include <algorithm>
#include <sstream>

#include "rootsim/errors.hpp"

namespace rootsim::app {

namespace {
constexpr int kMinSide = 64;     // [px] room for the overlays
constexpr int kMaxLong = 3840;   // [px] 4K UHD: the longer side at most 3840,
constexpr int kMaxShort = 2160;  // [px] the shorter at most 2160 (landscape or portrait)
}  // namespace

View::Kind parseViewKind(const std::string& v) {
  if (v == "top") return View::Kind::Top;
  if (v == "3d") return View::Kind::Perspective;
  throw SceneError("--view " + v + ": expected top or 3d");
}

std::pair<int, int> parseSize(const std::string& s) {
  const std::size_t x = s.find('x');
  auto number = [&](const std::string& part) {
    if (part.empty() || part.size() > 5 || part.find_first_not_of("0123456789") != std::string::npos)
      throw SceneError("--size " + s + ": expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
    return std::stoi(part);
  };
  if (x == std::string::npos) throw SceneError("--size " + s + ": expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
  const int w = number(s.substr(0, x)), h = number(s.substr(x + 1));
  if (w < kMinSide || h < kMinSide)
    throw SceneError("--size " + s + ": width and height must be at least " + std::to_string(kMinSide) + " px");
  if (std::max(w, h) > kMaxLong || std::min(w, h) > kMaxShort)
    throw SceneError("--size " + s + ": at most 3840x2160 (or 2160x3840)");
  if (w % 2 != 0 || h % 2 != 0)
    throw SceneError("--size " + s + ": width and height must be even (H.264 yuv420p), e.g. " +
                     std::to_string(w + w % 2) + "x" + std::to_string(h + h % 2));
  return {w, h};
}

VideoOptions parseVideo(int fps, int crf) {
  if (fps < 1 || fps > 240) throw SceneError("--fps " + std::to_string(fps) + ": expected 1..240");
  if (crf < 0 || crf > 51) throw SceneError("--crf " + std::to_string(crf) + ": expected 0..51");
  VideoOptions v;
  v.fps = fps;
  v.crf = crf;
  return v;
}

ColourField parseColourBy(const std::string& name) {
  ColourField f = ColourField::None;
  if (!parseColourField(name, f)) throw SceneError("--color-by " + name + ": expected one of " + colourFieldNames());
  return f;
}

}  // namespace rootsim::app
