#pragma once
// The subcommands, free of CLI11 (main.cpp parses; these run). Each returns the process exit code or
// throws SceneError (exit 2) / RunError or RelaxError (exit 1).
#include <string>
#include <vector>

namespace rootsim::cli {

// how a movie looks (render, run --movie, montage): camera, colour, plots, shadows
struct LookOptions {
  std::string camera = "fit";  // fit | follow
  double fieldMm = 2.0;        // follow window width [mm]
  bool fieldGiven = false;     // --field-mm was on the command line
  bool inset = false;          // fit view with a follow window in its corner
  std::string colorBy = "none";  // none | curvature | twist | kappa0 | stretch | contact
  std::string plot;            // comma-separated subset of theta_tip,Eb,Et,Wr,Tw
  bool shadows = false;        // the root's shadow on the plate
};

struct RunOptions {
  std::string scene;
  std::vector<std::string> sets;
  std::string out;        // run directory; default runs/<scene name>
  bool movie = false;
  LookOptions look;       // the movie's camera, colours, plots (with movie)
  bool force = false;     // replace an earlier run directory at --out (never a folder rootsim did not write)
  bool resume = false;    // continue DIR.partial from its checkpoint; a complete DIR is left as it is
  bool quiet = false;
};
int runCommand(const RunOptions& o);

struct CheckOptions {
  std::string scene;
  std::vector<std::string> sets;
};
int checkCommand(const CheckOptions& o);

struct RenderOptions {
  std::string runDir;
  // outputs: with none of mp4, pngDir, finalPng given, RUN_DIR/movie.mp4 and RUN_DIR/final_top.png;
  // otherwise exactly the ones given
  std::string mp4;        // H.264 movie
  std::string pngDir;     // every frame as PNG
  std::string finalPng;   // the last snapshot, top view
  std::string view = "top";
  std::string size = "auto";  // WxH, or auto: 1280x720 or 720x1280 from the root's shape
  int fps = 30;
  int crf = 18;
  bool whiskers = false;     // thin +-d1 spikes
  bool transparent = false;  // PNG frames without the plate (alpha 0 outside the root)
  bool noOverlays = false;   // no time, scale bar or parameters
  LookOptions look;
  bool force = false;        // replace outputs rootsim wrote earlier (never a user's file)
  std::string shaderDir;     // development: load tube/plane shaders from here instead of the built-in copies
  bool quiet = false;
};
int renderCommand(const RenderOptions& o);

struct ModesOptions {
  std::string runDir;
  int count = 6;          // modes to write
  bool force = false;     // replace modes.csv / modes.vtp written earlier
  bool quiet = false;
};
int modesCommand(const ModesOptions& o);

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
int montageCommand(const MontageOptions& o);

struct SweepCliOptions {
  std::string sweep;
  int jobs = 1;
  std::string shard;      // "K/N"
  std::string out;        // default runs/<sweep name>
  bool force = false;     // rerun points written with another scene, or that failed before
  bool quiet = false;
};
int sweepCommand(const SweepCliOptions& o);

struct FigureCliOptions {
  std::string name;
  bool quick = false;
  std::string out = "figures";
  int jobs = 2;
  bool force = false;     // replace panels rootsim wrote earlier in --out
  bool quiet = false;
};
int figureCommand(const FigureCliOptions& o);

// progress on stderr: a redrawn bar on a terminal, one line per percent otherwise
class Progress {
 public:
  Progress(int total, bool quiet, std::string what);
  void update(int done, const std::string& detail);
  void finish(const std::string& detail);

 private:
  int total_;
  bool quiet_, tty_;
  int lastPercent_ = -1;
  std::string what_;
  double start_;
};

}  // namespace rootsim::cli
