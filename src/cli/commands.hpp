#pragma once
// The subcommands, free of CLI11 (main.cpp parses; these run). Each returns the process exit code or
// throws SceneError (exit 2) / RunError or RelaxError (exit 1).
#include <functional>
#include <string>
#include <vector>

#include "rootsim/analyze_traces.hpp"
#include "rootsim/compare_trace.hpp"
#include "rootsim/fit_trace.hpp"
#include "rootsim/export_run.hpp"
#include "rootsim/montage_runs.hpp"
#include "rootsim/movie_look.hpp"
#include "rootsim/render_run.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"

namespace rootsim::cli {

struct RunOptions {
  std::string scene;
  std::vector<std::string> sets;
  std::string out;        // run directory; default runs/<scene name>
  bool movie = false;
  app::LookOptions look;  // the movie's camera, colours, plots (with movie)
  bool force = false;     // replace an earlier run directory at --out (never a folder rootsim did not write)
  bool resume = false;    // continue DIR.partial from its checkpoint; a complete DIR is left as it is
  bool quiet = false;
};
int runCommand(const RunOptions& o);
// the run command on a scene already loaded (rootsim.run's Scene; o.scene and o.sets are not read):
// checks the movie's flags, runs into o.out (default runs/<scene name>), renders the movie; onStep (may
// be empty) is called after every growth step, as the progress bar is
int runLoaded(const Scene& sc, const RunOptions& o, const std::function<void(const StepRecord&, int)>& onStep);

struct CheckOptions {
  std::string scene;
  std::vector<std::string> sets;
};
int checkCommand(const CheckOptions& o);

// render and montage: the app library's commands (rootsim_app); SceneError when the renderer is not built
int renderCommand(const app::RenderOptions& o);
int montageCommand(const app::MontageOptions& o);
// export: the app library's command (rootsim_app); SceneError when it is not built
int exportCommand(const app::ExportOptions& o);
// analyze: the app library's command (rootsim_app); SceneError when it is not built
int analyzeCommand(const app::AnalyzeOptions& o);
// compare and fit: the app library's commands (docs/experiments.md); SceneError when it is not built
int compareCommand(const app::CompareOptions& o);
int fitCommand(const app::FitOptions& o);

struct ModesOptions {
  std::string runDir;
  std::string root;       // a plate's run: the root NAME (its folder roots/NAME receives the files)
  int count = 6;          // modes to write
  bool force = false;     // replace modes.csv / modes.vtp written earlier
  bool quiet = false;
};
int modesCommand(const ModesOptions& o);

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
  double dpi = 300;       // PNG resolution (stored in the PNG)
  double widthMm = 0;     // physical panel width [mm] (85, 180: a journal column); 0: 96 layout units per inch
  bool noTitle = false;   // panels without their figure title
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
