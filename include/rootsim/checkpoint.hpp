#pragma once
// Checkpoints of a growing run (`rootsim run --resume`, sweeps): DIR.partial/checkpoint.bin holds
// everything the run carries from one growth step to the next, so that a run continued from it writes
// the same bytes as one never interrupted. Layout (little-endian, raw IEEE doubles: bit for bit):
//
//   header (40 bytes)  magic "RSCHKPT\0" (8) | u32 version | u32 kind (0 one root, 1 a plate) | u64 scene hash (FNV-1a of
//                      the resolved scene.toml) | i32 growth step | u32 reserved 0 | u64 payload bytes
//   payload            the rod state (its field list in rod_fields.hpp), SimulationCarry, the run's accumulators and the output writers'
//                      positions: each struct's field list (fields.hpp) in order, a field as its raw
//                      bytes (bool: 1 byte; an array or matrix: u64 length (columns), then its values;
//                      a string: u64 length, then its bytes; a BandLU: i32 n, kl, ku, then its storage
//                      and pivots as arrays; a SparseStiffness: its SparseMemory)
//   trailer (8 bytes)  u64 FNV-1a of the payload: a torn or corrupt file is recognised
//
// A plate's checkpoint (kind 1 in the header's second u32; a single root's is kind 0) has the same header
// and trailer; its payload is the plate's carry (PlateCarry, plate.hpp: every root's state and carry, the
// laterals emerged, ...), each root's accumulators and writer positions, and the plate's own (a list of
// structs: u64 length, then each struct's fields).
//
// The file is written atomically (checkpoint.bin.tmp, then rename): a kill leaves the previous one.
#include <cstdint>
#include <limits>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rootsim/fields.hpp"
#include "rootsim/plate.hpp"
#include "rootsim/run_watch.hpp"
#include "rootsim/rod.hpp"
#include "rootsim/rod_fields.hpp"
#include "rootsim/simulation.hpp"

namespace rootsim {

inline constexpr const char* kCheckpointFile = "checkpoint.bin";
inline constexpr std::uint32_t kCheckpointVersion = 5;

// FNV-1a 64 of a text (the resolved scene): the same on every machine
std::uint64_t sceneHash(const std::string& resolvedToml);

// what runSceneToDir accumulates over the steps besides the simulation
struct RunAccumulators {
  RunWatch watch;                  // the run's moments and extremes (run_watch.hpp)
  double wallBefore = 0;           // wall time of the earlier attempts [s]
  static constexpr auto fields() {
    using A = RunAccumulators;
    return std::tuple{field("watch", &A::watch), field("wallBefore", &A::wallBefore)};
  }
};

// where the output files stood at the checkpoint
struct WriterPositions {
  std::uint64_t timeseriesBytes = 0;
  std::uint64_t trajectoryBytes = 0;        // trajectory.csv (0 when not written)
  std::uint64_t trajectoryBinaryBytes = 0;  // trajectory.bin (0 when not written)
  int trajectoryFrames = 0;
  std::vector<std::pair<double, std::string>> vtkEntries;  // trajectory.pvd's entries so far (time_h, file)
  static constexpr auto fields() {
    using W = WriterPositions;
    return std::tuple{field("timeseriesBytes", &W::timeseriesBytes), field("trajectoryBytes", &W::trajectoryBytes),
                      field("trajectoryBinaryBytes", &W::trajectoryBinaryBytes),
                      field("trajectoryFrames", &W::trajectoryFrames), field("vtkEntries", &W::vtkEntries)};
  }
};

struct RunCheckpoint {
  std::uint64_t sceneHash = 0;
  int step = 0;
  RodState state;
  SimulationCarry carry;
  RunAccumulators acc;
  WriterPositions writers;
};

// what a plate's run carries of each root besides its simulation: its accumulators and its files' positions
struct PlateRootRun {
  RunWatch watch;
  WriterPositions writers;
  static constexpr auto fields() {
    using R = PlateRootRun;
    return std::tuple{field("watch", &R::watch), field("writers", &R::writers)};
  }
};
// and of itself: the summary's extremes so far, the wall time of the earlier attempts, plate_timeseries.csv's
// length
struct PlateRunAccumulators {
  int maxSweeps = 1;
  double minGap = std::numeric_limits<double>::quiet_NaN();
  double wallBefore = 0;
  std::uint64_t seriesBytes = 0;
  static constexpr auto fields() {
    using A = PlateRunAccumulators;
    return std::tuple{field("maxSweeps", &A::maxSweeps), field("minGap", &A::minGap),
                      field("wallBefore", &A::wallBefore), field("seriesBytes", &A::seriesBytes)};
  }
};
struct PlateCheckpoint {
  std::uint64_t sceneHash = 0;
  int step = 0;
  PlateCarry plate;
  std::vector<PlateRootRun> roots;  // as plate.roots
  PlateRunAccumulators acc;
};

// writes path atomically; throws RunError naming the file
void writeCheckpoint(const std::filesystem::path& path, const RunCheckpoint& c);
// reads and checks a checkpoint (magic, version, length, checksum, sizes); throws SceneError naming the
// file and what is wrong with it
RunCheckpoint readCheckpoint(const std::filesystem::path& path);

// a plate's (kind 1). seedlingNames: the plate's seedlings, whose roots' folders are roots/NAME (the
// laterals' names follow from their births: lateralName); each root's part is checked as a single root's,
// its files in its folder included
void writePlateCheckpoint(const std::filesystem::path& path, const PlateCheckpoint& c);
PlateCheckpoint readPlateCheckpoint(const std::filesystem::path& path, const std::vector<std::string>& seedlingNames);

// the dotted name of the first field (through the field lists) whose bytes differ, e.g.
// "carry.newton.matureK"; "" when every field is the same bit for bit (tests)
std::string checkpointDifference(const RunCheckpoint& a, const RunCheckpoint& b);
std::string carryDifference(const SimulationCarry& a, const SimulationCarry& b);
std::string stateDifference(const RodState& a, const RodState& b);
std::string plateCheckpointDifference(const PlateCheckpoint& a, const PlateCheckpoint& b);

}  // namespace rootsim
