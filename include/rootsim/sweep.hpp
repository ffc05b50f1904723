#pragma once
// Parameter sweeps (docs/cli.md, `rootsim sweep`): a base scene, a grid of overrides, one run directory per
// grid point, resumable (completed runs are skipped), shardable (--shard K/N runs every N-th point),
// and a table of results (table.csv) built from every completed run.
//
// Sweep file:
//   [sweep]
//   scene = "fig2a_alpha40.toml"      # base scene, relative to the sweep file
//   [grid]                             # every combination of these (row-major, first key slowest)
//   "plane.alpha_deg" = [0, 20, 40]
//   "tropism.beta" = [0.1, 0.2]
//   [set]                              # fixed overrides for every point
//   "growth.steps" = 600
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rootsim/run_scene.hpp"

namespace rootsim {

// most points a sweep file may have (the product of its grid arrays' lengths); counted before the grid
// is expanded
inline constexpr std::uint64_t kMaxSweepPoints = 10000;

struct SweepPoint {
  int index = 0;
  std::vector<std::string> overrides;          // "section.key=value", grid then fixed
  std::vector<std::pair<std::string, std::string>> grid;  // grid key, value text
  std::string dirName;                          // run directory name inside the sweep folder (<= 200
                                                // bytes: long names end in a hash of the full name)
  bool grows = true;                            // growth run (else mechanics only: another result header)
  bool plate = false;                           // a plate's scene: its run has plate.csv, a row per root
  std::string resolvedToml;                     // the point's resolved scene (what its scene.toml must hold)
  std::optional<Scene> scene;                   // a typed scene (sceneOf a model: the figure cases), run
                                                // instead of the plan's base scene and overrides
};

struct SweepPlan {
  std::string scenePath;                        // base scene ("" when every point has its scene)
  std::vector<std::string> gridKeys;
  std::vector<SweepPoint> points;
};

// parses and validates the sweep file (each point's scene is validated too); throws SceneError
SweepPlan loadSweep(const std::string& path);

// one point of a running sweep, reported as it finishes (SweepOptions::onPoint)
struct SweepPointDone {
  const SweepPoint* point = nullptr;
  std::string dir;            // its run directory (complete unless error is set)
  std::string error;          // "" or what failed it (the directory is then DIR.incomplete)
  bool skipped = false;       // complete before this sweep started (resumed): not run again
  double wallS = 0;           // wall time of the run [s] (0 when skipped or failed)
};

struct SweepOptions {
  int jobs = 1;                 // worker threads
  int shard = 1, shards = 1;    // run points with index % shards == shard - 1
  std::string out;              // sweep folder
  bool quiet = false;
  // rerun points whose run directory holds another scene (the base scene or [set] changed), is not
  // whole, or failed before; without it such points stop the sweep before it starts (stale) or stay
  // failed (failed before)
  bool force = false;
  std::vector<std::filesystem::path> inputs;  // files the sweep reads (never inside --out)
  // called for every point of this shard as it finishes (from its worker thread, one call at a time),
  // and first for each point found complete (skipped); the Python package yields results through it
  std::function<void(const SweepPointDone&)> onPoint;
  // polled before each point starts and after every growth step: true stops the sweep (running points
  // stop between growth steps and stay DIR.partial, no other point starts); the table of the points that
  // completed is still written, and the result says interrupted
  std::function<bool()> cancelled;
};

struct SweepResult {
  int ran = 0, skipped = 0, failed = 0;
  bool interrupted = false;  // stopped by SweepOptions::cancelled
};

// runs the plan; progress and failures are reported through log (one line each); writes table.csv
SweepResult runSweep(const SweepPlan& plan, const SweepOptions& opt,
                     const std::function<void(const std::string&)>& log);

// a file-name-safe "key=value" for a run directory's name: the key without its section, characters other
// than letters, digits, '.', '-' and '=' as '_' (sweep points; fit's evaluations)
std::string runNameSlug(const std::string& key, const std::string& val);

// "K/N" -> (K, N); throws SceneError
std::pair<int, int> parseShard(const std::string& text);

// rebuilds table.csv of a sweep folder from the summary.json of every completed run
void writeSweepTable(const SweepPlan& plan, const std::string& out);

}  // namespace rootsim
