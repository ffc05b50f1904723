#pragma once
// `rootsim montage RUN_DIR...` (docs/cli.md): several run directories side by side on one scale and one
// clock, to an MP4 and/or PNG frames. Bad flags or run directories throw SceneError (exit 2) before
// anything is written; render or encoder failures RenderError (exit 1).
#include <string>
#include <vector>

namespace rootsim::app {

struct MontageOptions {
  std::vector<std::string> runDirs;
  std::string mp4;           // at least one of mp4, pngDir
  std::string pngDir;
  std::string size = "1280x720";
  std::string labels;        // comma-separated, one per run; default: the scene keys that differ
  std::string view = "top";
  int fps = 30;
  int crf = 18;
  std::string colorBy = "none";
  bool shadows = false;
  bool force = false;        // replace outputs rootsim wrote earlier (never a user's file)
  bool quiet = false;
};
int montageRunsCommand(const MontageOptions& o);

}  // namespace rootsim::app
