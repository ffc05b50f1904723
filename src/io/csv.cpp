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

const std::vector<ShapeColumn>& shapeColumns() {
  using N = ShapeNode;
  static const std::vector<ShapeColumn> columns = {
      {"s_mm", "mm", "rest arc length from the base", [](const N& n) { return n.s; }},
      {"x_mm", "mm", "position, lab x", [](const N& n) { return n.x[0]; }},
      {"y_mm", "mm", "position, lab y", [](const N& n) { return n.x[1]; }},
      {"z_mm", "mm", "position, lab z", [](const N& n) { return n.x[2]; }},
      {"d1x", "", "node frame d1 (mean of the neighbouring elements' directors, re-orthonormalised), lab x", [](const N& n) { return n.d1[0]; }},
      {"d1y", "", "d1, lab y", [](const N& n) { return n.d1[1]; }},
      {"d1z", "", "d1, lab z", [](const N& n) { return n.d1[2]; }},
      {"d2x", "", "d2 = d3 x d1, lab x", [](const N& n) { return n.d2[0]; }},
      {"d2y", "", "d2, lab y", [](const N& n) { return n.d2[1]; }},
      {"d2z", "", "d2, lab z", [](const N& n) { return n.d2[2]; }},
      {"d3x", "", "d3 (the tangent's director), lab x", [](const N& n) { return n.d3[0]; }},
      {"d3y", "", "d3, lab y", [](const N& n) { return n.d3[1]; }},
      {"d3z", "", "d3, lab z", [](const N& n) { return n.d3[2]; }},
      {"kappa1_per_mm", "1/mm", "curvature about d1 (Voronoi value per current length; 0 at the ends)", [](const N& n) { return n.kappa[0]; }},
      {"kappa2_per_mm", "1/mm", "curvature about d2", [](const N& n) { return n.kappa[1]; }},
      {"kappa3_per_mm", "1/mm", "twist rate about d3", [](const N& n) { return n.kappa[2]; }},
      {"stretch", "", "dilatation, mean of the neighbouring elements'", [](const N& n) { return n.stretch; }},
      {"radius_mm", "mm", "radius R/sqrt(stretch)", [](const N& n) { return n.radius; }},
      {"lateral_mm", "mm", "plate coordinates: across the plate (origin at the foot of the base node)", [](const N& n) { return n.plate[0]; }},
      {"downhill_mm", "mm", "down the plate", [](const N& n) { return n.plate[1]; }},
      {"height_mm", "mm", "above the plate", [](const N& n) { return n.plate[2]; }},
  };
  return columns;
}

std::string shapeCsv(const Model& m, const RodState& s, const RodStrains& k) {
  std::ostringstream os;
  const std::vector<ShapeColumn>& cols = shapeColumns();
  for (std::size_t c = 0; c < cols.size(); ++c) os << (c ? "," : "") << cols[c].name;
  os << '\n';
  const int n = s.elements();
  const PlateFrame plate = m.env.plane.frame();
  for (int i = 0; i <= n; ++i) {
    const int a = std::max(i - 1, 0), b = std::min(i, n - 1);
    const Mat3 A = s.Q[static_cast<size_t>(a)] + s.Q[static_cast<size_t>(b)];
    ShapeNode node;
    node.d3 = A.row(2).transpose().normalized();
    const Vec3 d1 = A.row(0).transpose();
    node.d1 = (d1 - d1.dot(node.d3) * node.d3).normalized();
    node.d2 = node.d3.cross(node.d1);
    node.kappa = Vec3::Zero();
    if (i >= 1 && i <= n - 1) node.kappa = k.kappa.col(i - 1) / k.ev[i - 1] * units::mm;
    node.stretch = 0.5 * (k.e[a] + k.e[b]);
    node.s = s.S[i] / units::mm;
    node.x = s.x.col(i) / units::mm;
    node.radius = elementRadius(m.rod, node.stretch) / units::mm;
    node.plate = plate.coords(s.x.col(i)) / units::mm;
    for (std::size_t c = 0; c < cols.size(); ++c) os << (c ? "," : "") << numberText(cols[c].value(node));
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
