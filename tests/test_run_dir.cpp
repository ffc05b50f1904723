// run directories (src/io/run_dir.cpp): RunDir's DIR.partial, commit to DIR with its marker, fail to
// DIR.incomplete, the interrupted run left at DIR.partial, the --out name; files written atomically, a
// write failure (full disk, file size limit) stopping the run at once
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

#include "rootsim/errors.hpp"
#include "rootsim/run_dir.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::slurp;
using rootsim::test::kScene;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("run_dir", name); }

// what a run that could not write its output must leave: exit 1, a message naming the file, no DIR,
// DIR.incomplete or nothing; the failure noticed at the output step where it happened
void checkWriteFailure(const Result& r, const fs::path& out, const std::string& why) {
  CAPTURE(r.out);
  CHECK(r.code == 1);
  const std::regex msg("rootsim: run failed: write error on " + out.string() +
                       R"(\.partial/(trajectory\.csv|trajectory\.bin|timeseries\.csv|checkpoint\.bin) \(disk full\?\): )" + why +
                       R"( \(at growth step (\d+) of 3000\)\n)");
  std::smatch m;
  REQUIRE(std::regex_search(r.out, m, msg));
  // noticed at once: the run had a few frames' worth of room, not 3000 steps
  CHECK(std::stoi(m[2].str()) < 1000);
  CHECK(!fs::exists(out));
  CHECK(!fs::exists(fs::path(out.string() + ".partial")));
  if (fs::exists(fs::path(out.string() + ".incomplete")))
    CHECK(fs::exists(fs::path(out.string() + ".incomplete") / ".rootsim-run"));
}
}  // namespace

TEST_CASE("a full disk stops the run at once with exit 1 and never leaves a whole-looking run") {
  const fs::path d = scratch("diskfull");
  const fs::path mnt = d / "mnt";
  fs::create_directories(mnt);
  if (::geteuid() != 0 || ::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0) {
    rootsim::test::skipCase("mounting a 64 KiB tmpfs needs root (CI runs as root); the injected write failure test "
            "below covers the same path");
    fs::remove_all(d);
    return;
  }
  // output.vtk = false: the case the audit found noticed only after all 3000 steps
  const Result r = run("run " + kScene + " --set output.vtk=false --quiet --out " + (mnt / "out").string());
  checkWriteFailure(r, mnt / "out", "No space left on device");
  ::umount(mnt.c_str());
  fs::remove_all(d);
}

TEST_CASE("an injected write failure (file size limit) stops the run with exit 1 naming the file") {
  const fs::path d = scratch("fsize");
  // SIGXFSZ ignored, so a write past the limit fails with EFBIG like a full disk fails with ENOSPC
  const Result r = run("--version >/dev/null; trap '' XFSZ; ulimit -f 64; " + std::string(ROOTSIM_BINARY) + " run " +
                       kScene + " --set output.vtk=false --quiet --out " + (d / "out").string());
  checkWriteFailure(r, d / "out", "File too large");
  CHECK(fs::exists(d / "out.incomplete" / "ERROR.txt"));
  CHECK(slurp(d / "out.incomplete" / "ERROR.txt").find("write error on") == 0);
  fs::remove_all(d);
}

TEST_CASE("a RunDir writes into DIR.partial, commit makes DIR with its marker listing every file, fail keeps DIR.incomplete") {
  const fs::path d = scratch("states");
  const fs::path out = d / "run";
  {
    RunDir rd(out, {});
    CHECK(rd.final() == out);
    CHECK(rd.work() == fs::path(out.string() + ".partial"));
    CHECK(fs::is_directory(rd.work()));
    CHECK(!fs::exists(out));
    rd.write("scene.toml", "hello");
    rd.write("shape.csv", std::string(1000, 'x'));
    CHECK(slurp(rd.work() / "scene.toml") == "hello");
    rd.commit();
  }
  CHECK(!fs::exists(fs::path(out.string() + ".partial")));
  CHECK(slurp(out / "scene.toml") == "hello");
  CHECK(slurp(out / "shape.csv") == std::string(1000, 'x'));
  const std::string marker = slurp(out / kRunMarker);
  CHECK(marker.rfind("rootsim run directory ", 0) == 0);
  CHECK(marker.find("scene.toml") != std::string::npos);
  CHECK(marker.find("shape.csv") != std::string::npos);
  CHECK(whyNotWhole(out) == "");
  // a file cut short or missing: not whole, and the reason names it
  fs::resize_file(out / "shape.csv", 10);
  CHECK(whyNotWhole(out).find("shape.csv") != std::string::npos);
  fs::remove(out / "scene.toml");
  CHECK(whyNotWhole(out).find("scene.toml") != std::string::npos);
  // an earlier run is replaced only with force, and only while its files are as recorded: the file cut
  // short is no longer rootsim's (refused with force too, naming it) until it is moved away
  CHECK_THROWS_AS(RunDir(out, {}), SceneError);
  {
    RunDirOptions force;
    force.force = true;
    CHECK_THROWS_WITH_AS(RunDir(out, force), doctest::Contains("shape.csv, changed since rootsim wrote it"), SceneError);
  }
  CHECK(fs::file_size(out / "shape.csv") == 10);
  fs::remove(out / "shape.csv");
  {
    RunDirOptions force;
    force.force = true;
    RunDir rd(out, force);
    rd.write("summary.json", "new");
    rd.fail("boom: step 3");
  }
  // failed: DIR.incomplete with what was written and ERROR.txt; the earlier DIR is left as it was
  const fs::path inc = out.string() + ".incomplete";
  CHECK(slurp(inc / "summary.json") == "new");
  CHECK(slurp(inc / "ERROR.txt").find("boom: step 3") != std::string::npos);
  CHECK(fs::exists(inc / kRunMarker));
  CHECK(!fs::exists(fs::path(out.string() + ".partial")));
  fs::remove_all(d);
}

TEST_CASE("a RunDir left without commit or fail stays DIR.partial, refused later unless forced or continued") {
  const fs::path d = scratch("partial");
  const fs::path out = d / "run";
  {
    RunDir rd(out, {});
    rd.write("scene.toml", "first");
  }  // a run that stopped (interrupted): nothing committed
  const fs::path partial = out.string() + ".partial";
  CHECK(slurp(partial / "scene.toml") == "first");
  CHECK(fs::exists(partial / kRunMarker));
  CHECK(!fs::exists(out));
  CHECK_THROWS_AS(RunDir(out, {}), SceneError);
  CHECK(slurp(partial / "scene.toml") == "first");
  {
    RunDir rd(out, {}, PartialRun::Continue);
    CHECK(slurp(rd.work() / "scene.toml") == "first");  // kept: a resumed run writes on
    rd.write("timeseries.csv", "second");
    rd.commit();
  }
  CHECK(slurp(out / "scene.toml") == "first");
  CHECK(slurp(out / "timeseries.csv") == "second");
  CHECK(whyNotWhole(out) == "");
  {
    RunDir rd(d / "other", {});
    rd.write("scene.toml", "x");
  }
  {
    RunDir rd(d / "other", {}, PartialRun::Discard);
    CHECK(!fs::exists(rd.work() / "scene.toml"));  // started again
    rd.commit();
  }
  CHECK(!fs::exists(d / "other" / "scene.toml"));
  // the --out path as the user meant it
  CHECK(normaliseOutDir("out/") == fs::path("out"));
  CHECK(normaliseOutDir("./a/b/") == fs::path("a/b"));
  for (const char* bad : {"", ".", "..", "/", "a/.."}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(normaliseOutDir(bad), SceneError);
  }
  fs::remove_all(d);
}

TEST_CASE("two runs of one scene are the same bytes in every file, the marker too, but summary.json's wall time") {
  const fs::path d = scratch("same_bytes");
  const std::string sets = " --set growth.steps=40 --set root.element_length_mm=0.1 --set output.every_steps=10 --quiet";
  for (const char* name : {"a", "b"}) REQUIRE(run("run " + kScene + sets + " --out " + (d / name).string()).code == 0);
  // every file compared (summary.json without its wall_time_s)
  rootsim::test::checkSameRun(d / "a", d / "b");
  CHECK(slurp(d / "a" / ".rootsim-run") == slurp(d / "b" / ".rootsim-run"));
  // the wall times differ in their digits, yet the markers agree: the marker leaves that field out
  CHECK(slurp(d / "a" / ".rootsim-run").find("file summary.json - ") != std::string::npos);
  fs::remove_all(d);
}
