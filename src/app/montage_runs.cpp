// `rootsim montage RUN_DIR...`: validate the flags and the run directories (SceneError, exit 2), then
// hand the runs to the renderer library (RenderError, exit 1)
#include "rootsim/montage_runs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "flags.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/image.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/montage.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/trajectory.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/write_rule.hpp"
#include "run_files.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

namespace {

// scene keys as the paper writes them: symbol, unit (appended to the number), and whether a value all
// runs share goes into the caption line
struct KeySymbol {
  const char* key;
  const char* symbol;
  const char* unit;
  bool caption;
};
constexpr KeySymbol kSymbols[] = {
    {"plane.alpha_deg", "\xCE\xB1", "\xC2\xB0", true},
    {"tropism.beta", "\xCE\xB2", "", true},
    {"tropism.gamma", "\xCE\xB3", "", true},
    {"tropism.twist_r_tau", "R\xCF\x84", "", true},
    {"growth.growth_zone_mm", "L_gz", " mm", true},
    {"growth.rate_per_h", "rate", " /h", false},
    {"root.radius_mm", "R", " mm", false},
    {"root.initial_length_mm", "L\xE2\x82\x80", " mm", false},
    {"root.youngs_modulus_mpa", "E", " MPa", false},
    {"tropism.circumnutation_gain", "\xCE\xBB_cn", "", false},
    {"tropism.circumnutation_period_h", "T_cn", " h", false},
    {"friction.mu_static", "\xCE\xBC_s", "", false},
    {"friction.mu_kinetic", "\xCE\xBC_k", "", false},
};

const KeySymbol* symbolOf(const std::string& key) {
  for (const KeySymbol& k : kSymbols)
    if (key == k.key) return &k;
  return nullptr;
}

// a TOML number as a short decimal ("40.0" -> "40", "0.10" -> "0.1"); anything else unchanged
std::string shortNumber(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) return text;
  return significantText(v, 4);
}

// "value unit" of key (symbol table), or the TOML text
std::string valueText(const std::string& key, const std::string& text) {
  const KeySymbol* k = symbolOf(key);
  return k ? shortNumber(text) + k->unit : text;
}
// "α", or the key without its section ("growth.steps" -> "steps")
std::string nameOf(const std::string& key) {
  const KeySymbol* k = symbolOf(key);
  return k ? k->symbol : key.substr(key.find('.') + 1);
}

// the table's keys first (in its order), then obstacles, then the rest by name
int rank(const std::string& key) {
  for (std::size_t i = 0; i < std::size(kSymbols); ++i)
    if (key == kSymbols[i].key) return static_cast<int>(i);
  return key.rfind("obstacle[", 0) == 0 ? 1000 : 2000;
}

}  // namespace

MontageLabels montageLabels(const std::vector<Model>& models, const std::vector<std::string>& dirNames) {
  std::vector<std::map<std::string, std::string>> keys;
  std::set<std::string> all;
  for (const Model& m : models) {
    keys.emplace_back();
    for (const SceneValue& v : sceneValues(m, OutputParams{})) {  // output.* keys are not labels (below)
      keys.back()[v.key] = v.text;
      all.insert(v.key);
    }
  }
  std::vector<std::string> differ, shared;
  for (const std::string& k : all) {
    if (k.rfind("output.", 0) == 0) continue;
    std::set<std::string> values;
    for (const auto& m : keys) values.insert(m.count(k) ? m.at(k) : "-");
    if (values.size() > 1)
      differ.push_back(k);
    else if (const KeySymbol* s = symbolOf(k); s && s->caption)
      shared.push_back(k);
  }
  auto byRank = [](const std::string& a, const std::string& b) {
    return std::make_pair(rank(a), a) < std::make_pair(rank(b), b);
  };
  std::sort(differ.begin(), differ.end(), byRank);
  std::sort(shared.begin(), shared.end(), byRank);
  MontageLabels out;
  for (std::size_t i = 0; i < models.size(); ++i) {
    std::string l;
    for (const std::string& k : differ)
      l += (l.empty() ? "" : ", ") + nameOf(k) + " = " + (keys[i].count(k) ? valueText(k, keys[i].at(k)) : "-");
    out.labels.push_back(l.empty() && i < dirNames.size() ? dirNames[i] : l);
  }
  // the shared values once: keys with the same value and unit grouped, "β = γ = 0.1"
  std::vector<std::pair<std::string, std::string>> groups;  // (names joined, value)
  for (const std::string& k : shared) {
    const std::string v = valueText(k, keys.front().at(k));
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.second == v; });
    if (it == groups.end())
      groups.emplace_back(nameOf(k), v);
    else
      it->first += " = " + nameOf(k);
  }
  for (const auto& [names, v] : groups) out.caption += (out.caption.empty() ? "" : ", ") + names + " = " + v;
  return out;
}

int montageRunsCommand(const MontageOptions& o) {
  // every check first: exit 2 before anything is written
  if (o.runDirs.empty()) throw SceneError("montage: no run directories given (rootsim montage RUN_DIR... --mp4 FILE)");
  std::vector<fs::path> dirs;
  for (const std::string& d : o.runDirs) {
    if (const std::string why = whyUnfinished(d); !why.empty()) throw SceneError("montage: " + d + ": " + why);
    if (!fs::is_directory(d)) throw SceneError("montage: run directory " + d + " not found");
    if (!fs::is_regular_file(fs::path(d) / "scene.toml"))
      throw SceneError("montage: " + d + "/scene.toml not found (not a run directory?)");
    dirs.emplace_back(d);
  }
  if (o.mp4.empty() && o.pngDir.empty()) throw SceneError("montage: nothing to write; give --mp4 FILE and/or --png-dir DIR");
  // the runs are counted before their snapshots are read (every run's are held at once)
  checkCount("montage of " + std::to_string(dirs.size()) + " run directories", static_cast<double>(dirs.size()),
             caps::kMontageRuns, "tiles", "caps::kMontageRuns: every run's snapshots are held at once, ~22 MB a run; montage fewer runs");
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
  std::vector<std::string> names;
  for (const fs::path& d : dirs) names.push_back(fs::absolute(d).lexically_normal().filename().string());
  const MontageLabels automatic = montageLabels(models, names);
  if (labels.empty()) labels = automatic.labels;
  job.caption = automatic.caption;
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i].label = labels[i];
  // the tiles must fit the frame: a usage error, found before anything is written
  try {
    (void)montageLayout(runs, job.view);
  } catch (const RenderError& e) {
    throw SceneError("--size " + o.size + ": " + e.what() + " (a tile needs at least 16x16 px; give a larger --size or fewer runs)");
  }
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
