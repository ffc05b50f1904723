#pragma once
// Checkpoints of a growing run (`rootsim run --resume`, sweeps): DIR.partial/checkpoint.bin holds
// everything the run carries from one growth step to the next, so that a run continued from it writes
// the same bytes as one never interrupted. Layout (little-endian, raw IEEE doubles: bit for bit):
//
//   header (40 bytes)  magic "RSCHKPT\0" (8) | u32 version | u32 reserved 0 | u64 scene hash (FNV-1a of
//                      the resolved scene.toml) | i32 growth step | u32 reserved 0 | u64 payload bytes
//   payload            the rod state, SimulationCarry, the run's accumulators and the output writers'
//                      positions (checkpoint.cpp writes and reads them in one order)
//   trailer (8 bytes)  u64 FNV-1a of the payload: a torn or corrupt file is recognised
//
// The file is written atomically (checkpoint.bin.tmp, then rename): a kill leaves the previous one.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rootsim/rod.hpp"
#include "rootsim/simulation.hpp"

namespace rootsim {

inline constexpr const char* kCheckpointFile = "checkpoint.bin";
inline constexpr std::uint32_t kCheckpointVersion = 5;

// FNV-1a 64 of a text (the resolved scene): the same on every machine
std::uint64_t sceneHash(const std::string& resolvedToml);

// what runSceneToDir accumulates over the steps besides the simulation
struct RunAccumulators {
  double snapFirst = 0, snapVertical = 0, snapPrevTheta = 0, snapPrevTime = 0;  // SnapWatch [h], [rad]
  long maxSubsteps = 0;
  int maxSelfContacts = 0;
  double minSelfDistance = 0;      // [R] (NaN: never within 3R)
  double wallBefore = 0;           // wall time of the earlier attempts [s]
};

// where the output files stood at the checkpoint
struct WriterPositions {
  std::uint64_t timeseriesBytes = 0;
  std::uint64_t trajectoryBytes = 0;        // trajectory.csv (0 when not written)
  std::uint64_t trajectoryBinaryBytes = 0;  // trajectory.bin (0 when not written)
  int trajectoryFrames = 0;
  std::vector<std::pair<double, std::string>> vtkEntries;  // trajectory.pvd's entries so far (time_h, file)
};

struct RunCheckpoint {
  std::uint64_t sceneHash = 0;
  int step = 0;
  RodState state;
  SimulationCarry carry;
  RunAccumulators acc;
  WriterPositions writers;
};

// writes path atomically; throws RunError naming the file
void writeCheckpoint(const std::filesystem::path& path, const RunCheckpoint& c);
// reads and checks a checkpoint (magic, version, length, checksum, sizes); throws SceneError naming the
// file and what is wrong with it
RunCheckpoint readCheckpoint(const std::filesystem::path& path);

}  // namespace rootsim
