#pragma once
// `rootsim montage RUN_DIR...` (docs/cli.md): several run directories side by side on one scale and one
// clock, to an MP4 and/or PNG frames. Bad flags or run directories throw SceneError (exit 2) before
// anything is written; render or encoder failures RenderError (exit 1).
#include <string>
#include <vector>

#include "rootsim/model.hpp"

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

// the automatic labels of a montage: per run the scene keys whose values differ, as symbols with units
// ("α = 40°, β = 0.2"; keys without a symbol as "key = value"), the run's name (dirNames) when nothing
// differs; and a caption with the paper's parameters all runs share ("β = γ = 0.1, Rτ = 0")
struct MontageLabels {
  std::vector<std::string> labels;
  std::string caption;
};
MontageLabels montageLabels(const std::vector<Model>& models, const std::vector<std::string>& dirNames);

}  // namespace rootsim::app
