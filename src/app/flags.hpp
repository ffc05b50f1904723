#pragma once
// internal: the flags `render` and `montage` share, checked (SceneError naming the flag: exit 2)
#include <string>
#include <utility>
#include <vector>

#include "rootsim/colour_map.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/video_writer.hpp"

namespace rootsim::app {

// --view: "top" or "3d"
View::Kind parseViewKind(const std::string& v);
// --size "WxH" -> (W, H), both even, at least 64 px (room for the overlays), at most 3840x2160 (or
// 2160x3840)
std::pair<int, int> parseSize(const std::string& s);
// --fps 1..240 and --crf 0..51
VideoOptions parseVideo(int fps, int crf);
// --color-by: one of colourFieldNames()
ColourField parseColourBy(const std::string& name);

}  // namespace rootsim::app
