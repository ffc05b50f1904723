// the rootsim binary: exit codes, messages, run directories, determinism (src/cli, src/io/run_dir.cpp)
#include <doctest/doctest.h>

#include "run_rootsim.hpp"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {
using rootsim::test::Result;
using rootsim::test::run;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// a fresh scratch folder per test
fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("rootsim_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

const std::string kSmall = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml --set growth.steps=30 "
                           "--set output.every_steps=5 --quiet";
}  // namespace

TEST_CASE("--version and --help exit 0") {
  const Result v = run("--version");
  CHECK(v.code == 0);
  CHECK(v.out.find("rootsim 0.") != std::string::npos);
  CHECK(run("--help").code == 0);
  CHECK(run("run --help").code == 0);
}

TEST_CASE("bad usage exits 2") {
  CHECK(run("").code == 2);
  CHECK(run("frobnicate").code == 2);
  const Result r = run("run /nonexistent/x.toml");
  CHECK(r.code == 2);
  CHECK(r.out.find("/nonexistent/x.toml: no such scene file") != std::string::npos);
}

TEST_CASE("a bad scene exits 2 with file:line:key and writes nothing") {
  const fs::path d = scratch("bad");
  { std::ofstream(d / "bad.toml") << "[tropism]\nbeta = 0.1\nbta = 0.2\n"; }
  const Result r = run("run " + (d / "bad.toml").string() + " --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK(r.out.find("bad.toml:3: unknown key tropism.bta (did you mean tropism.beta?)") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
  CHECK(!fs::exists(d / "out.partial"));
  const Result s = run("run " + kSmall + " --set plane.alpha_deg=120 --out " + (d / "out").string());
  CHECK(s.code == 2);
  CHECK(s.out.find("--set plane.alpha_deg=120: plane.alpha_deg must be in [0, 90]") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
}

TEST_CASE("an unwritable or foreign output folder exits 2") {
  const Result r = run("run " + kSmall + " --out /proc/rootsim_cannot_write_here");
  CHECK(r.code == 2);
  CHECK(r.out.find("cannot create") != std::string::npos);
  const fs::path d = scratch("foreign");
  { std::ofstream(d / "notes.txt") << "mine\n"; }
  const Result f = run("run " + kSmall + " --out " + d.string());
  CHECK(f.code == 2);
  CHECK(f.out.find("is not a rootsim run directory") != std::string::npos);
  CHECK(fs::exists(d / "notes.txt"));
}

TEST_CASE("a run that fails exits 1 and keeps its partial output marked incomplete") {
  const fs::path d = scratch("fail");
  const Result r = run("run " + kSmall + " --set solver.max_substeps=3 --out " + (d / "out").string());
  CHECK(r.code == 1);
  CHECK(r.out.find("did not reach equilibrium in 3 sub-steps") != std::string::npos);
  CHECK(!fs::exists(d / "out"));
  CHECK(fs::exists(d / "out.incomplete" / "ERROR.txt"));
  CHECK(fs::exists(d / "out.incomplete" / "scene.toml"));
}

TEST_CASE("determinism: the same scene twice gives identical files") {
  const fs::path d = scratch("det");
  REQUIRE(run("run " + kSmall + " --out " + (d / "a").string()).code == 0);
  REQUIRE(run("run " + kSmall + " --out " + (d / "b").string()).code == 0);
  for (const char* f : {"scene.toml", "timeseries.csv", "shape.csv", "trajectory.csv", "trajectory.pvd",
                        "vtk/step_000030.vtp"}) {
    INFO(f);
    const std::string a = slurp(d / "a" / f), b = slurp(d / "b" / f);
    CHECK(!a.empty());
    CHECK(a == b);
  }
  // summary.json: identical except the wall time
  auto strip = [](std::string s) {
    const auto p = s.find("\"wall_time_s\"");
    return p == std::string::npos ? s : s.substr(0, p);
  };
  CHECK(strip(slurp(d / "a" / "summary.json")) == strip(slurp(d / "b" / "summary.json")));
  // the resolved scene reproduces the run
  REQUIRE(run("run " + (d / "a" / "scene.toml").string() + " --quiet --out " + (d / "c").string()).code == 0);
  CHECK(slurp(d / "c" / "timeseries.csv") == slurp(d / "a" / "timeseries.csv"));
}

TEST_CASE("check prints the resolved scene and the theory") {
  const Result r = run("check " + std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2b_waving.toml");
  CHECK(r.code == 0);
  CHECK(r.out.find("beta = 0.2") != std::string::npos);
  CHECK(r.out.find("\"T0_h\": 5.18") != std::string::npos);
}

TEST_CASE("every shipped scene and sweep validates, and every scene runs coarsened") {
  const fs::path src = ROOTSIM_SOURCE_DIR;
  const fs::path d = scratch("scenes");
  int n = 0;
  for (const auto& e : fs::directory_iterator(src / "scenes")) {
    if (e.path().extension() != ".toml") continue;
    INFO(e.path().string());
    CHECK(run("check " + e.path().string()).code == 0);
    // coarsened: 20 growth steps of 0.1 h with 0.1 mm elements (mechanics scenes: as they are)
    const std::string scene = slurp(e.path());
    const bool grows = scene.find("[growth]\nenabled = false") == std::string::npos;
    const std::string sets = grows ? " --set growth.steps=20 --set growth.step_h=0.1 --set root.element_length_mm=0.1"
                                   : "";
    const Result r = run("run " + e.path().string() + sets + " --quiet --set output.vtk=false --out " +
                         (d / e.path().stem()).string());
    CHECK(r.code == 0);
    CHECK(fs::exists(d / e.path().stem() / "summary.json"));
    ++n;
  }
  CHECK(n >= 10);
  for (const auto& e : fs::directory_iterator(src / "sweeps")) {
    INFO(e.path().string());
    // --shard 1/1000 keeps at most one point: validates the whole grid, runs almost nothing
    const Result r = run("sweep " + e.path().string() + " --shard 1000/1000 --quiet --out " +
                         (d / ("sweep_" + e.path().stem().string())).string());
    CHECK(r.code == 0);
  }
}
