// One growing root's folder (src/io/root_outputs.cpp): what it writes when it finishes (its own folder
// marked whole, or the run directory left to RunDir), and a root resumed with the watch and the stream
// positions its checkpoint saw, the leftovers of interrupted atomic writes removed.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "root_outputs.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/model.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/simulation.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;
using rootsim::test::coarseModel;
using rootsim::test::rootWriterOutputs;
using detail::RootOutputs;
using rootsim::test::slurp;

TEST_CASE("root outputs: a finished root writes shape, summary and result, and marks its own folder whole") {
  const fs::path d = rootsim::test::scratchDir("root_outputs", "finish");
  const Model m = coarseModel(4);
  for (const bool own : {true, false}) {
    CAPTURE(own);
    const fs::path dir = d / (own ? "own" : "run");
    fs::create_directories(dir);
    Simulation sim(m);
    RootOutputs root(dir, m, rootWriterOutputs(), own, Vec3::Zero());
    CHECK(root.dir() == dir);
    root.add(sim);
    root.start(sim.last());
    for (int k = 1; k <= m.growth.steps; ++k) {
      root.see(sim.growthStep());
      root.add(sim);
    }
    root.close();
    const RootOutputs::Final f = root.finish(m, sim, 1.5);
    CHECK(slurp(dir / "shape.csv") == f.shape);
    CHECK(slurp(dir / "summary.json") == f.summary);
    CHECK(slurp(dir / "result.csv") == f.result);
    CHECK(f.summary.find("\"steps\": 4") != std::string::npos);
    CHECK(f.summary.find("\"wall_time_s\": 1.5") != std::string::npos);
    CHECK(f.summary.find("\"max_substeps_per_step\": " + std::to_string(root.watch().maxSubsteps)) != std::string::npos);
    CHECK(readCsvColumns(dir / "timeseries.csv").values[0] == std::vector<double>{0, 1, 2, 3, 4});
    if (own) {
      CHECK(whyNotWhole(dir) == "");
    } else {
      CHECK_FALSE(fs::exists(dir / kRunMarker));  // the run directory's marker is RunDir's
    }
  }
  fs::remove_all(d);
}

TEST_CASE("root outputs: a resumed root keeps its checkpoint's watch and streams, and drops other interrupted writes") {
  const fs::path d = rootsim::test::scratchDir("root_outputs", "resume");
  const Model m = coarseModel(4);
  Simulation sim(m);
  PlateRootRun seen;
  {
    RootOutputs root(d, m, rootWriterOutputs(), false, Vec3::Zero());
    root.add(sim);
    root.start(sim.last());
    root.see(sim.growthStep());
    root.add(sim);
    seen = root.checkpointed();
    CHECK(seen.writers.timeseriesBytes > 0);
    root.see(sim.growthStep());
    root.add(sim);  // after the checkpoint: written again when resumed
    // killed here: the streams stay temporary files as they are (a writer destroyed unclosed removes its
    // own), and an atomic write was cut short
    for (const char* f : {"timeseries.csv.tmp", "trajectory.bin.tmp"}) fs::copy_file(d / f, d / (std::string(f) + ".killed"));
  }
  for (const char* f : {"timeseries.csv.tmp", "trajectory.bin.tmp"}) fs::rename(d / (std::string(f) + ".killed"), d / f);
  std::ofstream(d / "shape.csv.tmp") << "half";
  RootOutputs resumed(d, m, rootWriterOutputs(), false, Vec3::Zero(), &seen);
  CHECK_FALSE(fs::exists(d / "shape.csv.tmp"));
  CHECK(resumed.watch().maxSubsteps == seen.watch.maxSubsteps);
  CHECK(resumed.watch().prevTime == seen.watch.prevTime);
  CHECK(resumed.checkpointed().writers.timeseriesBytes == seen.writers.timeseriesBytes);
  resumed.add(sim);
  resumed.close();
  CHECK(readCsvColumns(d / "timeseries.csv").values[0] == std::vector<double>{0, 1, 2});
  fs::remove_all(d);
}
