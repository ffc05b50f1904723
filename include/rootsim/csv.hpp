#pragma once
// The CSV files of a run directory (docs/outputs.md): shape.csv, timeseries.csv (streamed), modes.csv,
// and the one reader of them. Lab frame of docs/model.md, Frames and signs; millimetres and hours.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rootsim/run_dir.hpp"
#include "rootsim/simulation.hpp"
#include "rootsim/stability.hpp"

namespace rootsim {

// final centreline per node: s_mm,x_mm,y_mm,z_mm, the node frame (mean of the neighbouring elements'
// directors, re-orthonormalised) d1x..d3z, curvature kappa1..3 [1/mm] (Voronoi value per current
// length at interior nodes, 0 at the ends), stretch (dilatation, mean of neighbours), radius_mm, and the
// node's plate coordinates lateral_mm, downhill_mm, height_mm (PlateFrame::coords of the scene's plate:
// across the plate, down it, above it; for a free organ the frame of plane.alpha_deg it started in)
std::string shapeCsv(const Model& m, const RodState& s, const RodStrains& k);
// one node of shape.csv in the file's units, and its columns declared once (shapeColumns: the writer's
// header and rows, docs/outputs.md's table)
struct ShapeNode {
  double s = 0;                     // [mm]
  Vec3 x, d1, d2, d3, kappa, plate; // [mm], unit vectors, [1/mm], [mm]
  double stretch = 0, radius = 0;   // [-], [mm]
};
struct ShapeColumn {
  const char* name;
  const char* unit;
  const char* help;
  double (*value)(const ShapeNode&);
};
const std::vector<ShapeColumn>& shapeColumns();

// stiffness modes of a state (`rootsim modes`): modes.csv, one row per mode and node
// (mode,eigenvalue_n_per_m,node,s_mm,x_mm,y_mm,z_mm,ux,uy,uz: the node's position and its displacement
// in the mode, largest 1), and modes.vtp, the centreline with one point-data vector per mode
std::string modesCsv(const RodState& s, const StiffnessModes& m);
// one column of timeseries.csv, declared once (timeseriesColumns): it writes the file's header and rows,
// fills the Python package's records (rootsim.Simulation.step) and docs/outputs.md's column table
struct RecordColumn {
  const char* name;                        // the header's name (its unit in it: time_h, length_mm)
  const char* unit;                        // "" for a count or a dimensionless value
  const char* help;
  double (*real)(const StepRecord&);       // the value, in the file's unit; null for a whole number
  long long (*whole)(const StepRecord&);   // a whole number (a step, a count), written as an integer
};
const std::vector<RecordColumn>& timeseriesColumns();

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
// the cells of a comma-separated line, a trailing comma giving an empty last cell (result.csv rows, the
// CLI's comma lists)
std::vector<std::string> splitCommas(const std::string& line);
// a text field of a CSV row: as it is, or quoted (quotes doubled) when it holds a comma, quote or newline
std::string csvField(const std::string& s);

struct CsvColumns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;  // values[c][row]
};
CsvColumns readCsvColumns(const std::filesystem::path& path);

}  // namespace rootsim
