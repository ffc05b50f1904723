#pragma once
// Files of a run directory (SPEC.md "A run directory"): shape.csv, timeseries.csv, summary.json,
// trajectory.csv and ParaView snapshots. Lab frame of MODEL.md section 3, millimetres and hours.
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
  void add(const StepRecord& r);
  void close();

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
  void add(const Snapshot& s);
  void close();
  int frames() const { return frames_; }

 private:
  AtomicFile f_;
  int frames_ = 0;
};
// reads trajectory.csv; throws SceneError naming the file and line when it is malformed
std::vector<Snapshot> readTrajectory(const std::filesystem::path& path);

// ParaView: vtk/step_NNNNNN.vtp (polyline, per-element d1, d3, radius) and trajectory.pvd
class VtkSeriesWriter {
 public:
  explicit VtkSeriesWriter(const std::filesystem::path& runDir);
  void add(const Snapshot& s);
  void close();

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
