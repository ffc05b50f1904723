// One scene -> one run directory (used by `rootsim run` and by sweeps).
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include <optional>

#include "rootsim/checkpoint.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/limits.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/results.hpp"
#include "rootsim/units.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/run_seams.hpp"
#include "rootsim/run_watch.hpp"
#include "rootsim/version.hpp"
#include "root_outputs.hpp"

#include <algorithm>
#include <optional>
#include <sstream>

#include <toml++/toml.h>

namespace fs = std::filesystem;

namespace rootsim {

using namespace detail;

namespace detail {

namespace {

// the first place where two TOML nodes differ: its dotted key and line in a (0: a's whole node), "" when
// they are the same
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

}  // namespace detail

double runSceneToDir(const Scene& sc, const std::string& outDir, const RunDirOptions& dirOptions,
                     const std::function<void(const StepRecord&, int total)>& progress) {
  if (sc.isPlate()) return runPlateToDir(sc, outDir, dirOptions, progress);
  const Model& m = sc.model;
  const std::uint64_t hash = sceneHash(sc.resolvedToml);
  std::optional<RunCheckpoint> ck;
  const PartialRun partial = dirOptions.resume ? resumePlan(sc, outDir, dirOptions.force,
                                                            [&](const fs::path& file) {
                                                              ck.reset();
                                                              ck = readCheckpoint(file);
                                                              checkSceneHash(file, ck->sceneHash, hash);
                                                              checkStreamLengths(file.parent_path(), m, ck->writers);
                                                            })
                                               : PartialRun::Refuse;
  if (partial != PartialRun::Continue) ck.reset();
  RunDir rd(outDir, dirOptions, partial);
  noteResume(dirOptions, rd, partial, ck ? ck->step : 0, m.growth.steps);
  const double t0 = now();
  try {
    const fs::path w = rd.work();
    std::unique_ptr<Simulation> simp;
    std::unique_ptr<RootStreams> out;
    RunWatch watch;
    double wallBefore = 0;         // wall time of earlier attempts (resumed) [s]
    int first = 1;                 // the first growth step this process runs
    if (ck) {
      // resumed: the state, the solvers' memory and the writers where the checkpoint saw them
      removeStaleTemps(w, kRootStreams);
      simp = std::make_unique<Simulation>(m, ck->state, ck->carry);
      out = std::make_unique<RootStreams>(w, m, &ck->writers);
      watch = ck->acc.watch;
      wallBefore = ck->acc.wallBefore;
      first = ck->step + 1;
    } else {
      rd.write("scene.toml", sc.resolvedToml);
      simp = std::make_unique<Simulation>(m);
      out = std::make_unique<RootStreams>(w, m);
    }
    Simulation& sim = *simp;
    if (!ck) {
      out->add(sim);
      watch.start(sim.last());
    }
    // a checkpoint: everything carried to the next step, and where the files stand (each add() flushed)
    auto checkpoint = [&](int k) {
      RunCheckpoint c;
      c.sceneHash = hash;
      c.step = k;
      c.state = sim.state();
      c.carry = sim.carry();
      c.acc = {watch, wallBefore + (now() - t0)};
      c.writers = out->positions();
      writeCheckpoint(w / kCheckpointFile, c);
    };
    const int steps = m.growth.enabled ? m.growth.steps : 0;
    const StepRecord* r = nullptr;
    runGrowthSteps(first, steps, m.output.checkpointEvery, RunSteps{
        [&](int) {
          r = &sim.growthStep();
          watch.see(*r);
        },
        [&](int k) {
          if (k % m.output.everySteps == 0 || k == steps) out->add(sim);
        },
        checkpoint,
        [&](int) {
          if (progress) progress(*r, steps);
        },
        [&] { out->closeQuietly(); }});
    out->close();
    // the finished run holds no checkpoint: it is the same as a run never interrupted
    std::error_code ec;
    fs::remove(w / kCheckpointFile, ec);
    const double wall = wallBefore + (now() - t0);
    const RootFinal f = finishRoot(m, sim, watch, wall);
    rd.write("shape.csv", f.shape);
    rd.write("summary.json", f.summary);
    rd.write("result.csv", f.result);
    rd.commit();
    return wall;
  } catch (const RunInterrupted&) {
    throw;  // stopped on purpose (a progress callback threw it): DIR.partial stays, like a killed run
  } catch (const std::exception& e) {
    rd.fail(failureText(e, "the run of " + sc.model.name + " into " + rd.work().string()));
    throw;
  }
}

}  // namespace rootsim
