// The CSV files of a run directory and their reader (csv.hpp).
#include "rootsim/csv.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim {

std::vector<std::string> splitCommas(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string shapeCsv(const Model& m, const RodState& s, const RodStrains& k) {
  std::ostringstream os;
  os << "s_mm,x_mm,y_mm,z_mm,d1x,d1y,d1z,d2x,d2y,d2z,d3x,d3y,d3z,kappa1_per_mm,kappa2_per_mm,kappa3_per_mm,"
        "stretch,radius_mm,lateral_mm,downhill_mm,height_mm\n";
  const int n = s.elements();
  const PlateFrame plate = m.env.plane.frame();
  for (int i = 0; i <= n; ++i) {
    const int a = std::max(i - 1, 0), b = std::min(i, n - 1);
    const Mat3 A = s.Q[static_cast<size_t>(a)] + s.Q[static_cast<size_t>(b)];
    Vec3 d3 = A.row(2).transpose().normalized();
    Vec3 d1 = A.row(0).transpose();
    d1 = (d1 - d1.dot(d3) * d3).normalized();
    const Vec3 d2 = d3.cross(d1);
    Vec3 kap = Vec3::Zero();
    if (i >= 1 && i <= n - 1) kap = k.kappa.col(i - 1) / k.ev[i - 1] * units::mm;
    const double e = 0.5 * (k.e[a] + k.e[b]);
    os << numberText(s.S[i] / units::mm);
    for (int d = 0; d < 3; ++d) os << ',' << numberText(s.x(d, i) / units::mm);
    const Vec3* frame[3] = {&d1, &d2, &d3};
    for (const Vec3* v : frame)
      for (int d = 0; d < 3; ++d) os << ',' << numberText((*v)[d]);
    for (int d = 0; d < 3; ++d) os << ',' << numberText(kap[d]);
    os << ',' << numberText(e) << ',' << numberText(elementRadius(m.rod, e) / units::mm);
    const Vec3 onPlate = plate.coords(s.x.col(i)) / units::mm;
    for (int d = 0; d < 3; ++d) os << ',' << numberText(onPlate[d]);
    os << '\n';
  }
  return os.str();
}

std::string modesCsv(const RodState& s, const StiffnessModes& m) {
  std::ostringstream o;
  o << "mode,eigenvalue_n_per_m,node,s_mm,x_mm,y_mm,z_mm,ux,uy,uz\n";
  for (size_t q = 0; q < m.modes.size(); ++q)
    for (int i = 0; i < s.nodes(); ++i) {
      o << q + 1 << ',' << numberText(m.eigenvalues[static_cast<long>(q)]) << ',' << i << ',' << numberText(s.S[i] / units::mm);
      for (int d = 0; d < 3; ++d) o << ',' << numberText(s.x(d, i) / units::mm);
      for (int d = 0; d < 3; ++d) o << ',' << numberText(m.modes[q][6 * i + d]);
      o << '\n';
    }
  return o.str();
}

const std::vector<RecordColumn>& timeseriesColumns() {
  using R = StepRecord;
  static const std::vector<RecordColumn> columns = {
      {"step", "", "growth step", nullptr, [](const R& r) -> long long { return r.step; }},
      {"time_h", "h", "growth time", [](const R& r) { return r.timeH; }, nullptr},
      {"length_mm", "mm", "rest length of the root", [](const R& r) { return r.length / units::mm; }, nullptr},
      {"elements", "", "elements of the rod", nullptr, [](const R& r) -> long long { return r.elements; }},
      {"theta_tip_deg", "deg", "planar tip angle, unwrapped over time", [](const R& r) { return r.thetaTip / units::deg; }, nullptr},
      {"Eb", "J", "bending energy of the growth zone", [](const R& r) { return r.zone.Eb; }, nullptr},
      {"Et", "J", "twist energy of the growth zone", [](const R& r) { return r.zone.Et; }, nullptr},
      {"Wr", "", "writhe of the growth zone", [](const R& r) { return r.zone.Wr; }, nullptr},
      {"Tw", "", "twist of the growth zone", [](const R& r) { return r.zone.Tw; }, nullptr},
      {"substeps", "", "explicit relaxation sub-steps of this step", nullptr, [](const R& r) -> long long { return r.substeps; }},
      {"residual_force_n", "N", "residual force when the step's relaxation stopped", [](const R& r) { return r.residualForce; }, nullptr},
      {"splits", "", "elements split in this step", nullptr, [](const R& r) -> long long { return r.splits; }},
      {"unstable", "", "unstable equilibria found (and left along their unstable mode) in this step", nullptr,
       [](const R& r) -> long long { return r.unstable; }},
      {"tip_x_mm", "mm", "tip position, lab x", [](const R& r) { return r.tip.x() / units::mm; }, nullptr},
      {"tip_y_mm", "mm", "tip position, lab y", [](const R& r) { return r.tip.y() / units::mm; }, nullptr},
      {"tip_z_mm", "mm", "tip position, lab z", [](const R& r) { return r.tip.z() / units::mm; }, nullptr},
      {"newton_iterations", "", "Newton iterations of this step", nullptr, [](const R& r) -> long long { return r.iterations; }},
      {"lowest_eigenvalue_n_per_m", "N/m", "stiffness eigenvalue nearest zero at the equilibrium (Newton with the stability check; else nan)",
       [](const R& r) { return r.lowestEigenvalue; }, nullptr},
      {"self_contacts", "", "element pairs in self-contact", nullptr, [](const R& r) -> long long { return r.selfContacts; }},
      {"min_self_distance_r", "R", "closest approach of elements at least 3R apart along the root, / R (nan: none within 3R)",
       [](const R& r) { return r.minSelfDistance; }, nullptr},
      {"obstacle_contacts", "", "elements touching an obstacle", nullptr, [](const R& r) -> long long { return r.obstacleContacts; }},
      {"slip_events", "", "node slips committed so far (friction), cumulative", nullptr, [](const R& r) -> long long { return r.slipEvents; }},
      {"frictional_work_j", "J", "work done against friction so far, cumulative", [](const R& r) { return r.frictionWork; }, nullptr},
  };
  return columns;
}

TimeseriesWriter::TimeseriesWriter(const fs::path& path) : f_(path) {
  auto& o = f_.stream();
  const std::vector<RecordColumn>& cols = timeseriesColumns();
  for (std::size_t c = 0; c < cols.size(); ++c) o << (c ? "," : "") << cols[c].name;
  o << '\n';
}

TimeseriesWriter::TimeseriesWriter(const fs::path& path, std::uintmax_t bytes) : f_(path, bytes) {}

void TimeseriesWriter::add(const StepRecord& r) {
  auto& o = f_.stream();
  const std::vector<RecordColumn>& cols = timeseriesColumns();
  for (std::size_t c = 0; c < cols.size(); ++c) {
    if (c) o << ',';
    if (cols[c].real) o << numberText(cols[c].real(r));
    else o << cols[c].whole(r);
  }
  o << '\n';
  f_.flush();  // one row per output step: a write failure stops the run here, not after the last step
}

void TimeseriesWriter::close() { f_.close(); }

CsvColumns readCsvColumns(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw SceneError(path.string() + ": cannot open (not a complete run directory?)");
  CsvColumns t;
  std::string line;
  if (!std::getline(in, line) || line.empty()) throw SceneError(path.string() + ":1: no header");
  auto cells = [](const std::string& l) {
    std::vector<std::string> f;
    std::stringstream ss(l);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (!l.empty() && l.back() == ',') f.push_back("");
    return f;
  };
  t.names = cells(line);
  t.values.resize(t.names.size());
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    const std::vector<std::string> f = cells(line);
    auto bad = [&](const std::string& why) {
      throw SceneError(path.string() + ":" + std::to_string(lineNo) + ": " + why);
    };
    if (f.size() != t.names.size())
      bad("expected " + std::to_string(t.names.size()) + " columns, found " + std::to_string(f.size()));
    for (std::size_t c = 0; c < f.size(); ++c) {
      double v = 0;
      const char* b = f[c].data();
      const char* e = b + f[c].size();
      const auto r = std::from_chars(b, e, v);
      if (f[c].empty() || r.ec != std::errc() || r.ptr != e)
        bad(t.names[c] + ": expected a number (got \"" + printable(f[c]) + "\")");
      t.values[c].push_back(v);
    }
  }
  return t;
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

}  // namespace rootsim
