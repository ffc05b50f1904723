// parameter sweeps (src/io/sweep.cpp): grids counted before they are expanded, short unique run names,
// escaped keys, the points reported and cancelled, resumed, the table of results, through the library
// and the binary
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
#include "rootsim/scene.hpp"
#include "rootsim/sweep.hpp"
#include "scene_support.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::slurp;
using rootsim::test::checkSameRun;
using rootsim::test::kCantilever;
using rootsim::test::kScene;
using rootsim::test::lines;
using rootsim::test::oneLine;
using rootsim::test::runKilled;
using rootsim::test::sweepError;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("sweep", name); }
}  // namespace

TEST_CASE("sweep grids are counted before they are expanded") {
  const fs::path d = scratch("grid");
  std::string axis = "[";
  for (int i = 0; i < 40; ++i) axis += (i ? ", " : "") + std::to_string(0.01 * (i + 1));
  axis += "]";
  {
    std::ofstream(d / "big.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/fig2b_waving.toml\"\n[grid]\n"
                                  << "\"tropism.beta\" = " << axis << "\n\"tropism.gamma\" = " << axis << "\n"
                                  << "\"plane.alpha_deg\" = " << axis << "\n\"growth.rate_per_h\" = " << axis << "\n";
  }
  const std::string e = sweepError(d / "big.toml");
  CHECK(e.find((d / "big.toml").string() + ":") == 0);
  CHECK(e.find(": the grid has more than 10000 points (the product of the grid arrays' lengths") != std::string::npos);
  // a key in [grid] and [set] would make every point the same
  {
    std::ofstream(d / "both.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/fig2b_waving.toml\"\n"
                                   << "[grid]\n\"tropism.beta\" = [0.1, 0.2]\n[set]\n\"tropism.beta\" = 0.3\n";
  }
  CHECK(sweepError(d / "both.toml").find(":6: set.tropism.beta is also a grid key") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("sweep run-directory names stay short and unique and deterministic") {
  const fs::path d = scratch("names");
  {
    std::ofstream(d / "long.toml")
        << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR << "/scenes/cantilever_tip_load.toml\"\n[grid]\n"
        << "\"load.tip_force_n\" = [[0.000012345678901234567, 0.000012345678901234567, -0.000012345678901234567],"
           " [0.000012345678901234568, 0.000012345678901234567, -0.000012345678901234567]]\n"
        << "\"load.tip_torque_nm\" = [[0.000000012345678901234567, 0.000000012345678901234567, 0.000000012345678901234567]]\n"
        << "\"root.youngs_modulus_mpa\" = [12.345678901234567]\n\"root.density_kg_per_m3\" = [1234.5678901234567]\n"
        << "\"solver.force_tol\" = [0.00012345678901234567]\n";
  }
  const SweepPlan a = loadSweep((d / "long.toml").string());
  const SweepPlan b = loadSweep((d / "long.toml").string());
  REQUIRE(a.points.size() == 2);
  std::set<std::string> names;
  for (size_t i = 0; i < a.points.size(); ++i) {
    CAPTURE(a.points[i].dirName);
    CHECK(a.points[i].dirName.size() <= 200);
    CHECK(a.points[i].dirName.rfind("run_000" + std::to_string(i) + "_tip_force_n=", 0) == 0);
    CHECK(a.points[i].dirName.find("_h") != std::string::npos);
    CHECK(a.points[i].dirName == b.points[i].dirName);
    names.insert(a.points[i].dirName);
  }
  CHECK(names.size() == 2);
  // short names are unchanged
  const SweepPlan s = loadSweep(std::string(ROOTSIM_SOURCE_DIR) + "/sweeps/fig3a_scaling.toml");
  CHECK(s.points[0].dirName == "run_0000_alpha_deg=20_beta=0.05");
  fs::remove_all(d);
}

TEST_CASE("sweep keys with control characters are escaped in messages") {
  const fs::path d = scratch("ctl");
  const std::string scene = std::string("[sweep]\nscene = \"") + ROOTSIM_SOURCE_DIR + "/scenes/fig2b_waving.toml\"\n";
  const std::pair<std::string, std::string> cases[] = {
      {scene + "[grid]\n\"tropism.be\\nta\" = [0.1]\n", "tropism.be\\nta"},
      {scene + "[set]\n\"tropism.be\\tta\" = 0.1\n", "tropism.be\\tta"},
      {scene + "[\"gr\\nid\"]\nx = 1\n", "[gr\\nid]"},
      {scene + "\"sc\\u0001ene\" = 1\n", "sweep.sc\\x01ene"},
      {scene + "[grid]\n\"tropism.be\\nta\" = 3\n", "grid.tropism.be\\nta must be a non-empty array"},
  };
  for (const auto& [text, shown] : cases) {
    { std::ofstream(d / "s.toml") << text; }
    const std::string e = sweepError(d / "s.toml");
    CAPTURE(e);
    CHECK(oneLine(e));
    CHECK(e.find(shown) != std::string::npos);
  }
  fs::remove_all(d);
}

TEST_CASE("a sweep reports every point through onPoint, skipped ones too, and stops when cancelled") {
  const fs::path d = scratch("sweep");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << kScene
                                << "\"\n[grid]\n\"plane.alpha_deg\" = [20, 40, 60]\n[set]\n\"growth.steps\" = 20\n";
  }
  const SweepPlan plan = loadSweep((d / "s.toml").string());
  std::mutex mu;
  std::vector<SweepPointDone> done;
  SweepOptions o;
  o.out = (d / "out").string();
  o.jobs = 2;
  o.onPoint = [&](const SweepPointDone& p) {
    std::lock_guard<std::mutex> lock(mu);
    done.push_back(p);
  };
  SweepResult r = runSweep(plan, o, nullptr);
  CHECK(r.ran == 3);
  CHECK(!r.interrupted);
  REQUIRE(done.size() == 3);
  std::set<int> indices;
  for (const auto& p : done) {
    indices.insert(p.point->index);
    CHECK(p.error.empty());
    CHECK(!p.skipped);
    CHECK(fs::is_regular_file(fs::path(p.dir) / "result.csv"));
  }
  CHECK(indices == std::set<int>{0, 1, 2});
  // again: every point complete, reported as skipped
  done.clear();
  r = runSweep(plan, o, nullptr);
  CHECK(r.skipped == 3);
  CHECK(done.size() == 3);
  for (const auto& p : done) CHECK(p.skipped);
  // cancelled before it starts: nothing runs, nothing is reported, the result says so
  done.clear();
  o.out = (d / "cancelled").string();
  o.cancelled = [] { return true; };
  r = runSweep(plan, o, nullptr);
  CHECK(r.interrupted);
  CHECK(r.ran == 0);
  CHECK(done.empty());
  // cancelled during a point: it stops between growth steps and stays DIR.partial
  done.clear();
  o.out = (d / "midway").string();
  o.jobs = 1;
  std::atomic<int> polls{0};
  o.cancelled = [&] { return ++polls > 5; };  // the check before the point, then four growth steps
  r = runSweep(plan, o, nullptr);
  CHECK(r.interrupted);
  CHECK(r.ran == 0);
  CHECK(r.failed == 0);
  CHECK(done.empty());
  CHECK(fs::is_directory(fs::path(o.out) / (plan.points[0].dirName + ".partial")));
  CHECK(!fs::exists(fs::path(o.out) / (plan.points[0].dirName + ".incomplete")));
  fs::remove_all(d);
}

TEST_CASE("an absurd sweep grid exits 2 before it is expanded") {
  const fs::path d = scratch("biggrid");
  std::string axis = "[";
  for (int i = 0; i < 40; ++i) axis += (i ? ", " : "") + std::to_string(40 + i);
  axis += "]";
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << kScene << "\"\n[grid]\n\"plane.alpha_deg\" = " << axis
                                << "\n\"root.radius_mm\" = " << axis << "\n\"tropism.beta\" = " << axis
                                << "\n\"tropism.gamma\" = " << axis << "\n";
  }
  const Result r = run("sweep " + (d / "s.toml").string() + " --quiet --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK(r.out.find("the grid has more than 10000 points") != std::string::npos);
  CHECK(lines(r.out) == 1);
  CHECK(!fs::exists(d / "out"));
  fs::remove_all(d);
}

TEST_CASE("a sweep whose run names would exceed 255 bytes runs with shortened names") {
  const fs::path d = scratch("longnames");
  {
    // two points; each name would be about 330 bytes
    std::ofstream(d / "s.toml")
        << "[sweep]\nscene = \"" << kCantilever << "\"\n[grid]\n"
        << "\"load.tip_force_n\" = [[0.000012345678901234567, 0.000012345678901234567, -0.000012345678901234567],"
           " [0.000022345678901234567, 0.000012345678901234567, -0.000012345678901234567]]\n"
        << "\"load.tip_torque_nm\" = [[0.000000012345678901234567, 0.000000012345678901234567, 0.000000012345678901234567]]\n"
        << "\"root.youngs_modulus_mpa\" = [12.345678901234567]\n\"solver.force_tol\" = [0.00012345678901234567]\n"
        << "[set]\n\"root.element_length_mm\" = 0.5\n\"output.vtk\" = false\n";
  }
  const Result r = run("sweep " + (d / "s.toml").string() + " -j 2 --out " + (d / "out").string());
  CAPTURE(r.out);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("2 ran, 0 already complete, 0 failed") != std::string::npos);
  int runs = 0;
  for (const auto& e : fs::directory_iterator(d / "out"))
    if (e.is_directory()) {
      ++runs;
      CHECK(e.path().filename().string().size() <= 200);
      CHECK(fs::exists(e.path() / "result.csv"));
    }
  CHECK(runs == 2);
  CHECK(lines(slurp(d / "out" / "table.csv")) == 3);
  fs::remove_all(d);
}

TEST_CASE("a sweep file key with a control character is printed escaped on one line") {
  const fs::path d = scratch("ctlsweep");
  { std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << kScene << "\"\n[grid]\n\"tropism.be\\nta\" = [0.1]\n"; }
  const Result r = run("sweep " + (d / "s.toml").string() + " --quiet --out " + (d / "out").string());
  CHECK(r.code == 2);
  CHECK(lines(r.out) == 1);
  CHECK(r.out.find("tropism.be\\nta") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("a killed sweep resumes its unfinished point from the checkpoint and matches an uninterrupted sweep") {
  const fs::path d = scratch("sweep");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << kScene << "\"\n[grid]\n\"tropism.beta\" = [0.1, 0.2]\n"
                                << "[set]\n\"growth.steps\" = 90\n\"output.checkpoint_every_s\" = 1e6\n";
  }
  const std::string cmd = "sweep " + (d / "s.toml").string() + " -j 1 --quiet --out ";
  REQUIRE(run(cmd + (d / "a").string()).code == 0);
  // the first point is killed at step 66 after a checkpoint at 52
  CHECK(runKilled(cmd + (d / "b").string(), "52:66").code == 137);
  std::vector<std::string> points, partials;
  for (const auto& e : fs::directory_iterator(d / "a"))
    if (e.is_directory()) points.push_back(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(d / "b"))
    if (e.path().extension() == ".partial") partials.push_back(e.path().filename().string());
  REQUIRE(points.size() == 2);
  REQUIRE(partials.size() == 1);
  CHECK(fs::exists(d / "b" / partials[0] / "checkpoint.bin"));
  const Result r = run("sweep " + (d / "s.toml").string() + " -j 1 --out " + (d / "b").string());
  REQUIRE_MESSAGE(r.code == 0, r.out);
  CHECK(r.out.find("2 ran") != std::string::npos);
  for (const std::string& p : points) {
    CAPTURE(p);
    checkSameRun(d / "a" / p, d / "b" / p);
  }
  // table.csv holds the wall time of each run: compare the rest
  auto table = [](const fs::path& f) {
    std::istringstream in(slurp(f));
    std::string line, out;
    std::getline(in, line);
    const auto col = [&] {
      int c = 0;
      std::istringstream h(line);
      std::string name;
      while (std::getline(h, name, ',')) {
        if (name == "wall_time_s") return c;
        ++c;
      }
      return -1;
    }();
    out += line + "\n";
    while (std::getline(in, line)) {
      std::istringstream row(line);
      std::string cell;
      for (int c = 0; std::getline(row, cell, ','); ++c) out += (c == col ? std::string("*") : cell) + ",";
      out += "\n";
    }
    return out;
  };
  CHECK(table(d / "a" / "table.csv") == table(d / "b" / "table.csv"));
  fs::remove_all(d);
}

TEST_CASE("a sweep over a mechanics-only scene resumes (its points count as complete)") {
  const fs::path d = scratch("mechsweep");
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << ROOTSIM_SOURCE_DIR
                                << "/scenes/cantilever_tip_load.toml\"\n[grid]\n\"root.youngs_modulus_mpa\" = [40, 50]\n"
                                   "[set]\n\"root.element_length_mm\" = 0.5\n\"output.vtk\" = false\n";
  }
  const std::string cmd = "sweep " + (d / "s.toml").string() + " --out " + (d / "out").string();
  const Result a = run(cmd);
  REQUIRE(a.code == 0);
  CHECK(a.out.find("2 ran, 0 already complete") != std::string::npos);
  const Result b = run(cmd);
  CHECK(b.code == 0);
  CHECK(b.out.find("0 ran, 2 already complete") != std::string::npos);
}

TEST_CASE("a small sweep: a failing point stays DIR.incomplete, the table holds the completed point's result row") {
  const fs::path d = scratch("states");
  // point 0 cannot relax in one sub-step (it fails at once); point 1 runs
  {
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << kScene << "\"\n[grid]\n\"solver.max_substeps\" = [1, 100000000]\n"
                                << "[set]\n\"growth.steps\" = 10\n\"root.element_length_mm\" = 0.1\n\"solver.kind\" = \"dynamic\"\n"
                                << "\"output.vtk\" = false\n";
  }
  const SweepPlan plan = loadSweep((d / "s.toml").string());
  REQUIRE(plan.points.size() == 2);
  REQUIRE(plan.gridKeys == std::vector<std::string>{"solver.max_substeps"});
  std::vector<SweepPointDone> done;
  std::mutex mu;
  SweepOptions o;
  o.out = (d / "out").string();
  o.quiet = true;
  o.onPoint = [&](const SweepPointDone& p) {
    std::lock_guard<std::mutex> lock(mu);
    done.push_back(p);
  };
  const SweepResult r = runSweep(plan, o, nullptr);
  CHECK(r.ran == 1);
  CHECK(r.failed == 1);
  CHECK(r.skipped == 0);
  REQUIRE(done.size() == 2);
  for (const auto& p : done) {
    CAPTURE(p.point->index);
    CHECK(p.error.empty() == (p.point->index == 1));
  }
  const fs::path failed = d / "out" / plan.points[0].dirName, ok = d / "out" / plan.points[1].dirName;
  CHECK(!fs::exists(failed));
  CHECK(!fs::exists(fs::path(failed.string() + ".partial")));
  CHECK(fs::is_regular_file(fs::path(failed.string() + ".incomplete") / "ERROR.txt"));
  CHECK(fs::is_regular_file(fs::path(failed.string() + ".incomplete") / kRunMarker));
  REQUIRE(fs::is_directory(ok));
  CHECK(whyNotWhole(ok) == "");
  // the point's scene.toml is the plan's resolved scene for it
  CHECK(slurp(ok / "scene.toml") == plan.points[1].resolvedToml);
  // table.csv: index, run, the grid value, then result.csv's own header and row, for the completed point only
  std::istringstream result(slurp(ok / "result.csv"));
  std::string resultHeader, resultRow;
  std::getline(result, resultHeader);
  std::getline(result, resultRow);
  REQUIRE(!resultRow.empty());
  CHECK(slurp(d / "out" / "table.csv") == "index,run,grid:solver.max_substeps," + resultHeader + "\n1," +
                                               plan.points[1].dirName + ",\"" + plan.points[1].grid[0].second + "\"," +
                                               resultRow + "\n");
  // again: the completed point is skipped, not run again
  done.clear();
  const SweepResult again = runSweep(plan, o, nullptr);
  CHECK(again.ran == 0);
  CHECK(again.skipped == 1);
  fs::remove_all(d);
}

TEST_CASE("a sweep of a plate scene: each point a plate, the table a row per root of each point, a rerun keeps them") {
  const fs::path d = scratch("plate");
  {
    std::ofstream(d / "plate.toml") << "[root]\nelement_length_mm = 0.1\n[growth]\nsteps = 20\nstep_h = 0.1\n[output]\nvtk = false\n"
                                       "[plate]\nwidth_mm = 30\nlength_mm = 20\n[[seedling]]\nname = \"a\"\nposition_mm = [10, 5]\n"
                                       "[[seedling]]\nname = \"b\"\ngenotype = \"tw\"\nposition_mm = [20, 5]\n"
                                       "set = { \"tropism.twist_r_tau\" = 0.4 }\n";
    std::ofstream(d / "s.toml") << "[sweep]\nscene = \"" << (d / "plate.toml").string() << "\"\n[grid]\n\"tropism.beta\" = [0.1, 0.3]\n";
  }
  const Result r = run("sweep " + (d / "s.toml").string() + " --quiet --out " + (d / "out").string());
  REQUIRE_MESSAGE(r.code == 0, r.out);
  const SweepPlan plan = loadSweep((d / "s.toml").string());
  REQUIRE(plan.points.size() == 2);
  const std::string table = slurp(d / "out" / "table.csv");
  INFO(table);
  std::istringstream in(table);
  std::string head;
  std::getline(in, head);
  CHECK(head.rfind("index,run,grid:tropism.beta,root,genotype,parent,", 0) == 0);
  // the point's plate.csv rows, each after the point's index, folder and grid value
  std::string want;
  for (const SweepPoint& p : plan.points) {
    const fs::path dir = d / "out" / p.dirName;
    REQUIRE(fs::is_regular_file(dir / "roots" / "a" / "result.csv"));
    CHECK(slurp(dir / "scene.toml") == p.resolvedToml);
    std::istringstream rows(slurp(dir / "plate.csv"));
    std::string row;
    std::getline(rows, row);
    CHECK(head.substr(head.find(",root,") + 1) == row);
    while (std::getline(rows, row)) want += std::to_string(p.index) + "," + p.dirName + ",\"" + p.grid[0].second + "\"," + row + "\n";
  }
  CHECK(table == head + "\n" + want);
  CHECK(lines(table) == 1 + 4);
  // run again: both points complete, nothing rerun
  const Result again = run("sweep " + (d / "s.toml").string() + " --out " + (d / "out").string());
  REQUIRE_MESSAGE(again.code == 0, again.out);
  CHECK(again.out.find("0 ran, 2 already complete") != std::string::npos);
  CHECK(slurp(d / "out" / "table.csv") == table);
}
