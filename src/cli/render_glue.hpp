#pragma once
// The CLI's door to the renderer (compiled only when rootsim_render is built: ROOTSIM_HAVE_RENDER).
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rootsim/camera.hpp"
#include "rootsim/colour_map.hpp"
#include "rootsim/model.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim::cli {

// the movie look flags, checked (SceneError naming the flag: exit 2)
struct MovieLook {
  CameraMode camera = CameraMode::Fit;
  double fieldMm = 2.0;
  bool inset = false;
  ColourField colourBy = ColourField::None;
  std::vector<std::string> plots;  // keys in the order given
  bool shadows = false;
};
MovieLook parseLook(const LookOptions& o);
// --field-mm larger than the plate a fit view shows (plateMm wide) is refused (SceneError)
void checkFieldAgainstPlate(const MovieLook& look, double plateMm);

// `rootsim render RUN_DIR`: RUN_DIR/trajectory.csv -> MP4 (default RUN_DIR/movie.mp4), optional PNG
// frames, and RUN_DIR/final_top.png (last snapshot, top view). Bad flags, a missing run directory or
// a malformed trajectory throw SceneError (exit 2); render or encoder failures RenderError (exit 1).
int renderRunCommand(const RenderOptions& o);

// `rootsim run --movie`: after the run, RUN_DIR/movie.mp4 (top view, size auto, 30 fps, crf 18, with
// the look's camera, colours and plots) and RUN_DIR/final_top.png from RUN_DIR/trajectory.csv; model is
// the run's (the scene `run` parsed: scene.toml is not read again)
void renderRunMovie(const std::filesystem::path& runDir, const Model& model, bool quiet, const MovieLook& look);

// `rootsim montage RUN_DIR...`
int montageRunsCommand(const MontageOptions& o);

}  // namespace rootsim::cli
