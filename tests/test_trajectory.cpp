// trajectory.csv and trajectory.bin (src/io/trajectory.cpp): written by their writers and read back
// (readTrajectory) as the snapshots, a continued file replacing what followed, and every malformed,
// truncated, corrupt or out-of-bounds file refused naming the file and the line or byte.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/snapshot.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::runScene;
using rootsim::test::slurp;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("trajectory", name); }
}  // namespace

TEST_CASE("a trajectory with NaN or inf or a malformed cell is refused naming file and line") {
  const fs::path d = scratch("traj");
  const std::string head = "frame,step,time_h,node,x_mm,y_mm,z_mm,d1x,d1y,d1z,d3x,d3y,d3z,radius_mm\n";
  const std::string good = "0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n";
  const std::pair<std::string, std::string> cases[] = {
      {"0,0,0,0,nan,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n", ":2: x_mm: not a finite number (got nan)"},
      {"0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-inf,-0.3,,,,,,,\n", ":3: y_mm: not a finite number (got -inf)"},
      {good + "1,5,1e999,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n", ":4: time_h: expected a number (got \"1e999\")"},
      {"0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0x,0,0,1,0,-0.3,-0.3,,,,,,,\n", ":3: frame: expected an integer (got \"0x\")"},
      {"0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n", ":2: radius_mm: must be > 0 (got 0)"},
      {"0,0,0,0,0,0,0.1,,,,,,,\n", ":2: frame 0 has one node"},
  };
  for (const auto& [rows, expected] : cases) {
    { std::ofstream(d / "trajectory.csv") << head << rows; }
    std::string e = "(no error)";
    try {
      readTrajectory(d / "trajectory.csv");
    } catch (const SceneError& x) {
      e = x.what();
    }
    CHECK(e.find((d / "trajectory.csv").string() + expected) == 0);
  }
  { std::ofstream(d / "trajectory.csv") << head << good; }
  CHECK(readTrajectory(d / "trajectory.csv").size() == 1);
  fs::remove_all(d);
}

TEST_CASE("a trajectory with a huge coordinate or radius is refused naming file line frame and node") {
  const fs::path d = scratch("trajbound");
  const std::string head = "frame,step,time_h,node,x_mm,y_mm,z_mm,d1x,d1y,d1z,d3x,d3y,d3z,radius_mm\n";
  const std::string good = "0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n";
  const std::pair<std::string, std::string> cases[] = {
      {good + "1,5,1,0,0,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n1,5,1,1,0,-1e7,-0.3,,,,,,,\n",
       ":5: frame 1, node 1: y_mm = -1e+07 is outside -10000 .. 10000 mm (positions are bounded to |x|, |y|, |z| <= 10 m)"},
      {"0,0,0,0,10000.5,0,0.1,1,0,0,0,-0.6,-0.8,0.1\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n", ":2: frame 0, node 0: x_mm = 10000.5 is outside"},
      {"0,0,0,0,0,0,0.1,1,0,0,0,-0.6,-0.8,200\n0,0,0,1,0,-0.3,-0.3,,,,,,,\n",
       ":2: frame 0, node 0: radius_mm = 200 is above 100 mm (radii are bounded to 0.1 m)"},
  };
  for (const auto& c : cases) {
    // (not a structured binding: clang before 16 cannot capture one in CAPTURE's lambda)
    const std::string& rows = c.first;
    const std::string& expected = c.second;
    CAPTURE(expected);
    { std::ofstream(d / "trajectory.csv") << head << rows; }
    std::string e = "(no error)";
    try {
      readTrajectory(d / "trajectory.csv");
    } catch (const SceneError& x) {
      e = x.what();
    }
    CHECK(e.find((d / "trajectory.csv").string() + expected) == 0);
  }
  // at the bounds: accepted
  { std::ofstream(d / "trajectory.csv") << head << "0,0,0,0,-10000,0,0.1,1,0,0,0,-0.6,-0.8,100\n0,0,0,1,0,10000,-0.3,,,,,,,\n"; }
  CHECK(readTrajectory(d / "trajectory.csv").size() == 1);
  fs::remove_all(d);
}

TEST_CASE("a truncated or corrupt trajectory.bin is refused naming the file and the byte") {
  const fs::path d = scratch("badbin");
  const fs::path out = d / "r";
  runScene(out, "--set growth.steps=20 --set output.vtk=false --quiet");
  REQUIRE(fs::exists(out / "trajectory.bin"));
  CHECK(!fs::exists(out / "trajectory.csv"));
  // readTrajectory(run/trajectory.csv) reads the binary sibling (what callers written for the CSV do)
  CHECK(rootsim::readTrajectory(out / "trajectory.csv").size() == 3);
  const std::string good = slurp(out / "trajectory.bin");
  auto refused = [&](const std::string& bytes, const std::string& why) {
    CAPTURE(why);
    { std::ofstream(out / "trajectory.bin", std::ios::binary) << bytes; }
    std::string e;
    try {
      rootsim::readTrajectory(out / "trajectory.bin");
    } catch (const rootsim::SceneError& x) {
      e = x.what();
    }
    CHECK(e.find((out / "trajectory.bin").string() + ": byte ") == 0);
    CHECK(e.find(why) != std::string::npos);
  };
  refused(good.substr(0, good.size() - 5), "truncated");
  std::string nan = good;
  const double q = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan.data() + 16 + 24, &q, 8);  // the first x of the first frame
  refused(nan, "x_mm: not a finite number");
  refused(std::string("RSTRAJ01\x02\0\0\0\0\0\0\0", 16), "version");
  fs::remove_all(d);
}

TEST_CASE("a trajectory.bin with one huge finite coordinate is refused by render quickly (it grew past 4 GB)") {
  const fs::path d = scratch("hugebin");
  const fs::path out = d / "r";
  runScene(out, "--set growth.steps=20 --set output.vtk=false --quiet");
  std::string b = slurp(out / "trajectory.bin");
  const double huge = 1e7;  // mm
  std::memcpy(b.data() + 16 + 24 + 8, &huge, 8);  // y of node 0 of the first frame
  { std::ofstream(out / "trajectory.bin", std::ios::binary) << b; }
  const auto t0 = std::chrono::steady_clock::now();
  const Result r = run("render " + out.string() + " --final-png " + (d / "x.png").string() + " --quiet");
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(r.code == 2);
  CHECK(r.out.find((out / "trajectory.bin").string() + ": byte 48: frame 0, node 0: y_mm = 1e+07 is outside -10000 .. "
                                                      "10000 mm (positions are bounded to |x|, |y|, |z| <= 10 m)") !=
        std::string::npos);
  CHECK(s < 20);
  CHECK(!fs::exists(d / "x.png"));
  fs::remove_all(d);
}

TEST_CASE("trajectory.csv and trajectory.bin written by their writers read back as the snapshots, and a continued file replaces what followed") {
  const fs::path d = scratch("trajrt");
  rootsim::test::GrownRoot g;
  std::vector<Snapshot> snaps;
  snaps.push_back(makeSnapshot(g.m.rod, g.sim.state(), g.k, 8));
  snaps.back().timeH = 0.8;
  g.grow(3);
  snaps.push_back(makeSnapshot(g.m.rod, g.sim.state(), g.k, 11));
  snaps.back().timeH = 1.1;
  REQUIRE(snaps[1].elements() > 0);
  auto same = [](const Snapshot& a, const Snapshot& b, double tol) {
    CHECK(a.step == b.step);
    CHECK(a.timeH == b.timeH);
    REQUIRE(a.x.cols() == b.x.cols());
    REQUIRE(a.elements() == b.elements());
    CHECK((a.x - b.x).cwiseAbs().maxCoeff() <= tol * a.x.cwiseAbs().maxCoeff());
    CHECK((a.d1 - b.d1).cwiseAbs().maxCoeff() <= tol);
    CHECK((a.d3 - b.d3).cwiseAbs().maxCoeff() <= tol);
    CHECK((a.radius - b.radius).cwiseAbs().maxCoeff() <= tol * a.radius.maxCoeff());
  };
  {
    TrajectoryWriter csv(d / "trajectory.csv");
    TrajectoryBinaryWriter bin(d / "trajectory.bin");
    for (const Snapshot& s : snaps) {
      csv.add(s);
      bin.add(s);
    }
    CHECK(csv.frames() == 2);
    CHECK(bin.frames() == 2);
    csv.close();
    bin.close();
  }
  const std::vector<Snapshot> a = readTrajectory(d / "trajectory.csv"), b = readTrajectory(d / "trajectory.bin");
  REQUIRE(a.size() == 2);
  REQUIRE(b.size() == 2);
  for (size_t f = 0; f < 2; ++f) {
    CAPTURE(f);
    // millimetres and back: within a few ulps of the state
    same(snaps[f], a[f], 4e-16);
    // the two files hold the same doubles
    CHECK(a[f].x == b[f].x);
    CHECK(a[f].d1 == b[f].d1);
    CHECK(a[f].d3 == b[f].d3);
    CHECK(a[f].radius == b[f].radius);
  }
  // a killed run's file continued from its first frame (a checkpoint's position): the second frame is
  // replaced by what the resumed run writes
  std::uintmax_t csvBytes = 0, binBytes = 0;
  {
    TrajectoryWriter csv(d / "one.csv");
    TrajectoryBinaryWriter bin(d / "one.bin");
    csv.add(snaps[0]);
    bin.add(snaps[0]);
    csv.close();
    bin.close();
  }
  csvBytes = fs::file_size(d / "one.csv");
  binBytes = fs::file_size(d / "one.bin");
  // the first frame's bytes are those of the two-frame files
  CHECK(slurp(d / "trajectory.csv").substr(0, csvBytes) == slurp(d / "one.csv"));
  CHECK(slurp(d / "trajectory.bin").substr(0, binBytes) == slurp(d / "one.bin"));
  Snapshot other = snaps[1];
  other.step = 12;
  other.timeH = 1.2;
  {
    TrajectoryWriter csv(d / "trajectory.csv", csvBytes, 1);
    TrajectoryBinaryWriter bin(d / "trajectory.bin", binBytes, 1);
    csv.add(other);
    bin.add(other);
    CHECK(csv.frames() == 2);
    csv.close();
    bin.close();
  }
  for (const char* f : {"trajectory.csv", "trajectory.bin"}) {
    CAPTURE(f);
    const std::vector<Snapshot> t = readTrajectory(d / f);
    REQUIRE(t.size() == 2);
    same(snaps[0], t[0], 4e-16);
    same(other, t[1], 4e-16);
  }
  fs::remove_all(d);
}
