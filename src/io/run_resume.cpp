// What a resumed run checks and cleans before it continues an interrupted run directory (run_resume.hpp)
#include "run_resume.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include <toml++/toml.h>

#include "rootsim/errors.hpp"
#include "rootsim/write_rule.hpp"

namespace fs = std::filesystem;

namespace rootsim::detail {

// what to do with an interrupted run DIR.partial when resuming: continue it from its checkpoint (load
// read it), discard it (killed before its first checkpoint: nothing to lose), or refuse (another scene,
// a corrupt checkpoint; with force those are discarded too)
PartialRun resumePlan(const Scene& sc, const std::string& outDir, bool force,
                      const std::function<void(const fs::path&)>& load) {
  fs::path work = normaliseOutDir(outDir);
  work += ".partial";
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(work, ec))) return PartialRun::Refuse;  // nothing to resume: a new run
  if (std::string why = whyNotOurs(work, runFolder()); !why.empty()) throw SceneError("--out " + outDir + ": " + why);
  // the first file a run writes is its resolved scene
  std::ifstream in(work / "scene.toml", std::ios::binary);
  if (!in) return PartialRun::Discard;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text != sc.resolvedToml) {
    if (force) return PartialRun::Discard;
    throw SceneError("--resume: " + work.string() + " was written by another scene (" +
                     sceneDifference((work / "scene.toml").string(), text, sc.resolvedToml, sc.path) +
                     "); pass the same scene and --set values, or --force to discard it and start again");
  }
  if (!fs::exists(work / kCheckpointFile, ec)) {
    // killed before its first checkpoint: nothing to lose. But a run that finished there (its
    // summary.json written: renamed by hand, or a commit that failed) is never discarded without --force
    if (!force && fs::exists(work / "summary.json", ec))
      throw SceneError("--resume: " + work.string() + " holds a finished run without a checkpoint (it has summary.json); "
                       "move it away, or pass --force to discard it and start again");
    return PartialRun::Discard;
  }
  try {
    load(work / kCheckpointFile);
  } catch (const SceneError&) {
    if (force) return PartialRun::Discard;
    throw;
  }
  return PartialRun::Continue;
}

void noteResume(const RunDirOptions& o, const RunDir& rd, PartialRun partial, int step, int steps) {
  if (!o.note) return;
  if (partial == PartialRun::Continue)
    o.note("resuming " + rd.final().string() + " from the checkpoint of growth step " + std::to_string(step) + " of " +
           std::to_string(steps));
  else if (partial == PartialRun::Discard)
    o.note("no usable checkpoint in " + rd.work().string() + ": starting " + rd.final().string() + " again");
}

void checkStreamLengths(const fs::path& dir, const OutputParams& o, const WriterPositions& w) {
  const bool traj = o.trajectory;
  const std::pair<const char*, std::uint64_t> streams[] = {
      {"timeseries.csv", w.timeseriesBytes},
      {"trajectory.csv", traj && o.trajectoryFormat != TrajectoryFormat::Binary ? w.trajectoryBytes : 0},
      {"trajectory.bin", traj && o.trajectoryFormat != TrajectoryFormat::Csv ? w.trajectoryBinaryBytes : 0}};
  for (const auto& [name, bytes] : streams) checkStreamLength(dir / name, bytes);
}

void checkStreamLength(const fs::path& file, std::uint64_t bytes) {
  if (bytes == 0) return;
  std::error_code ec;
  fs::path f = file;
  f += ".tmp";
  if (!fs::is_regular_file(f, ec)) f = file;  // killed after it was closed
  const std::uintmax_t have = fs::is_regular_file(f, ec) ? fs::file_size(f, ec) : 0;
  if (have < bytes)
    throw SceneError(f.string() + ": missing or shorter (" + std::to_string(have) + " bytes) than its checkpoint says (" +
                     std::to_string(bytes) + " bytes); pass --force to discard the interrupted run and start again");
}

void checkSceneHash(const fs::path& file, std::uint64_t found, std::uint64_t expected) {
  if (found != expected)
    throw SceneError(file.string() + ": written by another scene (scene hash differs); pass --force to discard it and "
                     "start again");
}

namespace {

// the text of a node's value as its file wrote it (its source region)
std::string sourceText(const std::string& file, const toml::node& n) {
  if (n.is_table()) return "a table";
  const toml::source_region& r = n.source();
  auto offset = [&](const toml::source_position& p) {
    std::size_t pos = 0;
    for (toml::source_index l = 1; l < p.line && pos != std::string::npos; ++l) {
      pos = file.find('\n', pos);
      if (pos != std::string::npos) ++pos;
    }
    return pos == std::string::npos ? file.size() : std::min(file.size(), pos + p.column - 1);
  };
  const std::size_t from = offset(r.begin), to = offset(r.end);
  return to > from ? file.substr(from, to - from) : "?";
}

struct SceneTexts {
  const std::string& a;
  const std::string& b;
};

// the first place where two TOML nodes differ: its dotted key and line in a (0: a's whole node), "" when
// they are the same
std::string nodeDifference(const toml::node& a, const toml::node& b, const std::string& key, int& line,
                           std::string& valueA, std::string& valueB, const SceneTexts& texts) {
  auto textA = [&](const toml::node& n) { return sourceText(texts.a, n); };
  auto textB = [&](const toml::node& n) { return sourceText(texts.b, n); };
  if (const toml::table* ta = a.as_table(); ta && b.is_table()) {
    const toml::table& tb = *b.as_table();
    for (const auto& [k, v] : *ta) {
      const std::string sub = key.empty() ? std::string(k.str()) : key + "." + std::string(k.str());
      const toml::node* w = tb.get(k.str());
      if (!w) {
        line = static_cast<int>(v.source().begin.line);
        valueA = textA(v);
        valueB = "not set";
        return sub;
      }
      if (std::string d = nodeDifference(v, *w, sub, line, valueA, valueB, texts); !d.empty()) return d;
    }
    for (const auto& [k, v] : tb)
      if (!ta->get(k.str())) {
        line = static_cast<int>(a.source().begin.line);
        valueA = "not set";
        valueB = textB(v);
        return key.empty() ? std::string(k.str()) : key + "." + std::string(k.str());
      }
    return "";
  }
  if (const toml::array* aa = a.as_array(); aa && b.is_array() && aa->is_array_of_tables() == b.as_array()->is_array_of_tables() &&
                                            aa->is_array_of_tables() && aa->size() == b.as_array()->size()) {
    // [[seedling]] and the like: element by element, named by their name (else their index from 1)
    for (std::size_t i = 0; i < aa->size(); ++i) {
      const toml::table* e = aa->get(i)->as_table();
      const std::optional<std::string> name = e ? e->get("name") ? e->get("name")->value<std::string>() : std::nullopt
                                                : std::nullopt;
      const std::string sub = key + (name ? " \"" + *name + "\"" : " " + std::to_string(i + 1));
      if (std::string d = nodeDifference(*aa->get(i), *b.as_array()->get(i), sub, line, valueA, valueB, texts); !d.empty())
        return d;
    }
    return "";
  }
  auto repr = [](const toml::node& n) {
    std::ostringstream os;
    if (const toml::array* arr = n.as_array()) os << *arr;
    else if (const toml::table* t = n.as_table()) os << *t;
    else n.visit([&](const auto& v) { os << v; });
    return os.str();
  };
  if (a.type() == b.type() && repr(a) == repr(b)) return "";
  valueA = textA(a);
  valueB = textB(b);
  line = static_cast<int>(a.source().begin.line);
  return key;
}

}  // namespace

std::string sceneDifference(const std::string& file, const std::string& written, const std::string& current,
                            const std::string& scenePath) {
  toml::table a, b;
  try {
    a = toml::parse(written, file);
    b = toml::parse(current, scenePath);
  } catch (const toml::parse_error& e) {
    return file + " is not the resolved scene (" + std::string(e.description()) + ")";
  }
  int line = 0;
  std::string va, vb;
  const std::string key = nodeDifference(a, b, "", line, va, vb, SceneTexts{written, current});
  if (key.empty()) return file + " differs from this scene in its text only";
  return file + ":" + std::to_string(std::max(line, 1)) + ": " + key + " is " + va + " there, " + vb + " in " + scenePath +
         " with these --set values";
}

void removeStaleTemps(const fs::path& dir, const std::vector<std::string>& streams) {
  std::error_code ec;
  for (const fs::path& d : {dir, dir / "vtk"}) {
    if (!fs::is_directory(d, ec)) continue;
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(d, ec)) {
      const std::string name = e.path().filename().string();
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0 &&
          std::find(streams.begin(), streams.end(), name.substr(0, name.size() - 4)) == streams.end())
        stale.push_back(e.path());
    }
    for (const auto& f : stale) fs::remove(f, ec);
  }
}

}  // namespace rootsim::detail
