// running a plate scene into a run directory (src/io/run_plate.cpp): a plate killed after a checkpoint
// and resumed writes the same bytes as one never interrupted, in every file of the plate and of every
// root's folder (summary.json's wall time aside), roots in contact and lateral roots emerging included;
// a plate of another scene is refused naming the key that differs; a plate that cannot write fails naming
// the file and the growth step.
//
// Kills as in test_run_scene.cpp: the test binary rootsim_killable with ROOTSIM_TEST_KILL="C:K" (a
// checkpoint after growth step C, _Exit(137) after step K), and a real SIGKILL wherever it lands.
#include <doctest/doctest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {
using rootsim::test::checkSameRun;
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::runKilled;
using rootsim::test::slurp;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("run_plate", name); }

// two roots grown into each other: they touch from step ~220 on
const std::string kCollision = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/plate_collision.toml";
const std::string kCollisionSets = " --set growth.steps=300 --set output.trajectory_format=both "
                                   "--set output.checkpoint_every_s=1e6 --quiet";
// two seedlings whose laterals emerge at steps 1, 25, 51, 76, 100, 126, 151, 176 and touch from step ~130
const std::string kLaterals = std::string(ROOTSIM_SOURCE_DIR) + "/tests/data/plate/laterals_touching.toml";

// the growth step of a checkpoint (its header: checkpoint.hpp), -1 when there is none yet
int checkpointStep(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char h[28];
  if (!in.read(h, sizeof h)) return -1;
  std::int32_t step = 0;
  std::memcpy(&step, h + 24, 4);
  return step;
}
}  // namespace

TEST_CASE("a plate killed in steps with roots in contact resumes to the same bytes as an uninterrupted plate") {
  const fs::path d = scratch("contact");
  const std::string args = "run " + kCollision + kCollisionSets + " --out ";
  REQUIRE(run(args + (d / "a").string()).code == 0);
  CHECK(slurp(d / "a" / "plate_timeseries.csv").find("\n250,12.5,2,") != std::string::npos);  // in contact there
  // the checkpoint of step 250, the kill 20 steps later: the rows and snapshots of steps 255-270 are on
  // disk and must be cut back and written again
  CHECK(runKilled(args + (d / "b").string(), "250:270").code == 137);
  CHECK(!fs::exists(d / "b"));
  REQUIRE(checkpointStep(d / "b.partial" / "checkpoint.bin") == 250);
  CHECK(fs::exists(d / "b.partial" / "roots" / "down" / "vtk" / "step_000270.vtp"));
  const Result r = run(args + (d / "b").string() + " --resume");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  CHECK(!fs::exists(d / "b.partial"));
  CHECK(!fs::exists(d / "b" / "checkpoint.bin"));
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("a plate killed between lateral emergences resumes to the same bytes as an uninterrupted plate") {
  const fs::path d = scratch("laterals");
  const std::string args = "run " + kLaterals + " --quiet --out ";
  REQUIRE(run(args + (d / "a").string()).code == 0);
  REQUIRE(fs::exists(d / "a" / "roots" / "b.8"));
  struct Kill {
    const char* hook;
    const char* what;
  };
  for (const Kill& k : {Kill{"60:110", "laterals emerged after the checkpoint (their folders go, they emerge again)"},
                        Kill{"25:26", "the checkpoint in the step a lateral emerged, before its first row"},
                        Kill{"160:185", "laterals in contact with the other seedling's, one emerging after the checkpoint"}}) {
    INFO(k.hook << ": " << k.what);
    const fs::path b = d / (std::string("b_") + std::string(k.hook).replace(std::string(k.hook).find(':'), 1, "_"));
    CHECK(runKilled(args + b.string(), k.hook).code == 137);
    const Result r = run(args + b.string() + " --resume");
    REQUIRE_MESSAGE(r.code == 0, r.out);
    checkSameRun(d / "a", b);
  }
  fs::remove_all(d);
}

TEST_CASE("a plate killed with SIGKILL in the middle of a step with roots in contact resumes to the same bytes") {
  // a checkpoint after every step; the signal lands wherever the plate is once the checkpoint says step 230
  // (the roots in contact), inside a coupled Newton solve or a checkpoint write alike
  const fs::path d = scratch("sigkill");
  const std::string sets = " --set growth.steps=300 --set output.checkpoint_every_s=0 --quiet --out ";
  REQUIRE(run("run " + kCollision + sets + (d / "a").string()).code == 0);
  const std::string out = (d / "b").string();
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::execl(ROOTSIM_BINARY, ROOTSIM_BINARY, "run", kCollision.c_str(), "--set", "growth.steps=300", "--set",
            "output.checkpoint_every_s=0", "--quiet", "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  bool ended = false;
  while (checkpointStep(d / "b.partial" / "checkpoint.bin") < 230 && !ended) {
    ::usleep(1000);
    ended = ::waitpid(pid, &status, WNOHANG) == pid;
  }
  if (!ended) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  REQUIRE_MESSAGE(WIFSIGNALED(status), "the plate ended before it could be killed");
  CHECK(!fs::exists(d / "b"));
  const Result r = run("run " + kCollision + sets + out + " --resume");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  CHECK(r.out.find("resuming " + out + " from the checkpoint of growth step ") != std::string::npos);
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("resume of a plate by another scene exits 2 naming the file line and key and with --force starts again") {
  const fs::path d = scratch("otherscene");
  const std::string out = (d / "b").string();
  CHECK(runKilled("run " + kCollision + kCollisionSets + " --out " + out, "30:35").code == 137);
  const std::string partial = (d / "b.partial").string();
  const std::string before = slurp(d / "b.partial" / "checkpoint.bin");
  const Result r = run("run " + kCollision + kCollisionSets + " --set plane.alpha_deg=50 --out " + out + " --resume");
  CHECK(r.code == 2);
  CHECK(rootsim::test::oneLine(r.out.substr(0, r.out.size() - 1)));
  CHECK(r.out.find("rootsim: error: --resume: " + partial + " was written by another scene (" + partial +
                   "/scene.toml:") != std::string::npos);
  CHECK(r.out.find(": plane.alpha_deg is 40.0 there, 50.0 in " + kCollision) != std::string::npos);
  CHECK(slurp(d / "b.partial" / "checkpoint.bin") == before);  // nothing touched
  // a seedling's key: named by the seedling
  {
    std::string scene = slurp(kCollision);
    scene.replace(scene.find("position_mm = [23, 7]"), 21, "position_mm = [24, 7]");
    std::ofstream(d / "moved.toml") << scene;
  }
  const Result moved = run("run " + (d / "moved.toml").string() + kCollisionSets + " --out " + out + " --resume");
  CHECK(moved.code == 2);
  CHECK(moved.out.find("seedling \"across\".position_mm is [23.0, 7.0] there, [24.0, 7.0] in ") != std::string::npos);
  const Result forced = run("run " + kCollision + kCollisionSets + " --set plane.alpha_deg=50 --out " + out + " --resume --force");
  CHECK(forced.code == 0);
  CHECK(slurp(d / "b" / "scene.toml").find("alpha_deg = 50") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("a plate whose files cannot be written stops with exit 1 naming the file and the growth step") {
  // SIGXFSZ ignored, so a write past the limit fails with EFBIG like a full disk fails with ENOSPC
  const fs::path d = scratch("fsize");
  const Result r = run("--version >/dev/null; trap '' XFSZ; ulimit -f 64; " + std::string(ROOTSIM_BINARY) + " run " +
                       kCollision + " --set output.vtk=false --quiet --out " + (d / "out").string());
  CHECK(r.code == 1);
  CHECK(rootsim::test::oneLine(r.out.substr(0, r.out.size() - 1)));
  CHECK(r.out.find("rootsim: run failed: write error on " + (d / "out").string() + ".partial/roots/") == 0);
  CHECK(r.out.find("(disk full?): File too large (at growth step ") != std::string::npos);
  CHECK(r.out.find(" of 600)") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
  CHECK(!fs::exists(d / "out.partial"));
  CHECK(slurp(d / "out.incomplete" / "ERROR.txt").find("write error on") == 0);
  fs::remove_all(d);
}
