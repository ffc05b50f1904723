#pragma once
// Files of a run directory (docs/cli.md, "Run directory"; docs/outputs.md): shape.csv, timeseries.csv,
// summary.json, trajectory.csv / trajectory.bin and ParaView snapshots. Lab frame of docs/model.md, Frames
// and signs; millimetres and hours.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rootsim/run_dir.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/stability.hpp"
#include "rootsim/theory.hpp"

namespace rootsim {

// final centreline per node: s_mm,x_mm,y_mm,z_mm, the node frame (mean of the neighbouring elements'
// directors, re-orthonormalised) d1x..d3z, curvature kappa1..3 [1/mm] (Voronoi value per current
// length at interior nodes, 0 at the ends), stretch (dilatation, mean of neighbours), radius_mm
std::string shapeCsv(const Model& m, const RodState& s, const RodStrains& k);

// stiffness modes of a state (`rootsim modes`): modes.csv, one row per mode and node
// (mode,eigenvalue_n_per_m,node,s_mm,x_mm,y_mm,z_mm,ux,uy,uz: the node's position and its displacement
// in the mode, largest 1), and modes.vtp, the centreline with one point-data vector per mode
std::string modesCsv(const RodState& s, const StiffnessModes& m);
std::string modesVtp(const RodState& s, const StiffnessModes& m);

// time series, one row per output step, streamed (temp file renamed on close)
class TimeseriesWriter {
 public:
  explicit TimeseriesWriter(const std::filesystem::path& path);
  // continues a killed run's file from the first `bytes` bytes (a checkpoint's position)
  TimeseriesWriter(const std::filesystem::path& path, std::uintmax_t bytes);
  void add(const StepRecord& r);
  void close();
  std::uintmax_t bytes() const { return f_.size(); }

 private:
  AtomicFile f_;
};

// a numeric CSV file of a run directory (timeseries.csv, shape.csv), column by column: the header's names
// and every column's values, parsed with from_chars, so they are the doubles the run wrote (writers use
// to_chars, a shortest round trip); "nan" and "inf" cells are read as such. Throws SceneError naming
// the file and line when it is missing or malformed (a cell that is not a whole number, a short row).
struct CsvColumns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;  // values[c][row]
};
CsvColumns readCsvColumns(const std::filesystem::path& path);

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

// ParaView: vtk/step_NNNNNN.vtp (polyline, per-element d1, d3, radius) and trajectory.pvd
// (VTK XML PolyData, binary appended data compressed with zlib: compressor="vtkZLibDataCompressor",
// header_type="UInt64"; ParaView and VTK's readers read it)
class VtkSeriesWriter {
 public:
  explicit VtkSeriesWriter(const std::filesystem::path& runDir);
  // continues a killed run's series with the entries it had written (a checkpoint's)
  VtkSeriesWriter(const std::filesystem::path& runDir, std::vector<std::pair<double, std::string>> entries);
  void add(const Snapshot& s);
  void close();
  // trajectory.pvd's entries so far: (time_h, file)
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }

 private:
  std::filesystem::path dir_;
  std::vector<std::pair<double, std::string>> entries_;
};

// minimal JSON object builder (numbers: NaN and infinities become null)
class Json {
 public:
  Json& num(const std::string& key, double v);
  Json& integer(const std::string& key, long long v);
  Json& str(const std::string& key, const std::string& v);
  Json& boolean(const std::string& key, bool v);
  Json& object(const std::string& key, const Json& v);
  std::string dump(int indent = 0) const;

 private:
  struct Item {
    std::string key, raw;           // raw JSON text of a scalar value
    std::shared_ptr<Json> child;    // or a nested object
  };
  std::vector<Item> items_;
};

// the theory block of summary.json and `rootsim check`
Json theoryJson(const Theory& t);

}  // namespace rootsim
