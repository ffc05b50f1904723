#pragma once
// overlay texts and rectangles drawn onto a finished picture on the CPU (stb_truetype)
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rootsim/image.hpp"
#include "rootsim/overlay_layout.hpp"
#include "rootsim/render_scene.hpp"

namespace rootsim::detail {

// the overlays' ink: scale bars, ticks, arrows and panel axes (render_scene.cpp, compose.cpp)
inline constexpr std::array<std::uint8_t, 4> kInk{40, 40, 40, 255};

// a TrueType font with a cache of rasterised glyphs; throws RenderError if the file is missing or
// not a font
class OverlayPainter {
 public:
  OverlayPainter();
  ~OverlayPainter();
  OverlayPainter(const OverlayPainter&) = delete;
  OverlayPainter& operator=(const OverlayPainter&) = delete;

  // draw scene.rects, scene.lines, then scene.texts over img (straight alpha "over"), leaving the
  // pixels of scene.keepOut as they are (but under lines drawn overRoot)
  void draw(const RenderScene& scene, Image& img);
  // the same for loose items (the compositor's panels, marks and labels); keepOut's pixel (x, y) is the
  // image's (x + offX, y + offY)
  void draw(const std::vector<OverlayRect>& rects, const std::vector<OverlayLine>& lines,
            const std::vector<OverlayText>& texts, const std::string& fontPath, Image& img,
            const RootFootprint* keepOut = nullptr, int offX = 0, int offY = 0);
  // width of text in pixels at sizePx with the font at fontPath
  float textWidth(const std::string& fontPath, const std::string& text, float sizePx);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// width of text in pixels at sizePx with the font at fontPath, for laying overlays out before they are
// painted (one process-wide font cache, thread safe); an estimate (0.6 sizePx per code point) when
// the font cannot be read: painting then throws the RenderError that names it
float measureText(const std::string& fontPath, const std::string& text, float sizePx);

}  // namespace rootsim::detail
