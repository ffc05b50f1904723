// checkpoints (src/io/checkpoint.cpp): every field through a round trip (a root's, a plate of one, and a
// plate's), corrupt, truncated, forged and older files refused.
// The field lists (include/rootsim/fields.hpp) through a checkpoint: a simulation of a coil in self-
// contact on a plate with friction, stepped, carried, written, read back into a fresh Simulation; every
// field of every persistent struct (the rod state with its friction stick points, the progress, the
// Newton solver's memory, the contact list, the run's accumulators and writer positions) compared by
// name through the same lists, before and after one more growth step of both. A scene of one root runs as
// a plate of one seedling (plateOfOne), and checkpoints so.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "rootsim/checkpoint.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "rod_fields_support.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace rootsim;

namespace {
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::slurp;
using rootsim::test::checkSameRun;
using rootsim::test::kScene;
using rootsim::test::kSets;
using rootsim::test::runKilled;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("checkpoint", name); }

// a root alone as a run steps it: a plate of one seedling
PlateSimulation plateOfOneRoot(const Model& m) { return PlateSimulation(PlateParams{}, plateOfOne(m).seedlings); }

// the checkpoint a run of one root would write of a after its current growth step
RunCheckpoint checkpointOf(const PlateSimulation& a, std::uint64_t sceneHash) {
  RunCheckpoint c;
  c.sceneHash = sceneHash;
  c.step = a.step();
  c.layout = RunLayout::OneRoot;
  c.plate = a.carry();
  c.roots.resize(1);
  return c;
}
const std::vector<std::string> kOneRoot = {""};  // a root alone: one seedling, no name

// the checkpoint of the 90-degree plate's root after one growth step of 0.2 h: a small state for the
// field checks
RunCheckpoint oneStepCheckpoint(std::uint64_t sceneHash) {
  const Scene sc = loadScene(std::string(ROOTSIM_SOURCE_DIR) + "/scenes/fig2a_alpha90.toml", {"growth.step_h=0.2"});
  PlateSimulation a = plateOfOneRoot(sc.model);
  a.growthStep();
  return checkpointOf(a, sceneHash);
}

// FNV-1a 64, the checkpoint's checksum (include/rootsim/checkpoint.hpp)
std::uint64_t fnv1a(const std::string& s, std::size_t from, std::size_t to) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = from; i < to; ++i) h = (h ^ static_cast<unsigned char>(s[i])) * 1099511628211ull;
  return h;
}
}  // namespace

TEST_CASE("every field of every persistent struct survives a checkpoint round trip (coil, self-contact, friction)") {
  const std::string src = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/";
  // the resume tests' coil (self-contact from growth step 30: the sparse Jacobian's memory), with friction
  const Scene sc = loadScene(src + "fig2a_alpha90.toml",
                             {"tropism.beta=1", "growth.step_h=0.2", "friction.enabled=true", "friction.mu_static=0.3",
                              "friction.mu_kinetic=0.2"});
  PlateSimulation a = plateOfOneRoot(sc.model);
  for (int i = 0; i < 36; ++i) a.growthStep();
  // the scene exercises what the lists carry
  REQUIRE(a.root(0).last().selfContacts > 0);
  const SimulationCarry ka = a.root(0).carry();
  REQUIRE(get<&NewtonWorkspace::sparseActive>(ka.newton));
  REQUIRE(get<&NewtonWorkspace::sparse>(ka.newton).n > 0);
  REQUIRE(!get<&ContactWorkspace::pairs>(ka.contact).empty());
  bool sticks = false;
  for (auto f : a.root(0).state().hasPlateStick) sticks = sticks || f != 0;
  REQUIRE(sticks);

  RunCheckpoint c = checkpointOf(a, 42);
  c.roots[0].watch.snapFirst = 1.5;
  c.roots[0].watch.maxSubsteps = 7;
  c.roots[0].watch.minSelfDistance = 0.25;
  c.roots[0].writers.timeseriesBytes = 123;
  c.roots[0].writers.vtkEntries = {{0.5, "vtk/step_000010.vtp"}};
  c.acc.wallBefore = 2.5;
  const fs::path dir = rootsim::test::scratchDir("checkpoint", "round_trip");
  fs::create_directories(dir);
  writeCheckpoint(dir / kCheckpointFile, c);
  const RunCheckpoint r = readCheckpoint(dir / kCheckpointFile, RunLayout::OneRoot, kOneRoot);
  // the file holds every field
  std::string d = checkpointDifference(c, r);
  CHECK_MESSAGE(d.empty(), "differs after the checkpoint: ", d);

  // a fresh plate of one from it carries the same again, and its root is the simulation a Simulation of
  // that state and carry is
  PlateSimulation b(PlateParams{}, plateOfOne(sc.model).seedlings, r.plate);
  Simulation alone(sc.model, r.plate.roots[0].state, r.plate.roots[0].carry);
  d = stateDifference(a.root(0).state(), b.root(0).state());
  CHECK_MESSAGE(d.empty(), "differs in the resumed state: ", d);
  d = carryDifference(ka, b.root(0).carry());
  CHECK_MESSAGE(d.empty(), "differs in the resumed simulation's carry: ", d);

  // and all go on bit for bit: a field that a list left out shows here, in what it changes
  for (int i = 0; i < 4; ++i) {
    a.growthStep();
    b.growthStep();
    alone.growthStep();
    d = stateDifference(a.root(0).state(), b.root(0).state());
    if (d.empty()) d = carryDifference(a.root(0).carry(), b.root(0).carry());
    if (d.empty()) d = stateDifference(a.root(0).state(), alone.state());
    if (d.empty()) d = carryDifference(a.root(0).carry(), alone.carry());
    CAPTURE(i);
    CHECK_MESSAGE(d.empty(), "differs after resuming and growing: ", d);
  }
  fs::remove_all(dir);
}

TEST_CASE("each field of the rod state's list reaches the checkpoint file and comes back from it") {
  const RunCheckpoint c = oneStepCheckpoint(7);
  const fs::path dir = scratch("each_rod_field");
  fs::create_directories(dir);
  writeCheckpoint(dir / kCheckpointFile, c);
  const std::string before = slurp(dir / kCheckpointFile);
  forEachRodField([&](auto index) {
    constexpr std::size_t I = decltype(index)::value;
    const std::string name = rootsim::test::rodField<I>().name;
    CAPTURE(name);
    // this field alone changed: the file changes, and reads back as the changed state, differing from
    // the first in this field
    RunCheckpoint changed = c;
    rootsim::test::perturbField<I>(changed.plate.roots[0].state, 0.5);
    writeCheckpoint(dir / kCheckpointFile, changed);
    CHECK(slurp(dir / kCheckpointFile) != before);
    const RunCheckpoint r = readCheckpoint(dir / kCheckpointFile, RunLayout::OneRoot, kOneRoot);
    CHECK(stateDifference(r.plate.roots[0].state, changed.plate.roots[0].state).empty());
    CHECK(stateDifference(r.plate.roots[0].state, c.plate.roots[0].state) == "state." + name);
    CHECK(checkpointDifference(r, changed).empty());
  });
  fs::remove_all(dir);
}

TEST_CASE("a checkpoint whose rod state arrays disagree on the element count is refused naming the field") {
  RunCheckpoint c = oneStepCheckpoint(0);
  c.plate.roots[0].state.hasObstacleStick.push_back(0);
  const fs::path dir = scratch("element_count");
  fs::create_directories(dir);
  writeCheckpoint(dir / kCheckpointFile, c);
  try {
    readCheckpoint(dir / kCheckpointFile, RunLayout::OneRoot, kOneRoot);
    FAIL("read a checkpoint whose arrays disagree");
  } catch (const SceneError& e) {
    const std::string what = e.what();
    CHECK(what.find("rod state fields disagree on the element count: hasObstacleStick does not fit") != std::string::npos);
    CHECK(what.find(kCheckpointFile) != std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("a corrupt or truncated checkpoint exits 2 naming it and --force discards it and starts again") {
  const fs::path d = scratch("corrupt");
  const std::string args = "run " + kScene + kSets + " --out ";
  REQUIRE(run(args + (d / "a").string()).code == 0);
  const fs::path ck = d / "b.partial" / "checkpoint.bin";
  CHECK(runKilled(args + (d / "b").string(), "40:45").code == 137);
  const std::string good = slurp(ck);
  REQUIRE(good.size() > 100);
  std::string flipped = good;
  flipped[good.size() / 2] = static_cast<char>(flipped[good.size() / 2] ^ 0x10);
  for (const std::string& bad : {good.substr(0, good.size() / 2), flipped, std::string("RSCHKPT"), std::string()}) {
    CAPTURE(bad.size());
    { std::ofstream(ck, std::ios::binary) << bad; }
    const Result r = run(args + (d / "b").string() + " --resume");
    CHECK(r.code == 2);
    CHECK(r.out.find(ck.string() + ": corrupt checkpoint") != std::string::npos);
    CHECK(r.out.find("--force") != std::string::npos);
    CHECK(fs::exists(ck));  // nothing discarded without --force
    CHECK(!fs::exists(d / "b"));
  }
  // a valid checkpoint, but a stream shorter than it says (the file was damaged): refused before
  // anything is touched
  { std::ofstream(ck, std::ios::binary) << good; }
  fs::resize_file(d / "b.partial" / "timeseries.csv.tmp", 100);
  const Result shortened = run(args + (d / "b").string() + " --resume");
  CHECK(shortened.code == 2);
  CHECK(shortened.out.find("timeseries.csv.tmp: missing or shorter") != std::string::npos);
  CHECK(fs::exists(ck));
  CHECK(!fs::exists(d / "b.incomplete"));
  const Result forced = run(args + (d / "b").string() + " --resume --force");
  REQUIRE_MESSAGE(forced.code == 0, forced.out);
  CHECK(forced.out.find("no usable checkpoint") != std::string::npos);
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("a forged checkpoint with a recomputed checksum and an impossible frame count is refused naming the field") {
  const fs::path d = scratch("forged");
  // no ParaView entries: the payload ends with the trajectory frame count (i32) and the entry count (u64)
  const std::string args = "run " + kScene + kSets + " --set output.vtk=false --out ";
  CHECK(runKilled(args + (d / "b").string(), "40:45").code == 137);
  const fs::path ck = d / "b.partial" / "checkpoint.bin";
  const std::string good = slurp(ck);
  REQUIRE(good.size() > 100);
  const std::size_t framesAt = good.size() - 8 - 8 - 4;
  std::int32_t frames = 0;
  std::memcpy(&frames, good.data() + framesAt, 4);
  REQUIRE(frames == 5);  // steps 0, 10, 20, 30, 40
  auto forged = [&](std::int32_t f) {
    std::string b = good;
    std::memcpy(b.data() + framesAt, &f, 4);
    const std::uint64_t sum = fnv1a(b, 40, b.size() - 8);
    std::memcpy(b.data() + b.size() - 8, &sum, 8);
    return b;
  };
  const std::pair<std::int32_t, std::string> cases[] = {
      {-5, "trajectory frame count -5 out of range (0 .. 41: at most one per growth step up to 40, and the initial one)"},
      {2000000000, "trajectory frame count 2000000000 out of range (0 .. 41"},
      {4, "trajectory frame count 4 disagrees with"},
  };
  for (const auto& c : cases) {
    // (not a structured binding: clang before 16 cannot capture one in CAPTURE's lambda)
    const std::int32_t f = c.first;
    const std::string& why = c.second;
    CAPTURE(f);
    { std::ofstream(ck, std::ios::binary) << forged(f); }
    const Result r = run(args + (d / "b").string() + " --resume");
    INFO(r.out);
    CHECK(r.code == 2);
    CHECK(r.out.find(ck.string() + ": corrupt checkpoint (" + why) != std::string::npos);
    CHECK(r.out.find("--force") != std::string::npos);
    CHECK(fs::exists(ck));
    CHECK(!fs::exists(d / "b"));
  }
  // the genuine one still resumes
  { std::ofstream(ck, std::ios::binary) << good; }
  const Result ok = run(args + (d / "b").string() + " --resume");
  CHECK_MESSAGE(ok.code == 0, ok.out);
  fs::remove_all(d);
}

TEST_CASE("an older rootsim's checkpoint is refused saying so (exit 2) and --force starts the run again") {
  // a single root's checkpoint of the version before a root ran as a plate of one had its own payload:
  // never misread as the plate's
  const fs::path d = scratch("older");
  const std::string args = "run " + kScene + kSets + " --out ";
  REQUIRE(run(args + (d / "a").string()).code == 0);
  CHECK(runKilled(args + (d / "b").string(), "40:45").code == 137);
  const fs::path ck = d / "b.partial" / "checkpoint.bin";
  std::string b = slurp(ck);
  REQUIRE(b.size() > 100);
  const std::uint32_t older = kCheckpointVersion - 1;
  std::memcpy(b.data() + 8, &older, 4);  // the header's version, after the magic
  { std::ofstream(ck, std::ios::binary) << b; }
  const Result r = run(args + (d / "b").string() + " --resume");
  INFO(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find("rootsim: error: " + ck.string() + ": checkpoint from an older rootsim (version " +
                   std::to_string(older)) != std::string::npos);
  CHECK(r.out.find("rerun with --force to discard it and start again") != std::string::npos);
  CHECK(fs::exists(ck));
  CHECK(!fs::exists(d / "b"));
  const Result forced = run(args + (d / "b").string() + " --resume --force");
  REQUIRE_MESSAGE(forced.code == 0, forced.out);
  checkSameRun(d / "a", d / "b");
  fs::remove_all(d);
}

TEST_CASE("every field of a plate's checkpoint survives a round trip and a plate's and a root's checkpoints refuse each other") {
  // two seedlings whose laterals (sides drawn from a seed) touch the other's from step ~130: at step 140
  // the carry holds laterals, pending sites, the sides' draws and the coupled system's memory
  const Scene sc = loadScene(std::string(ROOTSIM_SOURCE_DIR) + "/tests/data/plate/laterals_touching.toml", {});
  REQUIRE(sc.isPlate());
  PlateSimulation a(sc.plate.params, sc.plate.seedlings);
  int touching = 0;
  for (int i = 0; i < 140; ++i) touching = std::max(touching, a.growthStep().touchingPairs);
  REQUIRE(touching > 0);
  std::vector<std::string> names;
  for (const Seedling& sd : sc.plate.seedlings) names.push_back(sd.name);
  auto checkpointOf = [&](const PlateSimulation& p) {
    RunCheckpoint c;
    c.sceneHash = 42;
    c.step = p.step();
    c.plate = p.carry();
    c.roots.resize(static_cast<size_t>(p.size()));
    c.roots.back().watch.maxSubsteps = 3;
    c.acc = {2, 0.97, 1.5, 0};
    return c;
  };
  const RunCheckpoint c = checkpointOf(a);
  REQUIRE(c.plate.laterals.size() >= 8);
  REQUIRE(get<&CoupledWorkspace::sparse>(c.plate.coupled).n > 0);
  const fs::path dir = scratch("plate_round_trip");
  writeCheckpoint(dir / kCheckpointFile, c);
  const RunCheckpoint r = readCheckpoint(dir / kCheckpointFile, RunLayout::Plate, names);
  std::string d = checkpointDifference(c, r);
  CHECK_MESSAGE(d.empty(), "differs after the checkpoint: ", d);
  // a plate rebuilt from it carries the same again, and both go on bit for bit
  PlateSimulation b(sc.plate.params, sc.plate.seedlings, r.plate);
  d = checkpointDifference(c, checkpointOf(b));
  CHECK_MESSAGE(d.empty(), "differs in the resumed plate's carry: ", d);
  for (int i = 0; i < 10; ++i) {
    a.growthStep();
    b.growthStep();
  }
  d = checkpointDifference(checkpointOf(a), checkpointOf(b));
  CHECK_MESSAGE(d.empty(), "differs after resuming and growing: ", d);
  // a plate's checkpoint is no root's, and a root's no plate's
  try {
    readCheckpoint(dir / kCheckpointFile, RunLayout::OneRoot, kOneRoot);
    FAIL("a plate's checkpoint read as a root's");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()).find("corrupt checkpoint (a plate's checkpoint, this scene is one root") != std::string::npos);
  }
  writeCheckpoint(dir / "root.bin", ::checkpointOf(plateOfOneRoot(sc.plate.seedlings[0].model), 42));
  try {
    readCheckpoint(dir / "root.bin", RunLayout::Plate, names);
    FAIL("a root's checkpoint read as a plate's");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()).find("corrupt checkpoint (one root's checkpoint, this scene is a plate") != std::string::npos);
  }
  // a checkpoint of other seedlings: refused naming what does not fit
  try {
    readCheckpoint(dir / kCheckpointFile, RunLayout::Plate, {"a"});
    FAIL("a plate's checkpoint read for other seedlings");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()).find(" roots for 1 seedlings and ") != std::string::npos);
  }
  fs::remove_all(dir);
}
