#pragma once
// The trajectory of a run (docs/outputs.md): trajectory.csv and trajectory.bin, their writers and the one
// reader of both. Millimetres and hours.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rootsim/run_dir.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// snapshots for `rootsim render`: trajectory.csv, one row per node and snapshot:
// frame,step,time_h,node,x_mm,y_mm,z_mm,d1x,d1y,d1z,d3x,d3y,d3z,radius_mm,kappa0_per_mm,plate_force_n,
// f_plate_total_n,f_self_n,f_obstacle_n
// (the element columns d1..radius_mm of node i describe element i; they are empty on a snapshot's last
// node; kappa0_per_mm and plate_force_n are node values, see Snapshot; the last three are the
// magnitudes of the contact forces on the node [N]: plate with its friction, self-contact, obstacles with
// their friction). readTrajectory also reads the older 14- and 16-column files, leaving the missing
// fields of Snapshot empty.
class TrajectoryWriter {
 public:
  explicit TrajectoryWriter(const std::filesystem::path& path);
  // continues a killed run's file from the first `bytes` bytes, which hold `frames` frames
  TrajectoryWriter(const std::filesystem::path& path, std::uintmax_t bytes, int frames);
  void add(const Snapshot& s);
  void close();
  int frames() const { return frames_; }
  std::uintmax_t bytes() const { return f_.size(); }

 private:
  AtomicFile f_;
  int frames_ = 0;
};

// the same snapshots as trajectory.bin, raw little-endian doubles (docs/outputs.md has the layout):
//   file header   "RSTRAJ01" (8 bytes) | u32 version 1 | u32 0
//   per snapshot  i32 frame | i32 step | i32 nodes N | u32 fields | f64 time_h
//                 f64 x_mm[N][3] | f64 d1[N-1][3] | f64 d3[N-1][3] | f64 radius_mm[N-1]
//                 then, when fields has bit 0: f64 kappa0_per_mm[N]; bit 1: f64 plate_force_n[N];
//                 bit 2: f64 contact_force_n[N][3] (plate with friction, self, obstacles)
// The values are the CSV's (same units), bit for bit: a binary and a CSV trajectory of one run read
// back to the same snapshots.
class TrajectoryBinaryWriter {
 public:
  explicit TrajectoryBinaryWriter(const std::filesystem::path& path);
  TrajectoryBinaryWriter(const std::filesystem::path& path, std::uintmax_t bytes, int frames);
  void add(const Snapshot& s);
  void close();
  int frames() const { return frames_; }
  std::uintmax_t bytes() const { return f_.size(); }

 private:
  AtomicFile f_;
  int frames_ = 0;
  std::string buf_;   // one record, reused
};

// what readTrajectory accepts of a node's position and an element's radius: |x|, |y|, |z| <= 10 m and
// 0 < radius <= 0.1 m (the scene's own bound on root.radius_mm). The renderer sizes its frame, plate
// and grid from them: a single finite 1e7 mm coordinate made `rootsim render` grow past 4 GB.
inline constexpr double kMaxTrajectoryCoordMm = 1e4;
inline constexpr double kMaxTrajectoryRadiusMm = 100;

// reads a trajectory: trajectory.csv or trajectory.bin, told apart by their first bytes; a path to a
// trajectory.csv that does not exist reads the trajectory.bin beside it. Throws SceneError naming the
// file and line (CSV) or byte offset (binary) when it is malformed, and the frame and node when a
// position or radius is outside the bounds above
std::vector<Snapshot> readTrajectory(const std::filesystem::path& path);
// the trajectory file of a run directory: trajectory.bin when it exists, else trajectory.csv
std::filesystem::path trajectoryPath(const std::filesystem::path& runDir);

}  // namespace rootsim
