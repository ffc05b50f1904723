// `rootsim montage RUN_DIR...`: validate the flags and the run directories (SceneError, exit 2), then
// hand the runs to the renderer library (RenderError, exit 1)
#include "rootsim/montage_runs.hpp"

#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "flags.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/montage.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/trajectory.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/write_rule.hpp"
#include "run_files.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

// a label per run: the resolved scene keys whose values differ between the runs (not the output
// section), "key = value" in the order of the keys' names, obstacles first; a run without the key
// shows "-"; the run directory's name when nothing differs
std::vector<std::string> differingLabels(const std::vector<Model>& models, const std::vector<fs::path>& dirs) {
  std::vector<std::map<std::string, std::string>> keys;
  std::set<std::string> all;
  for (const Model& m : models) {
    keys.emplace_back();
    for (const SceneValue& v : sceneValues(m)) {
      keys.back()[v.key] = v.text;
      all.insert(v.key);
    }
  }
  std::vector<std::string> differ, obstacles;
  for (const std::string& k : all) {
    if (k.rfind("output.", 0) == 0) continue;
    std::set<std::string> values;
    for (const auto& m : keys) values.insert(m.count(k) ? m.at(k) : "-");
    if (values.size() > 1) (k.rfind("obstacle[", 0) == 0 ? obstacles : differ).push_back(k);
  }
  differ.insert(differ.begin(), obstacles.begin(), obstacles.end());
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    std::string l;
    for (const std::string& k : differ) {
      const std::string shortKey = k.substr(k.find('.') + 1);
      l += (l.empty() ? "" : "  ") + shortKey + " = " + (keys[i].count(k) ? keys[i].at(k) : "-");
    }
    labels.push_back(l.empty() ? fs::absolute(dirs[i]).lexically_normal().filename().string() : l);
  }
  return labels;
}

}  // namespace

int montageRunsCommand(const MontageOptions& o) {
  // every check first: exit 2 before anything is written
  if (o.runDirs.empty()) throw SceneError("montage: no run directories given (rootsim montage RUN_DIR... --mp4 FILE)");
  std::vector<fs::path> dirs;
  for (const std::string& d : o.runDirs) {
    if (!fs::is_directory(d)) throw SceneError("montage: run directory " + d + " not found");
    if (!fs::is_regular_file(fs::path(d) / "scene.toml"))
      throw SceneError("montage: " + d + "/scene.toml not found (not a run directory?)");
    dirs.emplace_back(d);
  }
  if (o.mp4.empty() && o.pngDir.empty()) throw SceneError("montage: nothing to write; give --mp4 FILE and/or --png-dir DIR");
  MontageJob job;
  std::tie(job.view.width, job.view.height) = parseSize(o.size);
  job.view.kind = parseViewKind(o.view);
  job.video = parseVideo(o.fps, o.crf);
  job.view.colourBy = parseColourBy(o.colorBy);
  job.view.shadows = o.shadows;
  job.mp4 = o.mp4;
  std::vector<std::string> labels;
  if (!o.labels.empty()) {
    labels = splitCommas(o.labels);
    if (labels.size() != dirs.size())
      throw SceneError("--labels " + o.labels + ": " + std::to_string(labels.size()) + " labels for " +
                       std::to_string(dirs.size()) + " runs");
  }
  std::vector<MontageRun> runs;
  std::vector<Model> models;
  for (const fs::path& d : dirs) {
    MontageRun r;
    models.push_back(loadScene((d / "scene.toml").string()).model);
    r.info = sceneInfoOf(models.back());
    if (job.view.shadows && !r.info.plate)
      throw SceneError("--shadows: " + (d / "scene.toml").string() + " has no plate to cast them on (plane.enabled = false)");
    r.snaps = loadSnapshots(d);
    if (job.view.colourBy == ColourField::Kappa0 && r.snaps.back().kappa0.size() == 0)
      throw SceneError("--color-by kappa0: " + trajectoryPath(d).string() + " has no kappa0_per_mm column");
    if (job.view.colourBy == ColourField::Contact && r.snaps.back().plateForce.size() == 0)
      throw SceneError("--color-by contact: " + trajectoryPath(d).string() + " has no plate_force_n column");
    runs.push_back(std::move(r));
  }
  if (labels.empty()) labels = differingLabels(models, dirs);
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i].label = labels[i];
  // the write rule, once the flags and the runs are known good: the run directories are read, never written
  WriteRule rule;
  rule.force = o.force;
  for (const fs::path& d : dirs) rule.inputs.push_back(WriteInput{d, {}});
  const Outputs outs = claimOutputs(o.mp4, fs::path(), o.pngDir, rule);
  std::optional<StagedFolder> frames;
  if (!o.pngDir.empty()) {
    frames.emplace(o.pngDir, framesFolder(), rule, "--png-dir");
    job.pngDir = frames->work().string();
  }
  renderMontage(runs, job, progressLines(o.quiet, "montage"));
  if (frames) frames->commit();
  if (!o.quiet) {
    if (!job.mp4.empty()) std::fprintf(stderr, "wrote %s\n", job.mp4.c_str());
    if (frames) std::fprintf(stderr, "wrote frames to %s\n", frames->final().c_str());
  }
  return 0;
}

}  // namespace rootsim::app
