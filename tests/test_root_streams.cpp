// The files one growing root streams (src/io/root_streams.cpp): a time-series row and a snapshot per
// output step read back as the simulation's, and a resumed root's files continued from the positions a
// checkpoint saw, what was written after them replaced.
#include <doctest/doctest.h>

#include <filesystem>
#include <limits>
#include <vector>

#include "root_streams.hpp"
#include "rootsim/csv.hpp"
#include "rootsim/model.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/trajectory.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;
using rootsim::test::coarseModel;
using rootsim::test::rootWriterOutputs;

namespace {
// a value written in mm and read back in m: two roundings of half an ulp each
constexpr double kUnitRounding = 2.0 * std::numeric_limits<double>::epsilon();
}  // namespace

TEST_CASE("root streams: each add writes a time-series row and a snapshot that read back as the simulation's") {
  const fs::path d = rootsim::test::scratchDir("root_streams", "streams");
  const Model m = coarseModel();
  Simulation sim(m);
  std::vector<Snapshot> seen;
  {
    detail::RootStreams streams(d, m, rootWriterOutputs(TrajectoryFormat::Both));
    streams.add(sim);
    seen.push_back(sim.snapshot());
    for (int k = 0; k < 3; ++k) {
      sim.growthStep();
      streams.add(sim);
      seen.push_back(sim.snapshot());
    }
    streams.close();
  }
  const CsvColumns ts = readCsvColumns(d / "timeseries.csv");
  REQUIRE(ts.names[0] == "step");
  CHECK(ts.values[0] == std::vector<double>{0, 1, 2, 3});
  const std::vector<Snapshot> bin = readTrajectory(d / "trajectory.bin");
  REQUIRE(bin.size() == 4);
  for (std::size_t k = 0; k < bin.size(); ++k) {
    CHECK(bin[k].step == seen[k].step);
    // trajectory.bin holds the positions in mm: one rounding there and one back
    CHECK((bin[k].x - seen[k].x).cwiseAbs().maxCoeff() <= kUnitRounding * seen[k].x.cwiseAbs().maxCoeff());
  }
  CHECK(readTrajectory(d / "trajectory.csv").size() == 4);
  CHECK_FALSE(fs::exists(d / "trajectory.pvd"));
  fs::remove_all(d);
}

TEST_CASE("root streams: a resumed root continues its files from the checkpoint's positions, what followed replaced") {
  const fs::path d = rootsim::test::scratchDir("root_streams", "resume");
  const Model m = coarseModel();
  Simulation sim(m);
  WriterPositions atCheckpoint;
  {
    detail::RootStreams streams(d, m, rootWriterOutputs(TrajectoryFormat::Both));
    streams.add(sim);
    sim.growthStep();
    streams.add(sim);
    atCheckpoint = streams.positions();
    sim.growthStep();
    streams.add(sim);  // written after the checkpoint: a resumed run writes it again
    streams.close();
  }
  CHECK(readTrajectory(d / "trajectory.bin").size() == 3);
  CHECK(atCheckpoint.trajectoryFrames == 2);
  Simulation again(m);
  again.growthStep();
  again.growthStep();
  again.growthStep();
  {
    detail::RootStreams resumed(d, m, rootWriterOutputs(TrajectoryFormat::Both), &atCheckpoint);
    resumed.add(again);
    resumed.close();
  }
  const CsvColumns ts = readCsvColumns(d / "timeseries.csv");
  CHECK(ts.values[0] == std::vector<double>{0, 1, 3});
  const std::vector<Snapshot> bin = readTrajectory(d / "trajectory.bin");
  REQUIRE(bin.size() == 3);
  CHECK(bin[2].step == 3);
  CHECK((bin[2].x - again.snapshot().x).cwiseAbs().maxCoeff() <= kUnitRounding * again.snapshot().x.cwiseAbs().maxCoeff());
  CHECK(readTrajectory(d / "trajectory.csv").size() == 3);
  fs::remove_all(d);
}
