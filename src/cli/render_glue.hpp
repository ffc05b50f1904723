#pragma once
// The CLI's door to the renderer (compiled only when rootsim_render is built: ROOTSIM_HAVE_RENDER).
#include <filesystem>

#include "commands.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim::cli {

// `rootsim render RUN_DIR`: RUN_DIR/trajectory.csv -> MP4 (default RUN_DIR/movie.mp4), optional PNG
// frames, and RUN_DIR/final_top.png (last snapshot, top view). Bad flags, a missing run directory or
// a malformed trajectory throw SceneError (exit 2); render or encoder failures RenderError (exit 1).
int renderRunCommand(const RenderOptions& o);

// `rootsim run --movie`: after the run, RUN_DIR/movie.mp4 (top view, 1280x720, 30 fps, crf 18) and
// RUN_DIR/final_top.png from RUN_DIR/trajectory.csv
void renderRunMovie(const std::filesystem::path& runDir, bool quiet);

}  // namespace rootsim::cli
