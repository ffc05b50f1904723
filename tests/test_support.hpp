#pragma once
// Process and file helpers shared by the tests that run the rootsim binary or read run directories
// (rootsim_io_tests, test_figure.cpp, and tests/render through run_rootsim.hpp and test_files.hpp): running the binary,
// a skipped case, a fresh scratch folder, a file's bytes, a folder's files, two runs compared byte for
// byte, a run killed by the test hook, a small grown root for the writers. The binary helpers need ROOTSIM_BINARY, the
// scene paths ROOTSIM_SOURCE_DIR (tests/CMakeLists.txt).
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "rootsim/model.hpp"
#include "rootsim/output_params.hpp"
#include "rootsim/rod.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/units.hpp"
#include "scratch_support.hpp"
#include "tolerance_support.hpp"

namespace rootsim::test {

// --- the rootsim binary ---

#ifdef ROOTSIM_BINARY
struct Result {
  int code;
  std::string out;  // stdout + stderr
};

// runs the rootsim binary (ROOTSIM_BINARY, set by CMake) with arguments; exit code and all its output
inline Result runBinary(const std::string& binary, const std::string& args) {
  const std::string cmd = binary + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  std::string out;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}
inline Result run(const std::string& args) { return runBinary(ROOTSIM_BINARY, args); }

// runs rootsim with dir as the working directory
inline Result runIn(const std::filesystem::path& dir, const std::string& args) {
  return run("--version >/dev/null && cd '" + dir.string() + "' && " + std::string(ROOTSIM_BINARY) + " " + args);
}

#ifdef ROOTSIM_KILLABLE_BINARY
// runs the test binary rootsim_killable with ROOTSIM_TEST_KILL="C:K" (tests/seams/kill_at_step.cpp: a
// checkpoint after growth step C, then _Exit(137) after step K, leaving DIR.partial as SIGKILL would)
inline Result runKilled(const std::string& args, const std::string& hook) {
  ::setenv("ROOTSIM_TEST_KILL", hook.c_str(), 1);
  Result r = runBinary(ROOTSIM_KILLABLE_BINARY, args);
  ::unsetenv("ROOTSIM_TEST_KILL");
  return r;
}
#endif  // ROOTSIM_KILLABLE_BINARY

#endif  // ROOTSIM_BINARY

#ifdef ROOTSIM_SOURCE_DIR
// shipped scenes the tests run
inline const std::string kScene = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml";
inline const std::string kCantilever = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/cantilever_tip_load.toml";
#ifdef ROOTSIM_BINARY
// `rootsim run` of kScene into out with more arguments (--set ..., --quiet), required to succeed: out
inline std::filesystem::path runScene(const std::filesystem::path& out, const std::string& args) {
  const Result r = run("run " + kScene + " " + args + " --out " + out.string());
  REQUIRE_MESSAGE(r.code == 0, r.out);
  return out;
}
#endif
#endif
// the resume tests' settings: every output on (both trajectory formats, ParaView), checkpoints only
// where the kill hook asks
inline const std::string kSets = " --set growth.steps=120 --set output.every_steps=10 --set output.trajectory_format=both "
                                 "--set output.checkpoint_every_s=1e6 --quiet";

// --- a small grown root ---

// the default model with 0.1 mm elements and 0.1 h growth steps, completed: the writers' tests' model
inline Model coarseModel() {
  Model m = defaultModel();
  m.initial.elementLength = 0.1 * units::mm;
  m.growth.stepTime = 0.1 * units::hour;
  completeModel(m);
  return m;
}
// the same run for the given number of growth steps
inline Model coarseModel(int steps) {
  Model m = coarseModel();
  m.growth.steps = steps;
  return m;
}

// what a root's writers are asked for in their tests: the trajectory in the given format, no ParaView files
inline OutputParams rootWriterOutputs(TrajectoryFormat trajectory = OutputParams{}.trajectoryFormat) {
  OutputParams o;
  o.trajectoryFormat = trajectory;
  o.vtk = false;
  return o;
}

// a root of coarseModel() grown for a few steps: its model, simulation and strains
struct GrownRoot {
  Model m;
  Simulation sim;
  RodStrains k;
  explicit GrownRoot(int steps = 8) : m(coarseModel()), sim(m) { grow(steps); }
  // steps more growth steps, the strains of the grown state
  void grow(int steps) {
    for (int i = 0; i < steps; ++i) sim.growthStep();
    k.resize(sim.state().elements());
    computeStrains(m.rod, sim.state(), k);
  }
};

// --- skipped cases ---

// a case that cannot run here says why on stdout; ctest's SKIP_REGULAR_EXPRESSION (tests/CMakeLists.txt)
// then reports it as skipped, never as passed
inline void skipCase(const std::string& why) {
  std::printf("rootsim-test-skipped: %s\n", why.c_str());
  std::fflush(stdout);
}

// --- files ---

// the bytes of a file ("" when it cannot be read)
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// the number of lines of a text (its newlines)
inline int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// a message on one line
inline bool oneLine(const std::string& s) { return s.find('\n') == std::string::npos && s.find('\r') == std::string::npos; }

// every file below d (relative path -> bytes), and with withDirs every folder too (as "<dir>"): a folder
// compared before and after
inline std::map<std::string, std::string> fileTree(const std::filesystem::path& d, bool withDirs = false) {
  std::map<std::string, std::string> t;
  for (const auto& e : std::filesystem::recursive_directory_iterator(d)) {
    if (e.is_regular_file())
      t[std::filesystem::relative(e.path(), d).string()] = slurp(e.path());
    else if (withDirs)
      t[std::filesystem::relative(e.path(), d).string()] = "<dir>";
  }
  return t;
}

// --- two runs compared ---

// summary.json without its wall time (the one field that may differ)
inline std::string stripWall(std::string s) {
  const auto p = s.find("\"wall_time_s\"");
  if (p != std::string::npos) s.erase(p, s.find('\n', p) - p);
  return s;
}

// the two run directories hold the same files with the same bytes (summary.json's wall time aside; the
// marker records summary.json without it, so the markers are the same bytes)
inline void checkSameRun(const std::filesystem::path& a, const std::filesystem::path& b) {
  auto files = [](const std::filesystem::path& dir) {
    std::map<std::string, std::string> out = fileTree(dir);
    for (auto& [rel, bytes] : out)
      if (rel == "summary.json" || (rel.size() > 13 && rel.compare(rel.size() - 13, 13, "/summary.json") == 0))
        bytes = stripWall(bytes);
    return out;
  };
  const auto fa = files(a), fb = files(b);
  std::string namesA, namesB;
  for (const auto& [k, v] : fa) namesA += k + " ";
  for (const auto& [k, v] : fb) namesB += k + " ";
  CHECK(namesA == namesB);
  for (const auto& kv : fa) {
    const std::string& k = kv.first;
    const std::string& v = kv.second;
    INFO(k);
    const auto it = fb.find(k);
    REQUIRE(it != fb.end());
    CHECK(!v.empty());
    CHECK(v.size() == it->second.size());
    CHECK((v == it->second));
  }
}

}  // namespace rootsim::test
