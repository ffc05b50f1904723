// `rootsim export` (src/app/export_run.cpp, docs/rsml.md) end to end: a short real run exported to RSML
// and read back by rootsim's reader, compared with the run's own files; --at-h, --every-h, the write
// rule, bad flags and bad run directories
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <map>
#include <vector>

#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/rsml.hpp"
#include "rootsim/trajectory.hpp"
#include <nlohmann/json.hpp>
#include "test_support.hpp"

using rootsim::test::kRoundoff;

namespace fs = std::filesystem;
using namespace rootsim;
using rootsim::test::run;
using rootsim::test::slurp;
using rootsim::test::Result;

namespace {

fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("export", name); }

// one short fig2b run (200 growth steps of 0.05 h, a snapshot every 10: 0, 0.5, ..., 10 h), made once
const fs::path& shortRun() {
  static const fs::path dir = [] {
    const fs::path d = scratch("run") / "wave";
    const auto r = run("run " + test::kScene + " --set growth.steps=200 --out " + d.string() + " --quiet");
    REQUIRE(r.code == 0);
    return d;
  }();
  return dir;
}

// the binary was built without the app library: export says so (exit 2); the case is skipped
bool exportBuilt() {
  const auto r = run("export " + shortRun().string() + " --rsml /nonexistent-folder/x.rsml");
  if (r.out.find("built without") != std::string::npos) {
    test::skipCase("rootsim built without the renderer: no export command");
    return false;
  }
  return true;
}

std::vector<double> column(const CsvColumns& c, const std::string& name) {
  for (std::size_t i = 0; i < c.names.size(); ++i)
    if (c.names[i] == name) return c.values[i];
  FAIL("no column " << name);
  return {};
}

}  // namespace

TEST_CASE("export --rsml: the final root in plate coordinates / its functions and the observables of the run") {
  if (!exportBuilt()) return;
  const fs::path out = scratch("final") / "wave.rsml";
  const auto r = run("export " + shortRun().string() + " --rsml " + out.string());
  REQUIRE(r.code == 0);
  CHECK(r.out.find("wrote " + out.string()) != std::string::npos);
  const std::string bytes = slurp(out);
  CHECK(bytes.find("rootsim-output") != std::string::npos);   // the signature: --force may replace it
  const rsml::Document d = rsml::readRsml(out);
  CHECK(d.meta.version == "1");
  CHECK(d.meta.unit == "mm");
  CHECK(d.meta.resolution == 1);
  CHECK(d.meta.software == "rootsim");
  CHECK(d.meta.lastModified == "1970-01-01T00:00:00");
  CHECK(d.meta.fileKey.rfind("wave-", 0) == 0);
  CHECK(d.hasTime);
  CHECK(d.timeH == 10);
  CHECK(d.sceneProperty("step")->number == 200);
  CHECK(d.sceneProperty("plane.alpha_deg")->number == 40);
  CHECK(d.sceneProperty("growth.steps")->number == 200);
  REQUIRE(d.plants.size() == 1);
  REQUIRE(d.plants[0].roots.size() == 1);
  const rsml::Root& root = d.plants[0].roots[0];
  CHECK(root.hasZ);

  // every point is shape.csv's lateral_mm, downhill_mm, height_mm (the final state) to 1e-9 mm
  const CsvColumns shape = readCsvColumns(shortRun() / "shape.csv");
  const std::vector<double> lat = column(shape, "lateral_mm"), down = column(shape, "downhill_mm"),
                            h = column(shape, "height_mm"), radius = column(shape, "radius_mm");
  REQUIRE(root.points() == lat.size());
  double worst = 0;
  for (std::size_t i = 0; i < lat.size(); ++i)
    worst = std::max({worst, std::fabs(root.x[i] - lat[i]), std::fabs(root.y[i] - down[i]), std::fabs(root.z[i] - h[i])});
  CHECK(worst < 1e-9);
  // origin at the seed: node 0 on the plate's origin, one radius above it; the root grows downhill (+y)
  CHECK(std::fabs(root.x[0]) < 1e-12);
  CHECK(std::fabs(root.y[0]) < 1e-12);
  ROOTSIM_CHECK_CLOSE(root.z[0], 0.1, kRoundoff);
  CHECK(root.y.back() > 2.0);

  // diameter: 2 R / sqrt(stretch) at the nodes, as shape.csv's radius (of the mean stretch) to 1e-6
  REQUIRE(root.diameterMm.size() == lat.size());
  for (std::size_t i = 0; i < lat.size(); ++i) CHECK(root.diameterMm[i] == doctest::Approx(2 * radius[i]).epsilon(1e-6));
  // curvature: 0 at the ends, the waving root's bends inside, within 25 % of the frame's |kappa_1,2| where
  // it bends most (the centreline and the directors differ by the shear)
  const rsml::Function* k = root.function("curvature");
  REQUIRE(k != nullptr);
  CHECK(k->samples.front() == 0);
  CHECK(k->samples.back() == 0);
  const std::vector<double> k1 = column(shape, "kappa1_per_mm"), k2 = column(shape, "kappa2_per_mm");
  double kmax = 0, framemax = 0;
  for (std::size_t i = 0; i < k1.size(); ++i) {
    kmax = std::max(kmax, k->samples[i]);
    framemax = std::max(framemax, std::hypot(k1[i], k2[i]));
  }
  CHECK(kmax > 0.3);
  CHECK(kmax == doctest::Approx(framemax).epsilon(0.25));
  // frame_angle: d1 starts in the plate (0 deg); no intrinsic twist here, so it stays within a few degrees
  // of the plate at the glued base
  const rsml::Function* phi = root.function("frame_angle");
  REQUIRE(phi != nullptr);
  CHECK(std::fabs(phi->samples.front()) < 30);
  // age: the base has been mature since the start (10 h), the growth zone (the last 1 mm) is 0, and it
  // never increases toward the tip
  const rsml::Function* age = root.function("age");
  REQUIRE(age != nullptr);
  ROOTSIM_CHECK_CLOSE(age->samples.front(), 10.0, kRoundoff);
  CHECK(age->samples.back() == 0);
  for (std::size_t i = 1; i < age->samples.size(); ++i) CHECK(age->samples[i] <= age->samples[i - 1] + 1e-12);
  CHECK(std::count(age->samples.begin(), age->samples.end(), 0.0) > 5);
  // the run's observables, with their units defined
  const std::string result = slurp(shortRun() / "result.csv");
  REQUIRE(root.property("pattern") != nullptr);
  CHECK(result.find("," + root.property("pattern")->text + ",") != std::string::npos);
  CHECK(root.property("length_mm")->number == doctest::Approx(3.1).epsilon(1e-9));   // 1.1 mm + 200 x 0.01 mm
  CHECK(root.property("alpha_deg")->number == 40);
  bool wavelengthUnit = false;
  for (const auto& def : d.meta.definitions) wavelengthUnit = wavelengthUnit || (def.label == "theta_tip_deg" && def.unit == "deg");
  CHECK(wavelengthUnit);

  // same run, same bytes
  const fs::path again = out.parent_path() / "again.rsml";
  REQUIRE(run("export " + shortRun().string() + " --rsml " + again.string() + " --quiet").code == 0);
  CHECK(slurp(again) == bytes);
}

TEST_CASE("export --at-h: the snapshot nearest H / ties to the earlier / outside the run exit 2 writing nothing") {
  if (!exportBuilt()) return;
  const fs::path dir = scratch("at");
  REQUIRE(run("export " + shortRun().string() + " --rsml " + (dir / "a.rsml").string() + " --at-h 2.25 --quiet").code == 0);
  const rsml::Document d = rsml::readRsml(dir / "a.rsml");
  CHECK(d.sceneProperty("time_h")->number == 2.0);   // 2.0 and 2.5 are as near: the earlier
  CHECK(d.sceneProperty("step")->number == 40);
  REQUIRE(run("export " + shortRun().string() + " --rsml " + (dir / "b.rsml").string() + " --at-h 2.26 --quiet").code == 0);
  CHECK(rsml::readRsml(dir / "b.rsml").sceneProperty("time_h")->number == 2.5);
  // the root at that time: 1.1 mm + 40 (50) growth steps of 0.01 mm
  CHECK(rsml::readRsml(dir / "a.rsml").plants[0].roots[0].property("length_mm")->number == doctest::Approx(1.5).epsilon(1e-9));
  CHECK(rsml::readRsml(dir / "b.rsml").plants[0].roots[0].property("length_mm")->number == doctest::Approx(1.6).epsilon(1e-9));
  for (const char* at : {"10.5", "-1"}) {
    const auto r = run("export " + shortRun().string() + " --rsml " + (dir / "c.rsml").string() + " --at-h " + at);
    CHECK(r.code == 2);
    CHECK(r.out.find("--at-h") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "c.rsml"));
  }
  CHECK(run("export " + shortRun().string() + " --rsml " + (dir / "c.rsml").string() + " --at-h 10.5").out.find("0 .. 10 h") !=
        std::string::npos);
}

TEST_CASE("export --every-h: one file per time / named by it / each a time-sequence entry") {
  if (!exportBuilt()) return;
  const fs::path dir = scratch("every");
  const auto r = run("export " + shortRun().string() + " --rsml " + (dir / "s.rsml").string() + " --every-h 2.5");
  REQUIRE(r.code == 0);
  const std::vector<std::string> names = {"s_t000.00h.rsml", "s_t002.50h.rsml", "s_t005.00h.rsml", "s_t007.50h.rsml",
                                          "s_t010.00h.rsml"};
  std::vector<std::string> have;
  for (const auto& e : fs::directory_iterator(dir)) have.push_back(e.path().filename().string());
  std::sort(have.begin(), have.end());
  CHECK(have == names);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const rsml::Document d = rsml::readRsml(dir / names[k]);
    CHECK(d.sceneProperty("time_h")->number == 2.5 * static_cast<double>(k));
    CHECK(d.meta.sequenceIndex == static_cast<int>(k));
    CHECK(d.meta.unified);
    CHECK(d.meta.sequenceLabel.rfind("wave-", 0) == 0);
  }
  // finer than the snapshots: two times would be one file's snapshot
  const auto fine = run("export " + shortRun().string() + " --rsml " + (dir / "f.rsml").string() + " --every-h 0.2");
  CHECK(fine.code == 2);
  CHECK(fine.out.find("shorter than the run's snapshot spacing") != std::string::npos);
  // again: every file is rootsim's, replaced only with --force
  CHECK(run("export " + shortRun().string() + " --rsml " + (dir / "s.rsml").string() + " --every-h 2.5").code == 2);
  CHECK(run("export " + shortRun().string() + " --rsml " + (dir / "s.rsml").string() + " --every-h 2.5 --force --quiet").code == 0);
  // a user's file among the series' names stops it before anything is written
  { std::ofstream(dir / "u_t005.00h.rsml") << "mine"; }
  const auto mine = run("export " + shortRun().string() + " --rsml " + (dir / "u.rsml").string() + " --every-h 2.5 --force");
  CHECK(mine.code == 2);
  CHECK(mine.out.find("was not written by rootsim") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "u_t000.00h.rsml"));
  CHECK(slurp(dir / "u_t005.00h.rsml") == "mine");
}

TEST_CASE("export: the write rule and bad flags") {
  if (!exportBuilt()) return;
  const fs::path dir = scratch("rule");
  const std::string runDir = shortRun().string();
  // a user's file is refused with and without --force, and left as it was
  { std::ofstream(dir / "mine.rsml") << "my file"; }
  for (const char* force : {"", " --force"}) {
    const auto r = run("export " + runDir + " --rsml " + (dir / "mine.rsml").string() + force);
    CHECK(r.code == 2);
    CHECK(r.out.find("was not written by rootsim") != std::string::npos);
    CHECK(slurp(dir / "mine.rsml") == "my file");
  }
  // rootsim's own: replaced only with --force
  const fs::path own = dir / "own.rsml";
  REQUIRE(run("export " + runDir + " --rsml " + own.string() + " --quiet").code == 0);
  const auto again = run("export " + runDir + " --rsml " + own.string() + " --at-h 1");
  CHECK(again.code == 2);
  CHECK(again.out.find("pass --force") != std::string::npos);
  CHECK(rsml::readRsml(own).sceneProperty("time_h")->number == 10);
  REQUIRE(run("export " + runDir + " --rsml " + own.string() + " --at-h 1 --force --quiet").code == 0);
  CHECK(rsml::readRsml(own).sceneProperty("time_h")->number == 1);
  // never into the run directory being read
  const auto inside = run("export " + runDir + " --rsml " + (shortRun() / "x.rsml").string());
  CHECK(inside.code == 2);
  CHECK_FALSE(fs::exists(shortRun() / "x.rsml"));
  // bad flags: one line, exit 2, nothing written
  struct Bad {
    std::string args, says;
  };
  const std::vector<Bad> bad = {
      {runDir, "no output asked for"},
      {runDir + " --rsml " + (dir / "n.rsml").string() + " --at-h 1 --every-h 2", "give --at-h or --every-h, not both"},
      {runDir + " --rsml " + (dir / "n.rsml").string() + " --every-h 0", "--every-h 0: expected a finite number in (0, 1e+06] h"},
      {runDir + " --rsml " + (dir / "n.rsml").string() + " --at-h nan", "--at-h nan: expected a finite number in [0, 1e+06] h"},
      {runDir + " --rsml " + (dir / "n.rsml").string() + " --every-h 1e-9", "--every-h 1e-09: a series over the run's"},
      {runDir + " --rsml " + (dir / "no-such-folder" / "n.rsml").string(), "not found"},
      {runDir + " --rsml ''", "empty value"},
      {(dir / "no-run").string() + " --rsml " + (dir / "n.rsml").string(), "run directory not found"},
      {dir.string() + " --rsml " + (dir / "n.rsml").string(), "scene.toml: not found"},
  };
  for (const Bad& b : bad) {
    CAPTURE(b.args);
    const auto r = run("export " + b.args);
    CHECK(r.code == 2);
    CHECK(r.out.find(b.says) != std::string::npos);
    CHECK(test::lines(r.out) == 1);
    CHECK_FALSE(fs::exists(dir / "n.rsml"));
  }
}

TEST_CASE("export: a run directory without its trajectory exits 2 naming the file") {
  if (!exportBuilt()) return;
  const fs::path dir = scratch("notraj");
  const fs::path copy = dir / "run";
  fs::create_directories(copy);
  for (const char* f : {"scene.toml", "timeseries.csv", "result.csv"}) fs::copy_file(shortRun() / f, copy / f);
  const auto r = run("export " + copy.string() + " --rsml " + (dir / "x.rsml").string());
  CHECK(r.code == 2);
  CHECK(r.out.find("trajectory") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "x.rsml"));
}

TEST_CASE("export: an --every-h RSML series is written all or none and a FILE.tmp in its way is refused untouched") {
  const fs::path dir = test::scratchDir("export", "series_all_or_none");
  const std::string runDir = shortRun().string();
  const fs::path rsml = dir / "s.rsml";
  REQUIRE(run("export " + runDir + " --rsml " + rsml.string() + " --every-h 5 --quiet").code == 0);
  const std::map<std::string, std::string> before = test::fileTree(dir);
  REQUIRE(before.size() > 2);
  std::vector<std::string> names;
  for (const auto& [name, bytes] : before) names.push_back(name);
  // the user's own FILE.tmp is in the way: refused before anything is written, and kept
  fs::create_directories(dir / (names[1] + ".tmp"));
  const auto r = run("export " + runDir + " --rsml " + rsml.string() + " --every-h 5 --force");
  CHECK(r.code == 2);
  CHECK(r.out.find(".tmp is in the way") != std::string::npos);
  CHECK(fs::is_directory(dir / (names[1] + ".tmp")));
  fs::remove(dir / (names[1] + ".tmp"));
  CHECK(test::fileTree(dir) == before);
}

namespace {
// a plate of two seedlings whose laterals emerge within a short run (60 growth steps, a snapshot every 20)
const fs::path& plateRun() {
  static const fs::path dir = [] {
    const fs::path d = scratch("plate");
    {
      std::ofstream f(d / "plate.toml");
      f << "[root]\nradius_mm = 0.1\ninitial_length_mm = 1.1\n[growth]\nsteps = 60\n[tropism]\nbeta = 0.2\n[plane]\n"
           "alpha_deg = 40\n[output]\nevery_steps = 20\nvtk = false\n[plate]\nwidth_mm = 60\nlength_mm = 40\n"
           "[laterals]\nenabled = true\nfirst_mm = 0.5\nspacing_mm = 0.5\napical_unbranched_mm = 0.5\n"
           "[[seedling]]\nname = \"a\"\nposition_mm = [20, 5]\n[[seedling]]\nname = \"b\"\nposition_mm = [40, 5]\n";
    }
    const auto r = run("run " + (d / "plate.toml").string() + " --out " + (d / "run").string() + " --quiet");
    REQUIRE_MESSAGE(r.code == 0, r.out);
    return d / "run";
  }();
  return dir;
}

// the JSON chunk of a GLB file
nlohmann::json glbJson(const fs::path& f) {
  const std::string b = slurp(f);
  REQUIRE(b.size() > 20);
  REQUIRE(b.compare(0, 4, "glTF") == 0);
  const std::uint32_t n = static_cast<unsigned char>(b[12]) | static_cast<unsigned char>(b[13]) << 8 |
                          static_cast<unsigned char>(b[14]) << 16 | static_cast<std::uint32_t>(static_cast<unsigned char>(b[15])) << 24;
  return nlohmann::json::parse(b.substr(20, n));
}
}  // namespace

TEST_CASE("export of a plate's run: --gltf one group per root named after it, each lateral from its emergence frame") {
  if (!exportBuilt()) return;
  const fs::path d = scratch("plate_gltf");
  const fs::path& rd = plateRun();
  // the plate's roots: the seedlings, then the laterals (plate.csv), each with its snapshot count
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(rd / "roots")) names.push_back(e.path().filename().string());
  REQUIRE(names.size() > 2);  // laterals emerged
  const Result r = run("export " + rd.string() + " --gltf " + (d / "plate.glb").string() + " --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  const nlohmann::json j = glbJson(d / "plate.glb");
  auto node = [&](const std::string& name) -> const nlohmann::json* {
    for (const auto& n : j["nodes"])
      if (n.value("name", "") == name) return &n;
    return nullptr;
  };
  const int frames = 4;  // steps 0, 20, 40, 60
  int shownAtEnd = 0;
  for (const std::string& n : names) {
    const nlohmann::json* g = node(n);
    REQUIRE_MESSAGE(g, "no group node " << n);
    const auto snaps = readTrajectory(rd / "roots" / n / "trajectory.bin");
    REQUIRE((*g)["children"].size() == snaps.size());
    // its k-th snapshot is the plate's frame frames - size + k, named after the root
    for (std::size_t k = 0; k < snaps.size(); ++k) {
      const auto& child = j["nodes"][(*g)["children"][k].get<std::size_t>()];
      const std::string name = child["name"];
      char want[32];
      std::snprintf(want, sizeof want, " frame %04d,", frames - static_cast<int>(snaps.size()) + static_cast<int>(k));
      CHECK(name.rfind(n + want, 0) == 0);
      CHECK(child["extras"]["time_h"].get<double>() == snaps[k].timeH);
      CHECK(child["extras"]["step"].get<int>() == snaps[k].step);
      if (child["scale"][0].get<double>() == 1.0) ++shownAtEnd;
    }
  }
  CHECK(shownAtEnd == static_cast<int>(names.size()));  // a viewer without the animation: every root's last
  // one channel per snapshot of every root; the plate quad covers the whole 60 x 40 mm plate
  std::size_t total = 0;
  for (const std::string& n : names) total += (*node(n))["children"].size();
  CHECK(j["animations"][0]["channels"].size() == total);
  const auto& plateMesh = j["meshes"][(*node("plate"))["mesh"].get<std::size_t>()];
  const auto& pa = j["accessors"][plateMesh["primitives"][0]["attributes"]["POSITION"].get<std::size_t>()];
  CHECK(pa["min"][0].get<double>() <= -1e-3);
  CHECK(pa["max"][0].get<double>() >= 61e-3 - 1e-9);
  CHECK(pa["max"][2].get<double>() >= 41e-3 - 1e-9);  // glTF z = downhill
}

TEST_CASE("export of a plate's run: --paraview a .pvd per root, a lateral's listing empty.vtp before it emerged") {
  if (!exportBuilt()) return;
  const fs::path d = scratch("plate_paraview");
  const fs::path& rd = plateRun();
  const Result r = run("export " + rd.string() + " --paraview " + (d / "pv").string() + " --quiet");
  REQUIRE_MESSAGE(r.code == 0, r.out);
  const fs::path pv = d / "pv";
  CHECK(fs::is_regular_file(pv / "plate.vtp"));
  const std::string script = slurp(pv / "open_in_paraview.py");
  bool lateral = false;
  for (const auto& e : fs::directory_iterator(rd / "roots")) {
    const std::string n = e.path().filename().string();
    const auto snaps = readTrajectory(e.path() / "trajectory.bin");
    const std::string pvd = slurp(pv / (n + ".pvd"));
    INFO(n << ": " << pvd);
    // every plate snapshot listed once; before the root's first, the empty file
    std::size_t entries = 0, empties = 0;
    for (std::size_t at = pvd.find("<DataSet"); at != std::string::npos; at = pvd.find("<DataSet", at + 1)) ++entries;
    for (std::size_t at = pvd.find("empty.vtp"); at != std::string::npos; at = pvd.find("empty.vtp", at + 1)) ++empties;
    CHECK(entries == 4);
    CHECK(empties == 4 - snaps.size());
    lateral = lateral || empties > 0;
    for (const Snapshot& s : snaps) {
      char f[64];
      std::snprintf(f, sizeof f, "/step_%06d.vtp", s.step);
      CHECK(fs::is_regular_file(pv / (n + f)));
      CHECK(pvd.find(n + f) != std::string::npos);
    }
    CHECK(script.find("(\"" + n + "\", \"" + n + ".pvd\")") != std::string::npos);
  }
  CHECK(lateral);
  CHECK(fs::is_regular_file(pv / "empty.vtp"));
  CHECK(slurp(pv / "empty.vtp").find("NumberOfPoints=\"0\"") != std::string::npos);
}
