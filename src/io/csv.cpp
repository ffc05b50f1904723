// The CSV files of a run directory and their reader (csv.hpp).
#include "rootsim/csv.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
// RFC 4180 over one record's text: the cells, or why it is malformed ("" when it is whole); open: the text
// ends inside a quoted field (the record continues on the next line)
std::string parseRecord(const std::string& text, std::vector<std::string>& cells, bool& open) {
  cells.assign(1, std::string());
  open = false;
  std::size_t i = 0;
  bool quoted = false, closed = false;  // the current cell began with a quote; its closing quote was seen
  while (i < text.size()) {
    const char c = text[i];
    if (quoted && !closed) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          cells.back() += '"';
          i += 2;
          continue;
        }
        closed = true;
      } else {
        cells.back() += c;
      }
    } else if (c == ',') {
      cells.emplace_back();
      quoted = closed = false;
    } else if (closed) {
      return "text after a quoted field's closing quote (cell " + std::to_string(cells.size()) + ")";
    } else if (c == '"' && cells.back().empty() && !quoted) {
      quoted = true;
    } else {
      cells.back() += c;
    }
    ++i;
  }
  open = quoted && !closed;
  return "";
}
}  // namespace

std::vector<std::string> csvCells(const std::string& record) {
  std::vector<std::string> cells;
  bool open = false;
  const std::string why = parseRecord(record, cells, open);
  if (!why.empty()) throw std::invalid_argument(why);
  if (open) throw std::invalid_argument("a quoted field is not closed");
  return cells;
}

bool readCsvRecord(std::istream& in, std::vector<std::string>& cells, int& lineNo, const std::string& where) {
  std::string text, line;
  if (!std::getline(in, line)) return false;
  ++lineNo;
  const int first = lineNo;
  text = line;
  if (!text.empty() && text.back() == '\r') text.pop_back();
  for (;;) {
    bool open = false;
    const std::string why = parseRecord(text, cells, open);
    if (!why.empty()) throw SceneError(where + ":" + std::to_string(lineNo) + ": " + why);
    if (!open) return true;
    if (!std::getline(in, line))
      throw SceneError(where + ":" + std::to_string(first) + ": a quoted field is not closed before the end of the file");
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    text += '\n' + line;
  }
}

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

TimeseriesWriter::TimeseriesWriter(const fs::path& path) : f_(path) {
  f_.stream() << "step,time_h,length_mm,elements,theta_tip_deg,Eb,Et,Wr,Tw,substeps,residual_force_n,splits,unstable,"
                 "tip_x_mm,tip_y_mm,tip_z_mm,newton_iterations,lowest_eigenvalue_n_per_m,self_contacts,"
                 "min_self_distance_r,obstacle_contacts,slip_events,frictional_work_j\n";
}

TimeseriesWriter::TimeseriesWriter(const fs::path& path, std::uintmax_t bytes) : f_(path, bytes) {}

void TimeseriesWriter::add(const StepRecord& r) {
  auto& o = f_.stream();
  o << r.step << ',' << numberText(r.timeH) << ',' << numberText(r.length / units::mm) << ',' << r.elements << ','
    << numberText(r.thetaTip / units::deg) << ',' << numberText(r.zone.Eb) << ',' << numberText(r.zone.Et) << ','
    << numberText(r.zone.Wr) << ',' << numberText(r.zone.Tw) << ',' << r.substeps << ',' << numberText(r.residualForce) << ','
    << r.splits << ',' << r.unstable << ',' << numberText(r.tip.x() / units::mm) << ',' << numberText(r.tip.y() / units::mm) << ',' << numberText(r.tip.z() / units::mm)
    << ',' << r.iterations << ',' << numberText(r.lowestEigenvalue)
    << ',' << r.selfContacts << ',' << numberText(r.minSelfDistance)
    << ',' << r.obstacleContacts << ',' << r.slipEvents << ',' << numberText(r.frictionWork) << '\n';
  f_.flush();  // one row per output step: a write failure stops the run here, not after the last step
}

void TimeseriesWriter::close() { f_.close(); }

CsvColumns readCsvColumns(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw SceneError(path.string() + ": cannot open (not a complete run directory?)");
  CsvColumns t;
  int lineNo = 0;
  std::vector<std::string> f;
  if (!readCsvRecord(in, f, lineNo, path.string()) || (f.size() == 1 && f[0].empty()))
    throw SceneError(path.string() + ":1: no header");
  t.names = f;
  t.values.resize(t.names.size());
  while (readCsvRecord(in, f, lineNo, path.string())) {
    if (f.size() == 1 && f[0].empty()) continue;  // an empty line
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

std::string csvQuoted(const std::string& s) {
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

std::string csvField(const std::string& s) {
  return s.find_first_of(",\"\n") == std::string::npos ? s : csvQuoted(s);
}

}  // namespace rootsim
