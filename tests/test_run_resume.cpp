// What a resumed run checks and cleans (src/io/run_resume.cpp): the plan for an interrupted DIR.partial
// (continue, discard, refuse), the first key where another scene differs, the streams' lengths against
// the checkpoint, and the leftovers of atomic writes.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rootsim/errors.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/scene.hpp"
#include "run_resume.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;
using detail::resumePlan;

namespace {
Scene sceneWithSteps(int steps) { return loadScene(rootsim::test::kScene, {"growth.steps=" + std::to_string(steps)}); }
// an interrupted run: DIR.partial with its marker, holding `scene` as its resolved scene when not empty
void interrupted(const fs::path& out, const std::string& scene) {
  RunDir rd(out, RunDirOptions{});
  if (!scene.empty()) rd.write("scene.toml", scene);
}
std::string message(const std::function<void()>& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("resume plan: nothing to resume, nothing to lose, another scene, a finished run, a usable or broken checkpoint") {
  const fs::path d = rootsim::test::scratchDir("run_resume", "plan");
  const Scene sc = sceneWithSteps(30);
  const fs::path out = d / "out";
  const fs::path partial = out.string() + ".partial";
  int loads = 0;
  auto load = [&](const fs::path& file) {
    ++loads;
    CHECK(file == partial / kCheckpointFile);
  };
  CHECK(resumePlan(sc, out.string(), false, load) == PartialRun::Refuse);  // a new run
  interrupted(out, "");
  CHECK(resumePlan(sc, out.string(), false, load) == PartialRun::Discard);  // killed before its scene
  fs::remove_all(partial);

  interrupted(out, sceneWithSteps(40).resolvedToml);
  const std::string other = message([&] { resumePlan(sc, out.string(), false, load); });
  CHECK(other.find("--resume: " + partial.string() + " was written by another scene (") != std::string::npos);
  CHECK(other.find("/scene.toml:") != std::string::npos);
  CHECK(other.find(": growth.steps is 40 there, 30 in " + rootsim::test::kScene) != std::string::npos);
  CHECK(resumePlan(sc, out.string(), true, load) == PartialRun::Discard);
  fs::remove_all(partial);

  interrupted(out, sc.resolvedToml);
  CHECK(resumePlan(sc, out.string(), false, load) == PartialRun::Discard);  // killed before its first checkpoint
  std::ofstream(partial / "summary.json") << "{}";
  CHECK(message([&] { resumePlan(sc, out.string(), false, load); }).find("holds a finished run without a checkpoint") !=
        std::string::npos);
  fs::remove(partial / "summary.json");

  std::ofstream(partial / kCheckpointFile) << "x";
  CHECK(loads == 0);
  CHECK(resumePlan(sc, out.string(), false, load) == PartialRun::Continue);
  CHECK(loads == 1);
  auto broken = [](const fs::path& file) { throw SceneError(file.string() + ": corrupt"); };
  CHECK(message([&] { resumePlan(sc, out.string(), false, broken); }) == (partial / kCheckpointFile).string() + ": corrupt");
  CHECK(resumePlan(sc, out.string(), true, broken) == PartialRun::Discard);
  fs::remove_all(d);
}

TEST_CASE("resume plan: a folder rootsim did not write at DIR.partial is refused, never taken") {
  const fs::path d = rootsim::test::scratchDir("run_resume", "foreign");
  const fs::path out = d / "out";
  fs::create_directories(out.string() + ".partial");
  const std::string why = message([&] { resumePlan(sceneWithSteps(30), out.string(), true, [](const fs::path&) {}); });
  CHECK(why.find("--out " + out.string() + ": ") == 0);
  CHECK(why.find("is not a") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("scene difference names the file, the line and the first key that differs, as each text wrote it") {
  const std::string a = "[plane]\nalpha_deg = 40\n\n[tropism]\nbeta = 0.1\n";
  const std::string b = "[plane]\nalpha_deg = 40\n\n[tropism]\nbeta = 2e-1\n";
  CHECK(detail::sceneDifference("old.toml", a, b, "new.toml") ==
        "old.toml:5: tropism.beta is 0.1 there, 2e-1 in new.toml with these --set values");
  CHECK(detail::sceneDifference("old.toml", a, a + "# a comment\n", "new.toml") ==
        "old.toml differs from this scene in its text only");
  CHECK(detail::sceneDifference("old.toml", a, "[plane]\nalpha_deg = 40\n", "new.toml") ==
        "old.toml:4: tropism is a table there, not set in new.toml with these --set values");
  CHECK(detail::sceneDifference("old.toml", "[plane", a, "new.toml").find("old.toml is not the resolved scene (") == 0);
}

TEST_CASE("stream lengths: a stream shorter than its checkpoint says is refused naming it, its temporary file read first") {
  const fs::path d = rootsim::test::scratchDir("run_resume", "lengths");
  fs::create_directories(d);
  std::ofstream(d / "timeseries.csv") << "0123456789";
  CHECK_NOTHROW(detail::checkStreamLength(d / "timeseries.csv", 10));
  CHECK_NOTHROW(detail::checkStreamLength(d / "missing.csv", 0));  // a stream never written
  const std::string shorter = message([&] { detail::checkStreamLength(d / "timeseries.csv", 11); });
  CHECK(shorter.find((d / "timeseries.csv").string() + ": missing or shorter (10 bytes) than its checkpoint says (11 bytes)") == 0);
  std::ofstream(d / "timeseries.csv.tmp") << "01234";
  CHECK(message([&] { detail::checkStreamLength(d / "timeseries.csv", 10); })
            .find((d / "timeseries.csv.tmp").string() + ": missing or shorter (5 bytes)") == 0);
  CHECK(message([&] { detail::checkSceneHash(d / "c.bin", 1, 2); }).find("c.bin: written by another scene") != std::string::npos);
  CHECK_NOTHROW(detail::checkSceneHash(d / "c.bin", 2, 2));
  fs::remove_all(d);
}

TEST_CASE("stale temporary files: an interrupted atomic write goes, the streams being continued stay") {
  const fs::path d = rootsim::test::scratchDir("run_resume", "stale");
  fs::create_directories(d / "vtk");
  for (const fs::path& f : {d / "timeseries.csv.tmp", d / "shape.csv.tmp", d / "vtk" / "step_000010.vtp.tmp", d / "scene.toml"})
    std::ofstream(f) << "x";
  detail::removeStaleTemps(d, detail::kRootStreams);
  CHECK(fs::exists(d / "timeseries.csv.tmp"));
  CHECK(fs::exists(d / "scene.toml"));
  CHECK_FALSE(fs::exists(d / "shape.csv.tmp"));
  CHECK_FALSE(fs::exists(d / "vtk" / "step_000010.vtp.tmp"));
  fs::remove_all(d);
}
