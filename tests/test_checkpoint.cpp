// The field lists (include/rootsim/fields.hpp) through a checkpoint: a simulation of a coil in self-
// contact on a plate with friction, stepped, carried, written, read back into a fresh Simulation; every
// field of every persistent struct (the rod state with its friction stick points, the progress, the
// Newton solver's memory, the contact list, the run's accumulators and writer positions) compared by
// name through the same lists, before and after one more growth step of both.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "rootsim/checkpoint.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/simulation.hpp"
#include "test_files.hpp"

namespace fs = std::filesystem;
using namespace rootsim;

TEST_CASE("every field of every persistent struct survives a checkpoint round trip (coil, self-contact, friction)") {
  const std::string src = std::string(ROOTSIM_SOURCE_DIR) + "/scenes/";
  // the resume tests' coil (self-contact from growth step 30: the sparse Jacobian's memory), with friction
  const Scene sc = loadScene(src + "fig2a_alpha90.toml",
                             {"tropism.beta=1", "growth.step_h=0.2", "friction.enabled=true", "friction.mu_static=0.3",
                              "friction.mu_kinetic=0.2"});
  Simulation a(sc.model);
  for (int i = 0; i < 36; ++i) a.growthStep();
  // the scene exercises what the lists carry
  REQUIRE(a.last().selfContacts > 0);
  const SimulationCarry ka = a.carry();
  REQUIRE(get<&NewtonWorkspace::sparseActive>(ka.newton));
  REQUIRE(get<&NewtonWorkspace::sparse>(ka.newton).n > 0);
  REQUIRE(!get<&ContactWorkspace::pairs>(ka.contact).empty());
  bool sticks = false;
  for (auto f : a.state().hasPlateStick) sticks = sticks || f != 0;
  REQUIRE(sticks);

  RunCheckpoint c;
  c.sceneHash = 42;
  c.step = a.step();
  c.state = a.state();
  c.carry = ka;
  c.acc.watch.snapFirst = 1.5;
  c.acc.watch.maxSubsteps = 7;
  c.acc.watch.minSelfDistance = 0.25;
  c.writers.timeseriesBytes = 123;
  c.writers.vtkEntries = {{0.5, "vtk/step_000010.vtp"}};
  const fs::path dir = rootsim::test::scratchDir("checkpoint", "round_trip");
  fs::create_directories(dir);
  writeCheckpoint(dir / kCheckpointFile, c);
  const RunCheckpoint r = readCheckpoint(dir / kCheckpointFile);
  // the file holds every field
  std::string d = checkpointDifference(c, r);
  CHECK_MESSAGE(d.empty(), "differs after the checkpoint: ", d);

  // a fresh Simulation from it carries the same again
  Simulation b(sc.model, r.state, r.carry);
  d = stateDifference(a.state(), b.state());
  CHECK_MESSAGE(d.empty(), "differs in the resumed state: ", d);
  d = carryDifference(ka, b.carry());
  CHECK_MESSAGE(d.empty(), "differs in the resumed simulation's carry: ", d);

  // and both go on bit for bit: a field that a list left out shows here, in what it changes
  for (int i = 0; i < 4; ++i) {
    a.growthStep();
    b.growthStep();
    d = stateDifference(a.state(), b.state());
    if (d.empty()) d = carryDifference(a.carry(), b.carry());
    CAPTURE(i);
    CHECK_MESSAGE(d.empty(), "differs after resuming and growing: ", d);
  }
  fs::remove_all(dir);
}
