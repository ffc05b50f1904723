#include "rootsim/sweep.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <thread>

#include <unistd.h>

#include <toml++/toml.h>

#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/results.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/write_rule.hpp"
#include "rootsim/scene.hpp"
#include "toml_guard.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
std::string where(const std::string& path, const toml::source_region& r) {
  return path + ":" + std::to_string(r.begin.line);
}
// TOML text of a scalar value, as --set takes it
std::string valueText(const toml::node& n, const std::string& loc) {
  if (n.is_string()) return *n.value<std::string>();
  if (n.is_integer()) return std::to_string(*n.value<int64_t>());
  if (n.is_boolean()) return *n.value<bool>() ? "true" : "false";
  // the shortest text that reads back as the same double (0.3, not 0.29999999999999999)
  if (n.is_floating_point()) return shortestNumber(*n.value<double>());
  if (n.is_array()) {
    std::string s = "[";
    const auto& a = *n.as_array();
    for (size_t i = 0; i < a.size(); ++i) s += (i ? "," : "") + valueText(*a.get(i), loc);
    return s + "]";
  }
  throw SceneError(loc + ": expected a number, string, boolean or array");
}
// a run-directory name short enough for every file system (255 bytes per name, with room for the
// ".incomplete" / ".partial" / ".replaced" siblings): a longer one keeps its first bytes and gets a hash
// of the whole name (FNV-1a, the same on every machine, so shards and reruns agree)
std::string shortName(const std::string& name) {
  constexpr size_t kMax = 200;
  if (name.size() <= kMax) return name;
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : name) h = (h ^ c) * 1099511628211ull;
  char tail[24];
  std::snprintf(tail, sizeof tail, "_h%016llx", static_cast<unsigned long long>(h));
  return name.substr(0, kMax - std::strlen(tail)) + tail;
}
}  // namespace

std::string runNameSlug(const std::string& key, const std::string& val) {
  std::string k = key.substr(key.find('.') + 1), s;
  for (char c : k + "=" + val) s += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '=') ? c : '_';
  return s;
}

std::pair<int, int> parseShard(const std::string& text) {
  int k = 0, n = 0;
  char slash = 0;
  std::istringstream is(text);
  if (!(is >> k >> slash >> n) || slash != '/' || !is.eof() || n < 1 || k < 1 || k > n)
    throw SceneError("--shard " + text + ": expected K/N with 1 <= K <= N (e.g. 2/8)");
  return {k, n};
}

SweepPlan loadSweep(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw SceneError(path + ": no such sweep file");
  std::string text;
  {
    // a sweep file is a few lines of TOML: like a scene, a regular file of at most 1 MiB
    text = readSceneFile(path, "sweep file");
    if (const std::string bad = detail::screenToml(text); !bad.empty())
      throw SceneError(printable(path) + ":" + bad);
  }
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw SceneError(path + ":" + std::to_string(e.source().begin.line) + ": TOML syntax error: " +
                     printable(std::string(e.description())));
  }
  for (auto&& [k, node] : root) {
    const std::string key(k.str());
    if (key != "sweep" && key != "grid" && key != "set")
      throw SceneError(where(path, k.source()) + ": unknown section [" + printable(key) +
                       "] (expected [sweep], [grid], [set])");
    if (!node.is_table())
      throw SceneError(where(path, k.source()) + ": " + key + " must be a table ([" + key + "])");
  }
  SweepPlan plan;
  const toml::table* sw = root["sweep"].as_table();
  if (!sw || !sw->get("scene") || !sw->get("scene")->is_string())
    throw SceneError(path + ": [sweep] needs scene = \"base scene file\"");
  for (auto&& [k, node] : *sw)
    if (k.str() != "scene")
      throw SceneError(where(path, k.source()) + ": unknown key sweep." + printable(std::string(k.str())));
  const fs::path base = fs::path(path).parent_path() / *sw->get("scene")->value<std::string>();
  plan.scenePath = base.string();
  std::vector<std::string> fixed;
  // the line of each [set] and [grid] key, for a point's error: the key it names (its --set origin
  // first), else the first key it mentions
  std::vector<std::pair<std::string, std::uint32_t>> keyLines;
  auto lineOf = [&](const std::string& why) -> std::string {
    for (const char* prefix : {"--set ", ""})
      for (const auto& [key, line] : keyLines)
        if (why.find(prefix + key + (*prefix ? "=" : "")) != std::string::npos ||
            (*prefix && why.find(prefix + key + ":") != std::string::npos))
          return ":" + std::to_string(line);
    return "";
  };
  const toml::table* st = root["set"].as_table();
  const toml::table* gt = root["grid"].as_table();
  if (st)
    for (auto&& [k, node] : *st) {
      // a key in both tables would silently make every point the same (the fixed value wins)
      if (gt && gt->contains(k.str()))
        throw SceneError(where(path, k.source()) + ": set." + printable(std::string(k.str())) +
                         " is also a grid key; give it in [grid] or in [set], not both");
      fixed.push_back(std::string(k.str()) + "=" + valueText(node, where(path, k.source())));
      keyLines.emplace_back(std::string(k.str()), k.source().begin.line);
    }
  std::vector<std::vector<std::string>> values;
  // every combination, first key slowest: counted before anything is expanded (a grid of 40^4 points
  // once took GBs before failing)
  std::uint64_t total = 1;
  if (gt)
    for (auto&& [k, node] : *gt) {
      const std::string loc = where(path, k.source());
      const toml::array* a = node.as_array();
      if (!a || a->empty())
        throw SceneError(loc + ": grid." + printable(std::string(k.str())) + " must be a non-empty array");
      total *= a->size();
      if (total > kMaxSweepPoints)
        throw SceneError(loc + ": the grid has more than " + std::to_string(kMaxSweepPoints) +
                         " points (the product of the grid arrays' lengths, up to grid." +
                         printable(std::string(k.str())) + "); split the sweep into several files");
    }
  if (gt)
    for (auto&& [k, node] : *gt) {
      const std::string loc = where(path, k.source());
      plan.gridKeys.emplace_back(k.str());
      keyLines.emplace_back(std::string(k.str()), k.source().begin.line);
      values.emplace_back();
      for (const auto& v : *node.as_array()) values.back().push_back(valueText(v, loc));
    }
  // the base scene is read once; each point is validated with its overrides
  std::string baseText;
  try {
    baseText = readSceneFile(plan.scenePath);
  } catch (const SceneError& e) {
    throw SceneError(where(path, sw->get("scene")->source()) + ": sweep.scene: " + e.what());
  }
  plan.points.reserve(static_cast<size_t>(total));
  for (size_t i = 0; i < total; ++i) {
    SweepPoint p;
    p.index = static_cast<int>(i);
    size_t rem = i;
    std::vector<size_t> idx(values.size());
    for (size_t d = values.size(); d-- > 0;) {
      idx[d] = rem % values[d].size();
      rem /= values[d].size();
    }
    char num[32];
    std::snprintf(num, sizeof num, "%04zu", i);
    p.dirName = std::string("run_") + num;
    for (size_t d = 0; d < values.size(); ++d) {
      p.grid.emplace_back(plan.gridKeys[d], values[d][idx[d]]);
      p.overrides.push_back(plan.gridKeys[d] + "=" + values[d][idx[d]]);
      p.dirName += "_" + runNameSlug(plan.gridKeys[d], values[d][idx[d]]);
    }
    p.dirName = shortName(p.dirName);
    p.overrides.insert(p.overrides.end(), fixed.begin(), fixed.end());
    // validate now: a typo in the grid fails before any run starts
    try {
      const Scene point = parseScene(baseText, plan.scenePath, p.overrides);
      p.plate = point.isPlate();  // each point a plate (docs/plate.md): a plate run directory
      p.grows = point.model.growth.enabled;
      p.resolvedToml = point.resolvedToml;
    } catch (const SceneError& e) {
      throw SceneError(path + lineOf(e.what()) + ": point " + std::to_string(i) + ": " + e.what());
    }
    plan.points.push_back(std::move(p));
  }
  return plan;
}

void writeSweepTable(const SweepPlan& plan, const std::string& out) {
  std::string header, body;
  for (const auto& p : plan.points) {
    // a root's result.csv; a plate's plate.csv: one row per root (its seedling, then its result)
    std::ifstream in(fs::path(out) / p.dirName / (p.plate ? "plate.csv" : "result.csv"));
    std::string h, r;
    if (!in || !std::getline(in, h) || !std::getline(in, r)) continue;
    std::string prefix = std::to_string(p.index) + "," + p.dirName;
    for (const auto& [k, v] : p.grid) prefix += "," + csvQuoted(v);
    if (header.empty()) {
      header = "index,run";
      for (const auto& k : plan.gridKeys) header += ",grid:" + k;
      header += "," + h;
    }
    do
      body += prefix + "," + r + "\n";
    while (p.plate && std::getline(in, r) && !r.empty());
  }
  if (header.empty()) return;
  // shards of a job array finish at the same time and each writes the table: every process through a
  // working name of its own, in rootsim's temporary form (table.csv.tmp<pid>-<host's number>: shards may
  // share a network file system, so the pid alone is not the process's), then renamed into place
  char host[256] = "host";
  ::gethostname(host, sizeof host - 1);
  const fs::path mine = fs::path(out) / ("table.csv.tmp" + std::to_string(::getpid()) + "-" +
                                         std::to_string(std::hash<std::string>{}(host) % 1000000000u));
  writeFileAtomic(mine, header + "\n" + body);
  // renamed and recorded under the folder's record lock: the marker holds the table that is there
  recordFiles(fs::path(out), sweepFolder(), {"table.csv"}, [&] {
    std::error_code ec;
    fs::rename(mine, fs::path(out) / "table.csv", ec);
    if (ec) {
      fs::remove(mine, ec);
      throw RunError("cannot write " + (fs::path(out) / "table.csv").string() + ": " + ec.message());
    }
  });
}

namespace {
// what a sweep finds at a point before it starts
enum class PointState { Fresh, Complete, Stale, FailedBefore };

// a point is complete only if its run directory is whole (every file its marker lists, at the size its
// run wrote), holds the current result columns, and was run with the point's current scene; an
// interrupted attempt (DIR.partial) of the same scene is continued, one of another scene is stale
PointState stateOf(const SweepPoint& p, const fs::path& dir, std::string& why) {
  std::error_code ec;
  const std::string& want = p.scene ? p.scene->resolvedToml : p.resolvedToml;
  auto sceneOf = [](const fs::path& d) {
    std::ifstream in(d / "scene.toml", std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  if (fs::exists(fs::symlink_status(dir, ec))) {
    if (std::string bad = whyNotOurs(dir, runFolder()); !bad.empty()) throw SceneError(bad);
    // a plate's plate.csv: the seedling's columns, then those of result.csv
    std::ifstream prev(dir / (p.plate ? "plate.csv" : "result.csv"));
    std::string head;
    const std::string cols = resultHeader(p.grows);
    if (!prev || !std::getline(prev, head) ||
        (p.plate ? !(head.size() > cols.size() && head.compare(head.size() - cols.size(), cols.size(), cols) == 0 &&
                     head[head.size() - cols.size() - 1] == ',')
                 : head != cols)) {
      why = "its result.csv has other columns (written by another rootsim version)";
      return PointState::Stale;
    }
    if (sceneOf(dir) != want) {
      why = "its scene.toml differs from the point's scene now (the base scene or [set] changed)";
      return PointState::Stale;
    }
    if (why = whyNotWhole(dir); !why.empty()) return PointState::Stale;
    return PointState::Complete;
  }
  fs::path part = dir, inc = dir;
  part += ".partial";
  inc += ".incomplete";
  if (fs::exists(fs::symlink_status(inc, ec))) {
    why = "it failed before (see " + (inc / "ERROR.txt").string() + ")";
    return PointState::FailedBefore;
  }
  if (fs::exists(fs::symlink_status(part, ec)) && fs::exists(part / "scene.toml", ec) && sceneOf(part) != want) {
    why = "its interrupted run " + part.string() + " holds another scene";
    return PointState::Stale;
  }
  return PointState::Fresh;
}
}  // namespace

SweepResult runSweep(const SweepPlan& plan, const SweepOptions& opt,
                     const std::function<void(const std::string&)>& log) {
  // the write rule: a new folder, or a sweep folder of rootsim's holding nothing foreign; never the
  // working folder, the sweep file's or the base scene's folder, nor inside them
  WriteRule rule;
  rule.force = opt.force;
  rule.inputs.push_back(workingFolder());
  for (const fs::path& in : opt.inputs) rule.inputs.push_back(WriteInput{in, {}, false});
  const fs::path out = checkOutputName(opt.out, "--out");
  // the shards of a job array share the folder (a shared lock: a run, fit or figure writing there is
  // refused, and refuses them); one shard started twice is refused (each point's run directory is
  // locked as well, so overlapping shardings never write one point twice)
  const OutputLock folderLock = lockOutput(out, "--out", LockMode::Shared);
  claimFolder(out, sweepFolder(), rule, "--out", false);
  createOwnFolder(out, sweepFolder());
  const OutputLock shardLock = lockOutput(out / ("shard-" + std::to_string(opt.shard) + "-of-" + std::to_string(opt.shards)),
                                          "--out " + out.string() + " shard");
  std::vector<const SweepPoint*> pending;
  SweepResult res;
  int stale = 0;
  std::string firstStale;
  std::vector<std::pair<const SweepPoint*, std::string>> failedEarlier;
  for (const auto& p : plan.points) {
    if (p.index % opt.shards != opt.shard - 1) continue;
    const fs::path dir = out / p.dirName;
    std::string why;
    const PointState st = stateOf(p, dir, why);
    if (st == PointState::Complete) {
      ++res.skipped;
      if (opt.onPoint) {
        SweepPointDone d;
        d.point = &p;
        d.dir = dir.string();
        d.skipped = true;
        opt.onPoint(d);
      }
      continue;
    }
    if (st == PointState::Stale) {
      if (stale++ == 0) firstStale = p.dirName + ": " + why;
    } else if (st == PointState::FailedBefore && !opt.force) {
      failedEarlier.emplace_back(&p, why);
      continue;
    }
    pending.push_back(&p);
  }
  if (stale > 0 && !opt.force)
    throw SceneError("--out " + out.string() + ": " + std::to_string(stale) + " point(s) hold runs that cannot be kept (not whole, or not the sweep's scene now; first: " +
                     firstStale + "); pass --force to rerun them");
  if (stale > 0 && log) log(std::to_string(stale) + " point(s) rerun: their runs could not be kept (first: " + firstStale + ")");
  for (const auto& [p, why] : failedEarlier) {
    ++res.failed;
    if (log) log(p->dirName + ": FAILED earlier: " + why + "; pass --force to rerun it");
    if (opt.onPoint) {
      SweepPointDone d;
      d.point = p;
      d.dir = (out / p->dirName).string();
      d.error = "failed earlier: " + why;
      opt.onPoint(d);
    }
  }
  std::mutex mu;
  std::atomic<size_t> next{0};
  std::atomic<bool> interrupted{false};
  const auto start = std::chrono::steady_clock::now();
  auto worker = [&]() {
    for (;;) {
      if (opt.cancelled && opt.cancelled()) {
        interrupted = true;
        return;
      }
      const size_t i = next++;
      if (i >= pending.size()) return;
      const SweepPoint& p = *pending[i];
      std::string msg;
      bool ok = true;
      double wall = 0;
      const std::string dir = (out / p.dirName).string();
      std::function<void(const StepRecord&, int)> poll;
      if (opt.cancelled)
        poll = [&](const StepRecord& r, int) {
          if (opt.cancelled()) throw RunInterrupted("sweep cancelled at growth step " + std::to_string(r.step));
        };
      try {
        // a point not complete is continued from its checkpoint when it has one (a killed sweep), else
        // redone: its earlier attempt (a run directory, never user files) is replaced
        RunDirOptions ro;
        ro.force = opt.force;
        ro.resume = true;
        wall = p.scene ? runSceneToDir(*p.scene, dir, ro, poll)
                       : runSceneToDir(loadScene(plan.scenePath, p.overrides), dir, ro, poll);
      } catch (const RunInterrupted&) {
        interrupted = true;
        return;
      } catch (const std::exception& e) {
        ok = false;
        msg = e.what();
      }
      const std::string error = ok ? std::string() : msg;
      std::lock_guard<std::mutex> lock(mu);
      if (ok) {
        ++res.ran;
        char b[64];
        std::snprintf(b, sizeof b, " (%.1f s)", wall);
        msg = p.dirName + ": done" + b;
      } else {
        ++res.failed;
        msg = p.dirName + ": FAILED: " + msg;
      }
      if (log) {
        // progress over the whole sweep: done / to do, elapsed and an estimate of what is left
        const int done = res.ran + res.failed - static_cast<int>(failedEarlier.size());
        const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char eta[96];
        std::snprintf(eta, sizeof eta, " [%3.0f %%, %.0f s elapsed, ~%.0f s left]", 100.0 * done / pending.size(), el,
                      el / done * (static_cast<double>(pending.size()) - done));
        log("[" + std::to_string(done) + "/" + std::to_string(pending.size()) + "] " + msg + eta);
      }
      if (opt.onPoint) {
        SweepPointDone d;
        d.point = &p;
        d.dir = dir;
        d.error = error;
        d.wallS = ok ? wall : 0.0;
        opt.onPoint(d);
      }
    }
  };
  std::vector<std::thread> pool;
  const int jobs = std::max(1, std::min<int>(opt.jobs, static_cast<int>(pending.size())));
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  writeSweepTable(plan, opt.out);
  res.interrupted = interrupted;
  return res;
}

}  // namespace rootsim
