#pragma once
// `rootsim render RUN_DIR` and `rootsim run --movie` (docs/cli.md): a run directory's trajectory to a
// movie and its final picture.
#include <filesystem>
#include <string>

#include "rootsim/compare_trace.hpp"
#include "rootsim/model.hpp"
#include "rootsim/movie_look.hpp"
#include "rootsim/limits.hpp"

namespace rootsim::app {

struct RenderOptions {
  static constexpr double kUnset = kUnsetFlag;  // a number flag not given (limits.hpp)
  std::string runDir;
  // outputs: with none of mp4, pngDir, finalPng, png given, RUN_DIR/movie.mp4 and RUN_DIR/final_top.png;
  // otherwise exactly the ones given
  std::string mp4;        // H.264 movie
  std::string pngDir;     // every frame as PNG
  std::string finalPng;   // the movie's last frame (the same look), as PNG
  // a still (docs/cli.md, "Stills"): one frame of the movie these flags make, to the PNG file `png`;
  // at the snapshot nearest atH (ties to the earlier), or frame number `frame` of the movie
  std::string png;
  double atH = kUnset;    // --at-h [h]
  int frame = 0;          // --frame N (0-based, as frame_<N>.png)
  bool frameGiven = false;
  // time window and speed of the movie: the snapshots with fromH <= t <= toH; hoursPerSecond growth
  // hours per second of movie (unset: one frame per snapshot); see movieFrames (movie.hpp)
  double fromH = kUnset, toH = kUnset, hoursPerSecond = kUnset;
  std::string view = "top";
  std::string size = "auto";  // WxH, or auto: 1280x720 or 720x1280 from the root's shape
  int fps = 30;
  int crf = 18;
  bool whiskers = false;     // thin +-d1 spikes
  bool transparent = false;  // PNG frames without the plate (alpha 0 outside the root)
  bool noOverlays = false;   // no time, scale bar or parameters
  LookOptions look;
  // --trace FILE (with --trace-root, --trace-px-per-mm, --trace-downhill): a traced root drawn over every
  // frame, aligned at the run's seed as `compare` aligns it (docs/experiments.md); trace.trace "" for none
  TraceFlags trace;
  // a plate's run (docs/plate.md): --root NAME (drawn last: the followed root), --plate-view (the sown
  // area, or with --whole-plate the whole plate), --scan PX (a scanner's picture at PX px/mm)
  std::string root;
  bool plateView = false;
  bool wholePlate = false;   // --whole-plate: --plate-view frames the whole plate, not the sown area
  double scanPxPerMm = kUnset;
  bool force = false;        // replace outputs rootsim wrote earlier (never a user's file)
  std::string shaderDir;     // development: load tube/plane shaders from here instead of the built-in copies
  bool quiet = false;
};

// `rootsim render RUN_DIR`: RUN_DIR/trajectory.csv -> MP4 (default RUN_DIR/movie.mp4), optional PNG
// frames, and RUN_DIR/final_top.png (the movie's last frame); or a still (png). Bad flags, a missing run directory or
// a malformed trajectory throw SceneError (exit 2); render or encoder failures RenderError (exit 1).
int renderRunCommand(const RenderOptions& o);

// `rootsim run --movie`: after the run, RUN_DIR/movie.mp4 (top view, size auto, 30 fps, crf 18, with
// the look's camera, colours and plots) and RUN_DIR/final_top.png from RUN_DIR/trajectory.csv; model is
// the run's (the scene `run` parsed: scene.toml is not read again)
// With MovieLook::defaultCamera (no --camera and no --inset given) the movie is the inset look: the fit
// view with a follow window (--field-mm, 2 mm) in a corner, so the whole root and its stripes both read;
// a plate narrower than the window keeps the plain fit view. final_top.png is the movie's last frame.
void renderRunMovie(const std::filesystem::path& runDir, const Model& model, bool quiet, const MovieLook& look);

}  // namespace rootsim::app
