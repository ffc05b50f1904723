// running a scene into a run directory (src/io/run_scene.cpp): checkpoints and `rootsim run --resume`
// a run killed after a checkpoint and resumed writes the same bytes as one never
// interrupted (summary.json's wall time aside); refusals; a progress hook stopping the run.
//
// A kill is emulated by the test binary rootsim_killable (tests/seams/kill_at_step.cpp) with
// ROOTSIM_TEST_KILL="C:K": a checkpoint after growth step C, then _Exit(137) after step K, leaving
// DIR.partial as SIGKILL would (the files written after the checkpoint included, so resuming has to cut
// them back).
#include <doctest/doctest.h>

#include <sys/mount.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>
#include <signal.h>
#include <sys/wait.h>

#include "rootsim/errors.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/run_scene.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/units.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::slurp;
using rootsim::test::checkSameRun;
using rootsim::test::kScene;
using rootsim::test::kSets;
using rootsim::test::runKilled;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("run_scene", name); }
}  // namespace

TEST_CASE("a killed run resumed from its checkpoint writes the same bytes as an uninterrupted run") {
  struct Variant {
    const char* name;
    std::string scene;
  };
  const std::string src = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/";
  for (const Variant& v : {Variant{"newton", kScene}, Variant{"dynamic", kScene + " --set solver.kind=dynamic"},
                           Variant{"friction", src + "friction_waving.toml"},
                           Variant{"obstacle", src + "obstacle_peg.toml"},
                           Variant{"window", kScene + " --set solver.window_mm=1"},
                           // a long frozen part at the checkpoint (4 mm, ~80 elements): the frozen
                           // twists' kept stiffness carried over it
                           Variant{"frozen", kScene + " --set solver.window_mm=1 --set growth.step_h=0.5"},
                           // a coil in self-contact from step 30 on: the sparse Jacobian's pattern,
                           // pivots and last factors (the next step's chord step) carried over the
                           // checkpoint
                           Variant{"coil", src + "fig2a_alpha90.toml --set tropism.beta=1 --set growth.step_h=0.2"}}) {
    const std::string variant = v.name;
    CAPTURE(variant);
    const fs::path d = scratch(std::string("same_") + v.name);
    const std::string args = "run " + v.scene + kSets + " --out ";
    REQUIRE(run(args + (d / "a").string()).code == 0);
    // killed at step 63, 16 steps after the checkpoint of step 47: the frames of steps 50 and 60 are on
    // disk and must be cut back and written again
    const Result k = runKilled(args + (d / "b").string(), "47:63");
    CHECK(k.code == 137);
    CHECK(!fs::exists(d / "b"));
    REQUIRE(fs::exists(d / "b.partial" / "checkpoint.bin"));
    CHECK(fs::exists(d / "b.partial" / "vtk" / "step_000060.vtp"));
    const Result r = run(args + (d / "b").string() + " --resume");
    REQUIRE_MESSAGE(r.code == 0, r.out);
    CHECK(r.out.find("resuming " + (d / "b").string() + " from the checkpoint of growth step 47 of 120") != std::string::npos);
    CHECK(!fs::exists(d / "b.partial"));
    CHECK(!fs::exists(d / "b" / "checkpoint.bin"));
    checkSameRun(d / "a", d / "b");
    fs::remove_all(d);
  }
}

TEST_CASE("a run killed with SIGKILL once a checkpoint exists resumes to the same bytes") {
  // the real thing, at whatever point of the step the signal lands (inside a checkpoint write included)
  const fs::path d = scratch("sigkill");
  const std::string sets = " --set growth.steps=1000 --set output.checkpoint_every_s=0.05 --quiet --out ";
  REQUIRE(run("run " + kScene + sets + (d / "a").string()).code == 0);
  const std::string out = (d / "b").string();
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::execl(ROOTSIM_BINARY, ROOTSIM_BINARY, "run", kScene.c_str(), "--set", "growth.steps=1000", "--set",
            "output.checkpoint_every_s=0.05", "--quiet", "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // wait for the first checkpoint, let the run go on a little, kill it
  int status = 0;
  bool ended = false;
  while (!fs::exists(d / "b.partial" / "checkpoint.bin") && !ended) {
    ::usleep(2000);
    ended = ::waitpid(pid, &status, WNOHANG) == pid;
  }
  ::usleep(30000);
  if (!ended) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  REQUIRE_MESSAGE(WIFSIGNALED(status), "the run ended before it could be killed");
  CHECK(!fs::exists(d / "b"));
  const Result r = run("run " + kScene + sets + out + " --resume");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("a run killed twice (the second time while resuming) still ends with the same bytes") {
  const fs::path d = scratch("twice");
  const std::string args = "run " + kScene + kSets + " --out ";
  REQUIRE(run(args + (d / "a").string()).code == 0);
  CHECK(runKilled(args + (d / "b").string(), "20:29").code == 137);
  CHECK(runKilled(args + (d / "b").string() + " --resume", "75:99").code == 137);
  // a checkpoint writer killed mid-write leaves checkpoint.bin.tmp: ignored and removed
  { std::ofstream(d / "b.partial" / "checkpoint.bin.tmp") << "torn"; }
  { std::ofstream(d / "b.partial" / "vtk" / "step_000080.vtp.tmp") << "torn"; }
  const Result r = run(args + (d / "b").string() + " --resume");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("resume on a complete run says so and exits 0 and on another scene's complete run exits 2") {
  const fs::path d = scratch("complete");
  const std::string out = (d / "a").string();
  REQUIRE(run("run " + kScene + kSets + " --out " + out).code == 0);
  const std::string before = slurp(d / "a" / "summary.json");
  const Result again = run("run " + kScene + kSets + " --out " + out + " --resume");
  CHECK(again.code == 0);
  CHECK(again.out.find("is complete: nothing to resume") != std::string::npos);
  CHECK(slurp(d / "a" / "summary.json") == before);
  const Result other = run("run " + kScene + kSets + " --set tropism.beta=0.3 --out " + out + " --resume");
  CHECK(other.code == 2);
  CHECK(other.out.find("complete run of another scene") != std::string::npos);
  CHECK(slurp(d / "a" / "summary.json") == before);
  fs::remove_all(d);
}

TEST_CASE("resume refuses an interrupted run of another scene with exit 2 and with --force starts again") {
  const fs::path d = scratch("otherscene");
  const std::string out = (d / "b").string();
  CHECK(runKilled("run " + kScene + kSets + " --out " + out, "30:35").code == 137);
  const Result r = run("run " + kScene + kSets + " --set plane.alpha_deg=50 --out " + out + " --resume");
  CHECK(r.code == 2);
  CHECK(r.out.find("written by another scene") != std::string::npos);
  CHECK(fs::exists(d / "b.partial" / "checkpoint.bin"));
  // without --resume the interrupted run is not discarded either; the message says how to continue
  const Result plain = run("run " + kScene + kSets + " --out " + out);
  CHECK(plain.code == 2);
  CHECK(plain.out.find("--resume") != std::string::npos);
  const Result forced = run("run " + kScene + kSets + " --set plane.alpha_deg=50 --out " + out + " --resume --force");
  CHECK(forced.code == 0);
  CHECK(slurp(d / "b" / "scene.toml").find("alpha_deg = 50") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("a progress hook throwing RunInterrupted stops the run and leaves DIR.partial, not DIR.incomplete") {
  const fs::path d = scratch("interrupt");
  const Scene sc = loadScene(kScene, {"growth.steps=50"});
  int last = 0;
  CHECK_THROWS_AS(runSceneToDir(sc, (d / "run").string(), {},
                                [&](const StepRecord& r, int) {
                                  last = r.step;
                                  if (r.step == 7) throw RunInterrupted("stop");
                                }),
                  RunInterrupted);
  CHECK(last == 7);
  CHECK(fs::is_regular_file(d / "run.partial" / kRunMarker));
  CHECK(!fs::exists(d / "run"));
  CHECK(!fs::exists(d / "run.incomplete"));
  fs::remove_all(d);
}

TEST_CASE("the production binary has no kill seam: ROOTSIM_TEST_KILL changes nothing") {
  const fs::path d = scratch("no_seam");
  ::setenv("ROOTSIM_TEST_KILL", "2:3", 1);
  const Result r = run("run " + kScene + " --set growth.steps=6 --quiet --out " + (d / "a").string());
  ::unsetenv("ROOTSIM_TEST_KILL");
  CHECK(r.code == 0);
  CHECK(fs::exists(d / "a" / "summary.json"));
  CHECK(!fs::exists(d / "a.partial"));
}
