#pragma once
// Checkpoints of a growing run (`rootsim run --resume`, sweeps): DIR.partial/checkpoint.bin holds
// everything the run carries from one growth step to the next, so that a run continued from it writes
// the same bytes as one never interrupted. Layout (little-endian, raw IEEE doubles: bit for bit):
//
//   header (40 bytes)  magic "RSCHKPT\0" (8) | u32 version | u32 layout (RunLayout: 0 one root, 1 a plate) |
//                      u64 scene hash (FNV-1a of the resolved scene.toml) | i32 growth step | u32 reserved 0 |
//                      u64 payload bytes
//   payload            the run's accumulators (RunAccumulators), the plate's carry (PlateCarry, plate.hpp:
//                      every root's rod state and SimulationCarry, the laterals emerged, ...), then each
//                      root's accumulators and output writers' positions (PlateRootRun): each struct's field
//                      list (fields.hpp) in order, a field as its raw bytes (bool: 1 byte; an array or
//                      matrix: u64 length (columns), then its values; a string: u64 length, then its bytes;
//                      a list of structs: u64 length, then each struct's fields; a BandLU: i32 n, kl, ku,
//                      then its storage and pivots as arrays; a SparseStiffness: its SparseMemory)
//   trailer (8 bytes)  u64 FNV-1a of the payload: a torn or corrupt file is recognised
//
// A scene of one root alone runs as a plate of one seedling (runSceneToDir): its checkpoint is a plate's
// with one root, whose files are at the run directory's top (layout 0) rather than in roots/NAME (layout 1).
// A checkpoint of an older version (a single root's had its own payload) is refused, saying so.
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
inline constexpr std::uint32_t kCheckpointVersion = 6;

// FNV-1a 64 of a text (the resolved scene): the same on every machine
std::uint64_t sceneHash(const std::string& resolvedToml);

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

// what a run carries of each root besides its simulation: its accumulators and its files' positions
struct PlateRootRun {
  RunWatch watch;
  WriterPositions writers;
  static constexpr auto fields() {
    using R = PlateRootRun;
    return std::tuple{field("watch", &R::watch), field("writers", &R::writers)};
  }
};
// and of itself: a plate summary's extremes so far, the wall time of the earlier attempts, plate_timeseries.csv's
// length (0: a scene of one root, which writes no such file)
struct RunAccumulators {
  int maxSweeps = 1;
  double minGap = std::numeric_limits<double>::quiet_NaN();
  double wallBefore = 0;
  std::uint64_t seriesBytes = 0;
  static constexpr auto fields() {
    using A = RunAccumulators;
    return std::tuple{field("maxSweeps", &A::maxSweeps), field("minGap", &A::minGap),
                      field("wallBefore", &A::wallBefore), field("seriesBytes", &A::seriesBytes)};
  }
};
// where a run's roots keep their files (the header's layout): a scene of one root at the run directory's top,
// a plate's roots each in roots/NAME
enum class RunLayout : std::uint32_t { OneRoot = 0, Plate = 1 };

// a run's checkpoint: the plate's (a scene of one root: a plate of one seedling)
struct RunCheckpoint {
  std::uint64_t sceneHash = 0;
  int step = 0;
  RunLayout layout = RunLayout::Plate;
  PlateCarry plate;
  std::vector<PlateRootRun> roots;  // as plate.roots
  RunAccumulators acc;
};

// writes path atomically; throws RunError naming the file
void writeCheckpoint(const std::filesystem::path& path, const RunCheckpoint& c);
// reads and checks a checkpoint of a run of `layout` (magic, version, layout, length, checksum, sizes, each
// root's part against its files); throws SceneError naming the file and what is wrong with it.
// seedlingNames: the run's seedlings (one root: one name, its folder the run directory's), whose folders are
// roots/NAME in a plate (the laterals' names follow from their births: lateralName)
RunCheckpoint readCheckpoint(const std::filesystem::path& path, RunLayout layout,
                             const std::vector<std::string>& seedlingNames);

// the dotted name of the first field (through the field lists) whose bytes differ, e.g.
// "carry.newton.matureK"; "" when every field is the same bit for bit (tests)
std::string checkpointDifference(const RunCheckpoint& a, const RunCheckpoint& b);
std::string carryDifference(const SimulationCarry& a, const SimulationCarry& b);
std::string stateDifference(const RodState& a, const RodState& b);

}  // namespace rootsim
