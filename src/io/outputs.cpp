#include "rootsim/outputs.hpp"

#include <charconv>
#include <cstring>
#include <iterator>
#include <zlib.h>
#include <cmath>
#include <system_error>
#include <fstream>
#include <sstream>

#include "rootsim/errors.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
// shortest round-trip text of a double (locale-independent, deterministic)
std::string fmt(double x) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}
std::string jsonEscape(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') { o += '\\'; o += c; }
    else if (c == '\n') o += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20) { char b[8]; std::snprintf(b, sizeof b, "\\u%04x", c); o += b; }
    else o += c;
  }
  return o + "\"";
}
}  // namespace

std::string shapeCsv(const Model& m, const RodState& s, const RodStrains& k) {
  std::ostringstream os;
  os << "s_mm,x_mm,y_mm,z_mm,d1x,d1y,d1z,d2x,d2y,d2z,d3x,d3y,d3z,kappa1_per_mm,kappa2_per_mm,kappa3_per_mm,"
        "stretch,radius_mm\n";
  const int n = s.elements();
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
    os << fmt(s.S[i] / units::mm);
    for (int d = 0; d < 3; ++d) os << ',' << fmt(s.x(d, i) / units::mm);
    const Vec3* frame[3] = {&d1, &d2, &d3};
    for (const Vec3* v : frame)
      for (int d = 0; d < 3; ++d) os << ',' << fmt((*v)[d]);
    for (int d = 0; d < 3; ++d) os << ',' << fmt(kap[d]);
    os << ',' << fmt(e) << ',' << fmt(elementRadius(m.rod, e) / units::mm) << '\n';
  }
  return os.str();
}

std::string modesCsv(const RodState& s, const StiffnessModes& m) {
  std::ostringstream o;
  o << "mode,eigenvalue_n_per_m,node,s_mm,x_mm,y_mm,z_mm,ux,uy,uz\n";
  for (size_t q = 0; q < m.modes.size(); ++q)
    for (int i = 0; i < s.nodes(); ++i) {
      o << q + 1 << ',' << fmt(m.eigenvalues[static_cast<long>(q)]) << ',' << i << ',' << fmt(s.S[i] / units::mm);
      for (int d = 0; d < 3; ++d) o << ',' << fmt(s.x(d, i) / units::mm);
      for (int d = 0; d < 3; ++d) o << ',' << fmt(m.modes[q][6 * i + d]);
      o << '\n';
    }
  return o.str();
}

namespace {
// the opening of a ParaView polyline file: the centreline nodes [mm] joined by one line per element; the
// caller adds its point or cell data and closes with vtpClose()
void vtpPolyline(std::ostream& o, const Eigen::Matrix3Xd& x) {
  const long nn = x.cols(), n = nn - 1;
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<PolyData>\n<Piece NumberOfPoints=\"" << nn << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << n
    << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<Points>\n"
    << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (long i = 0; i < nn; ++i) o << fmt(x(0, i) / units::mm) << ' ' << fmt(x(1, i) / units::mm) << ' ' << fmt(x(2, i) / units::mm) << '\n';
  o << "</DataArray>\n</Points>\n<Lines>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (long i = 0; i < n; ++i) o << i << ' ' << i + 1 << '\n';
  o << "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (long i = 0; i < n; ++i) o << 2 * (i + 1) << '\n';
  o << "</DataArray>\n</Lines>\n";
}
}  // namespace

std::string modesVtp(const RodState& s, const StiffnessModes& m) {
  const int nn = s.nodes();
  std::ostringstream o;
  vtpPolyline(o, s.x);
  o << "<PointData Vectors=\"mode_1\">\n";
  for (size_t q = 0; q < m.modes.size(); ++q) {
    o << "<DataArray type=\"Float64\" Name=\"mode_" << q + 1 << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (int i = 0; i < nn; ++i)
      o << fmt(m.modes[q][6 * i]) << ' ' << fmt(m.modes[q][6 * i + 1]) << ' ' << fmt(m.modes[q][6 * i + 2]) << '\n';
    o << "</DataArray>\n";
  }
  o << "</PointData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
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
  o << r.step << ',' << fmt(r.timeH) << ',' << fmt(r.length / units::mm) << ',' << r.elements << ','
    << fmt(r.thetaTip / units::deg) << ',' << fmt(r.zone.Eb) << ',' << fmt(r.zone.Et) << ','
    << fmt(r.zone.Wr) << ',' << fmt(r.zone.Tw) << ',' << r.substeps << ',' << fmt(r.residualForce) << ','
    << r.splits << ',' << r.unstable << ',' << fmt(r.tip.x() / units::mm) << ',' << fmt(r.tip.y() / units::mm) << ',' << fmt(r.tip.z() / units::mm)
    << ',' << r.iterations << ',' << fmt(r.lowestEigenvalue)
    << ',' << r.selfContacts << ',' << fmt(r.minSelfDistance)
    << ',' << r.obstacleContacts << ',' << r.slipEvents << ',' << fmt(r.frictionWork) << '\n';
  f_.flush();  // one row per output step: a write failure stops the run here, not after the last step
}

void TimeseriesWriter::close() { f_.close(); }

TrajectoryWriter::TrajectoryWriter(const fs::path& path) : f_(path) {
  f_.stream() << "frame,step,time_h,node,x_mm,y_mm,z_mm,d1x,d1y,d1z,d3x,d3y,d3z,radius_mm,kappa0_per_mm,"
                 "plate_force_n,f_plate_total_n,f_self_n,f_obstacle_n\n";
}

TrajectoryWriter::TrajectoryWriter(const fs::path& path, std::uintmax_t bytes, int frames)
    : f_(path, bytes), frames_(frames) {}

void TrajectoryWriter::add(const Snapshot& s) {
  auto& o = f_.stream();
  const int n = s.elements();
  const bool k0 = s.kappa0.size() == n + 1, pf = s.plateForce.size() == n + 1, cf = s.contactForce.cols() == n + 1;
  for (int i = 0; i <= n; ++i) {
    o << frames_ << ',' << s.step << ',' << fmt(s.timeH) << ',' << i;
    for (int d = 0; d < 3; ++d) o << ',' << fmt(s.x(d, i) / units::mm);
    if (i < n) {
      for (int d = 0; d < 3; ++d) o << ',' << fmt(s.d1(d, i));
      for (int d = 0; d < 3; ++d) o << ',' << fmt(s.d3(d, i));
      o << ',' << fmt(s.radius[i] / units::mm);
    } else {
      o << ",,,,,,,";
    }
    o << ',' << (k0 ? fmt(s.kappa0[i] * units::mm) : "") << ',' << (pf ? fmt(s.plateForce[i]) : "");
    for (int c = 0; c < 3; ++c) o << ',' << (cf ? fmt(s.contactForce(c, i)) : "");
    o << '\n';
  }
  ++frames_;
  f_.flush();  // one frame per output step: a write failure stops the run here, not after the last step
}

void TrajectoryWriter::close() { f_.close(); }

namespace {
constexpr char kTrajMagic[8] = {'R', 'S', 'T', 'R', 'A', 'J', '0', '1'};
constexpr std::uint32_t kTrajVersion = 1;
constexpr std::uint32_t kHasKappa0 = 1, kHasPlateForce = 2, kHasContactForce = 4;
template <class T>
void putRaw(std::string& b, const T& v) {
  b.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// the refusals of a position or radius beyond the trajectory bounds (outputs.hpp)
std::string trajectoryCoordBound(char axis, double v) {
  return std::string(1, axis) + "_mm = " + fmt(v) + " is outside -" + fmt(kMaxTrajectoryCoordMm) + " .. " +
         fmt(kMaxTrajectoryCoordMm) + " mm (positions are bounded to |x|, |y|, |z| <= 10 m)";
}
std::string trajectoryRadiusBound(double r) {
  return "radius_mm = " + fmt(r) + " is above " + fmt(kMaxTrajectoryRadiusMm) + " mm (radii are bounded to 0.1 m)";
}

// trajectory.bin (layout in outputs.hpp and docs/outputs.md)
std::vector<Snapshot> readTrajectoryBinary(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw SceneError(path.string() + ": cannot open trajectory");
  const std::string b((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::size_t pos = 0;
  auto bad = [&](const std::string& why) {
    throw SceneError(path.string() + ": byte " + std::to_string(pos) + ": " + why);
  };
  auto take = [&](void* p, std::size_t n) {
    if (n > b.size() - pos) bad("truncated (the file ends inside a snapshot)");
    std::memcpy(p, b.data() + pos, n);
    pos += n;
  };
  if (b.size() < 16 || std::memcmp(b.data(), kTrajMagic, 8) != 0) bad("not a rootsim binary trajectory");
  pos = 8;
  std::uint32_t version = 0, reserved = 0;
  take(&version, 4);
  take(&reserved, 4);
  if (version != kTrajVersion) bad("version " + std::to_string(version) + " (this rootsim reads version 1)");
  std::vector<Snapshot> out;
  // every number finite, as the CSV reader demands; converted from the file's units as it does
  // (divide: as the CSV reader converts per-mm values, a division rather than a product by 1/mm)
  auto reals = [&](double* dst, std::size_t n, double scale, const char* what, bool divide = false) {
    const std::size_t at = pos;
    take(dst, n * sizeof(double));
    for (std::size_t i = 0; i < n; ++i) {
      dst[i] = divide ? dst[i] / scale : dst[i] * scale;
      if (!std::isfinite(dst[i])) {
        pos = at + i * sizeof(double);
        bad(std::string(what) + ": not a finite number");
      }
    }
  };
  while (pos < b.size()) {
    const std::size_t start = pos;
    std::int32_t frame = 0, step = 0, nodes = 0;
    std::uint32_t fields = 0;
    double t = 0;
    take(&frame, 4);
    take(&step, 4);
    take(&nodes, 4);
    take(&fields, 4);
    take(&t, 8);
    pos = start;
    if (frame != static_cast<std::int32_t>(out.size())) bad("frame " + std::to_string(frame) + " out of order");
    if (nodes < 2) bad("a snapshot of " + std::to_string(nodes) + " nodes (a rod needs two)");
    if ((fields & ~std::uint32_t{7}) != 0) bad("unknown fields " + std::to_string(fields));
    if (!std::isfinite(t)) bad("time_h: not a finite number");
    const std::size_t N = static_cast<std::size_t>(nodes);
    // the record: its 24-byte head, 3N + 7(N - 1) doubles, and the optional node fields
    const std::size_t perNode = 10 + ((fields & kHasKappa0) ? 1 : 0) + ((fields & kHasPlateForce) ? 1 : 0) +
                                ((fields & kHasContactForce) ? 3 : 0);
    if (N > (b.size() - pos) / sizeof(double) || 24 + (perNode * N - 7) * sizeof(double) > b.size() - pos)
      bad("truncated (a snapshot of " + std::to_string(N) + " nodes)");
    pos = start + 24;
    Snapshot s;
    s.step = step;
    s.timeH = t;
    const auto n = static_cast<Eigen::Index>(N - 1);
    s.x.resize(3, n + 1);
    s.d1.resize(3, n);
    s.d3.resize(3, n);
    s.radius.resize(n);
    reals(s.x.data(), 3 * N, units::mm, "x_mm");
    reals(s.d1.data(), 3 * (N - 1), 1.0, "d1");
    reals(s.d3.data(), 3 * (N - 1), 1.0, "d3");
    const std::size_t rAt = pos;
    reals(s.radius.data(), N - 1, units::mm, "radius_mm");
    for (Eigen::Index i = 0; i < n; ++i)
      if (s.radius[i] <= 0) {
        pos = rAt + static_cast<std::size_t>(i) * sizeof(double);
        bad("radius_mm: must be > 0");
      }
    // bounded before anything is sized from them (kMaxTrajectoryCoordMm, kMaxTrajectoryRadiusMm)
    for (Eigen::Index i = 0; i <= n; ++i)
      for (int d = 0; d < 3; ++d) {
        const double v = s.x(d, i) / units::mm;
        if (std::abs(v) > kMaxTrajectoryCoordMm) {
          pos = start + 24 + static_cast<std::size_t>(3 * i + d) * sizeof(double);
          bad("frame " + std::to_string(frame) + ", node " + std::to_string(i) + ": " + trajectoryCoordBound("xyz"[d], v));
        }
      }
    for (Eigen::Index i = 0; i < n; ++i)
      if (const double r = s.radius[i] / units::mm; r > kMaxTrajectoryRadiusMm) {
        pos = rAt + static_cast<std::size_t>(i) * sizeof(double);
        bad("frame " + std::to_string(frame) + ", node " + std::to_string(i) + ": " + trajectoryRadiusBound(r));
      }
    if (fields & kHasKappa0) {
      s.kappa0.resize(n + 1);
      reals(s.kappa0.data(), N, units::mm, "kappa0_per_mm", true);
    }
    if (fields & kHasPlateForce) {
      s.plateForce.resize(n + 1);
      reals(s.plateForce.data(), N, 1.0, "plate_force_n");
    }
    if (fields & kHasContactForce) {
      s.contactForce.resize(3, n + 1);
      reals(s.contactForce.data(), 3 * N, 1.0, "contact_force_n");
    }
    out.push_back(std::move(s));
  }
  if (out.empty()) throw SceneError(path.string() + ": no frames");
  return out;
}
}  // namespace

TrajectoryBinaryWriter::TrajectoryBinaryWriter(const fs::path& path) : f_(path) {
  std::string h(kTrajMagic, 8);
  putRaw(h, kTrajVersion);
  putRaw(h, std::uint32_t{0});
  f_.stream().write(h.data(), static_cast<std::streamsize>(h.size()));
}

TrajectoryBinaryWriter::TrajectoryBinaryWriter(const fs::path& path, std::uintmax_t bytes, int frames)
    : f_(path, bytes), frames_(frames) {}

void TrajectoryBinaryWriter::add(const Snapshot& s) {
  const int n = s.elements();
  const bool k0 = s.kappa0.size() == n + 1, pf = s.plateForce.size() == n + 1, cf = s.contactForce.cols() == n + 1;
  std::string& b = buf_;
  b.clear();
  putRaw(b, static_cast<std::int32_t>(frames_));
  putRaw(b, static_cast<std::int32_t>(s.step));
  putRaw(b, static_cast<std::int32_t>(n + 1));
  putRaw(b, static_cast<std::uint32_t>((k0 ? kHasKappa0 : 0) | (pf ? kHasPlateForce : 0) | (cf ? kHasContactForce : 0)));
  putRaw(b, s.timeH);
  // the CSV's values: lengths in mm, curvature per mm (x / mm is the double the CSV prints exactly)
  for (int i = 0; i <= n; ++i)
    for (int d = 0; d < 3; ++d) putRaw(b, s.x(d, i) / units::mm);
  for (const auto* arr : {&s.d1, &s.d3})
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) putRaw(b, (*arr)(d, i));
  for (int i = 0; i < n; ++i) putRaw(b, s.radius[i] / units::mm);
  if (k0)
    for (int i = 0; i <= n; ++i) putRaw(b, s.kappa0[i] * units::mm);
  if (pf)
    for (int i = 0; i <= n; ++i) putRaw(b, s.plateForce[i]);
  if (cf)
    for (int i = 0; i <= n; ++i)
      for (int c = 0; c < 3; ++c) putRaw(b, s.contactForce(c, i));
  f_.stream().write(b.data(), static_cast<std::streamsize>(b.size()));
  ++frames_;
  f_.flush();  // one frame per output step: a write failure stops the run here, not after the last step
}

void TrajectoryBinaryWriter::close() { f_.close(); }

fs::path trajectoryPath(const fs::path& runDir) {
  std::error_code ec;
  if (fs::is_regular_file(runDir / "trajectory.bin", ec)) return runDir / "trajectory.bin";
  return runDir / "trajectory.csv";
}

std::vector<Snapshot> readTrajectory(const fs::path& path) {
  {
    std::error_code ec;
    // a caller asking for trajectory.csv of a run that wrote the binary sibling
    if (!fs::exists(path, ec) && path.filename() == "trajectory.csv" &&
        fs::is_regular_file(path.parent_path() / "trajectory.bin", ec))
      return readTrajectoryBinary(path.parent_path() / "trajectory.bin");
    std::ifstream probe(path, std::ios::binary);
    char magic[8] = {};
    if (probe && probe.read(magic, 8) && std::memcmp(magic, kTrajMagic, 8) == 0) return readTrajectoryBinary(path);
  }
  std::ifstream in(path);
  if (!in) throw SceneError(path.string() + ": cannot open trajectory (is this a run directory written with "
                                            "output.trajectory = true?)");
  std::string line;
  int lineNo = 1;
  if (!std::getline(in, line) || line.rfind("frame,step,time_h,node,x_mm", 0) != 0)
    throw SceneError(path.string() + ":1: not a rootsim trajectory (unexpected header)");
  // 14 columns (before the node fields), 16 (with kappa0_per_mm, plate_force_n) or 19 (and the contact
  // forces f_plate_total_n, f_self_n, f_obstacle_n)
  const std::size_t columns = line.find(",f_self_n,") != std::string::npos
                                  ? 19
                                  : (line.find(",kappa0_per_mm,plate_force_n") != std::string::npos ? 16 : 14);
  struct Row { int frame, step, node; double t; double v[10]; bool hasElem; double k0 = 0, pf = 0; bool hasK0 = false, hasPf = false; double c[3] = {0, 0, 0}; bool hasContact = false; };
  std::vector<Snapshot> out;
  std::vector<Row> rows;
  auto flush = [&]() {
    if (rows.empty()) return;
    Snapshot s;
    const int nn = static_cast<int>(rows.size()), n = nn - 1;
    if (n < 1) throw SceneError(path.string() + ": frame " + std::to_string(rows[0].frame) + " has one node");
    s.step = rows[0].step;
    s.timeH = rows[0].t;
    s.x.resize(3, nn);
    s.d1.resize(3, n);
    s.d3.resize(3, n);
    s.radius.resize(n);
    bool allK0 = true, allPf = true, allC = true;
    for (const Row& r : rows) allK0 = allK0 && r.hasK0, allPf = allPf && r.hasPf, allC = allC && r.hasContact;
    if (allK0) s.kappa0.resize(nn);
    if (allPf) s.plateForce.resize(nn);
    if (allC) {
      s.contactForce.resize(3, nn);
      for (int i = 0; i < nn; ++i)
        for (int d = 0; d < 3; ++d) s.contactForce(d, i) = rows[static_cast<size_t>(i)].c[d];
    }
    for (int i = 0; i < nn; ++i) {
      if (allK0) s.kappa0[i] = rows[static_cast<size_t>(i)].k0 / units::mm;
      if (allPf) s.plateForce[i] = rows[static_cast<size_t>(i)].pf;
      for (int d = 0; d < 3; ++d) s.x(d, i) = rows[static_cast<size_t>(i)].v[d] * units::mm;
      if (i < n) {
        for (int d = 0; d < 3; ++d) s.d1(d, i) = rows[static_cast<size_t>(i)].v[3 + d];
        for (int d = 0; d < 3; ++d) s.d3(d, i) = rows[static_cast<size_t>(i)].v[6 + d];
        s.radius[i] = rows[static_cast<size_t>(i)].v[9] * units::mm;
      }
    }
    out.push_back(std::move(s));
    rows.clear();
  };
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (line.back() == ',') f.push_back("");
    auto bad = [&](const std::string& why) {
      throw SceneError(path.string() + ":" + std::to_string(lineNo) + ": " + why);
    };
    if (f.size() != columns) bad("expected " + std::to_string(columns) + " columns, found " + std::to_string(f.size()));
    static const char* const kColumns[19] = {"frame", "step", "time_h", "node", "x_mm", "y_mm", "z_mm", "d1x",
                                             "d1y", "d1z", "d3x", "d3y", "d3z", "radius_mm", "kappa0_per_mm",
                                             "plate_force_n", "f_plate_total_n", "f_self_n", "f_obstacle_n"};
    // every cell whole (no "12abc"), every number finite: a corrupt file is bad input, found here with
    // its line rather than by the renderer
    auto integer = [&](size_t c) {
      int x = 0;
      const char* b = f[c].data();
      const char* e = b + f[c].size();
      const auto r = std::from_chars(b, e, x);
      if (f[c].empty() || r.ec != std::errc() || r.ptr != e)
        bad(std::string(kColumns[c]) + ": expected an integer (got \"" + printable(f[c]) + "\")");
      return x;
    };
    auto real = [&](size_t c) {
      double x = 0;
      const char* b = f[c].data();
      const char* e = b + f[c].size();
      const auto r = std::from_chars(b, e, x);
      if (f[c].empty() || r.ec != std::errc() || r.ptr != e)
        bad(std::string(kColumns[c]) + ": expected a number (got \"" + printable(f[c]) + "\")");
      if (!std::isfinite(x)) bad(std::string(kColumns[c]) + ": not a finite number (got " + f[c] + ")");
      return x;
    };
    Row r{};
    r.frame = integer(0);
    r.step = integer(1);
    r.t = real(2);
    r.node = integer(3);
    for (int d = 0; d < 3; ++d) r.v[d] = real(static_cast<size_t>(4 + d));
    // bounded before anything is sized from them (kMaxTrajectoryCoordMm, kMaxTrajectoryRadiusMm)
    for (int d = 0; d < 3; ++d)
      if (std::abs(r.v[d]) > kMaxTrajectoryCoordMm)
        bad("frame " + std::to_string(r.frame) + ", node " + std::to_string(r.node) + ": " +
            trajectoryCoordBound("xyz"[d], r.v[d]));
    r.hasElem = !f[7].empty();
    if (r.hasElem) {
      for (int d = 0; d < 7; ++d) r.v[3 + d] = real(static_cast<size_t>(7 + d));
      if (r.v[9] <= 0) bad("radius_mm: must be > 0 (got " + f[13] + ")");
      if (r.v[9] > kMaxTrajectoryRadiusMm)
        bad("frame " + std::to_string(r.frame) + ", node " + std::to_string(r.node) + ": " + trajectoryRadiusBound(r.v[9]));
    } else {
      for (size_t c = 8; c < 14; ++c)
        if (!f[c].empty()) bad("the element columns of a frame's last node must all be empty");
    }
    if (columns >= 16) {
      if ((r.hasK0 = !f[14].empty())) r.k0 = real(14);
      if ((r.hasPf = !f[15].empty())) r.pf = real(15);
    }
    if (columns == 19 && (r.hasContact = !f[16].empty())) {
      for (int d = 0; d < 3; ++d) r.c[d] = real(static_cast<size_t>(16 + d));
    }
    if (!rows.empty() && r.frame != rows[0].frame) {
      if (rows.back().hasElem) bad("frame " + std::to_string(rows[0].frame) + " ends without its last node");
      flush();
    }
    if (rows.empty() && !r.hasElem) bad("frame " + std::to_string(r.frame) + " has one node (a rod needs two)");
    if (r.node != static_cast<int>(rows.size())) bad("node " + std::to_string(r.node) + " out of order");
    rows.push_back(r);
  }
  if (!rows.empty() && rows.back().hasElem) throw SceneError(path.string() + ": truncated (last frame incomplete)");
  flush();
  if (out.empty()) throw SceneError(path.string() + ": no frames");
  return out;
}

VtkSeriesWriter::VtkSeriesWriter(const fs::path& runDir) : dir_(runDir) {
  std::error_code ec;
  fs::create_directories(dir_ / "vtk", ec);
  if (ec) throw RunError("cannot create " + (dir_ / "vtk").string() + ": " + ec.message());
}

VtkSeriesWriter::VtkSeriesWriter(const fs::path& runDir, std::vector<std::pair<double, std::string>> entries)
    : VtkSeriesWriter(runDir) {
  entries_ = std::move(entries);
}

namespace {
// VTK's appended binary data with zlib (vtkZLibDataCompressor, header_type UInt64): each array is a
// header of UInt64s (number of blocks, uncompressed block size, uncompressed size of the last block or 0
// when it is full, compressed size of each block) followed by the blocks, each compressed on its own
constexpr std::size_t kVtkBlock = 32768;

class VtkAppended {
 public:
  // compresses an array; returns its offset in the appended data (what a DataArray's offset= says)
  std::size_t add(const void* data, std::size_t bytes) {
    const std::size_t offset = data_.size();
    const std::size_t blocks = (bytes + kVtkBlock - 1) / kVtkBlock;
    std::vector<std::uint64_t> head{blocks, kVtkBlock, bytes % kVtkBlock};
    std::string body;
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < blocks; ++k) {
      const std::size_t n = std::min(kVtkBlock, bytes - k * kVtkBlock);
      uLongf len = compressBound(static_cast<uLong>(n));
      zbuf_.resize(len);
      if (compress2(zbuf_.data(), &len, p + k * kVtkBlock, static_cast<uLong>(n), Z_DEFAULT_COMPRESSION) != Z_OK)
        throw RunError("zlib: cannot compress a ParaView array");
      head.push_back(len);
      body.append(reinterpret_cast<const char*>(zbuf_.data()), len);
    }
    data_.append(reinterpret_cast<const char*>(head.data()), head.size() * sizeof(std::uint64_t));
    data_ += body;
    return offset;
  }
  const std::string& data() const { return data_; }

 private:
  std::string data_;
  std::vector<Bytef> zbuf_;
};
}  // namespace

void VtkSeriesWriter::add(const Snapshot& s) {
  char name[64];
  std::snprintf(name, sizeof name, "vtk/step_%06d.vtp", s.step);
  const int n = s.elements(), nn = n + 1;
  // the arrays, in ParaView's units (mm) and layout (components interleaved)
  VtkAppended a;
  std::vector<double> pts(static_cast<std::size_t>(3 * nn));
  for (int i = 0; i < nn; ++i)
    for (int d = 0; d < 3; ++d) pts[static_cast<std::size_t>(3 * i + d)] = s.x(d, i) / units::mm;
  std::vector<std::int32_t> conn(static_cast<std::size_t>(2 * n)), offs(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    conn[static_cast<std::size_t>(2 * i)] = i;
    conn[static_cast<std::size_t>(2 * i + 1)] = i + 1;
    offs[static_cast<std::size_t>(i)] = 2 * (i + 1);
  }
  std::vector<double> rad(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) rad[static_cast<std::size_t>(i)] = s.radius[i] / units::mm;
  const std::size_t oPts = a.add(pts.data(), pts.size() * sizeof(double));
  const std::size_t oConn = a.add(conn.data(), conn.size() * sizeof(std::int32_t));
  const std::size_t oOffs = a.add(offs.data(), offs.size() * sizeof(std::int32_t));
  const std::size_t oRad = a.add(rad.data(), rad.size() * sizeof(double));
  const std::size_t oD1 = a.add(s.d1.data(), static_cast<std::size_t>(s.d1.size()) * sizeof(double));
  const std::size_t oD3 = a.add(s.d3.data(), static_cast<std::size_t>(s.d3.size()) * sizeof(double));
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
    << "<PolyData>\n<Piece NumberOfPoints=\"" << nn << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << n
    << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<Points>\n"
    << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" << oPts << "\"/>\n"
    << "</Points>\n<Lines>\n"
    << "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"appended\" offset=\"" << oConn << "\"/>\n"
    << "<DataArray type=\"Int32\" Name=\"offsets\" format=\"appended\" offset=\"" << oOffs << "\"/>\n"
    << "</Lines>\n<CellData Scalars=\"radius_mm\">\n"
    << "<DataArray type=\"Float64\" Name=\"radius_mm\" format=\"appended\" offset=\"" << oRad << "\"/>\n"
    << "<DataArray type=\"Float64\" Name=\"d1\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" << oD1 << "\"/>\n"
    << "<DataArray type=\"Float64\" Name=\"d3\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" << oD3 << "\"/>\n"
    << "</CellData>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
  std::string text = o.str();
  text += a.data();
  text += "\n</AppendedData>\n</VTKFile>\n";
  writeFileAtomic(dir_ / name, text);
  entries_.emplace_back(s.timeH, name);
}

void VtkSeriesWriter::close() {
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, f] : entries_) o << "<DataSet timestep=\"" << fmt(t) << "\" file=\"" << f << "\"/>\n";
  o << "</Collection>\n</VTKFile>\n";
  writeFileAtomic(dir_ / "trajectory.pvd", o.str());
}

Json& Json::num(const std::string& key, double v) {
  items_.push_back({key, std::isfinite(v) ? fmt(v) : "null", nullptr});
  return *this;
}
Json& Json::integer(const std::string& key, long long v) {
  items_.push_back({key, std::to_string(v), nullptr});
  return *this;
}
Json& Json::str(const std::string& key, const std::string& v) {
  items_.push_back({key, jsonEscape(v), nullptr});
  return *this;
}
Json& Json::boolean(const std::string& key, bool v) {
  items_.push_back({key, v ? "true" : "false", nullptr});
  return *this;
}
Json& Json::object(const std::string& key, const Json& v) {
  items_.push_back({key, "", std::make_shared<Json>(v)});
  return *this;
}
std::string Json::dump(int indent) const {
  const std::string pad(static_cast<size_t>(indent + 2), ' ');
  std::string o = "{\n";
  for (size_t i = 0; i < items_.size(); ++i) {
    o += pad + jsonEscape(items_[i].key) + ": " + (items_[i].child ? items_[i].child->dump(indent + 2) : items_[i].raw);
    o += i + 1 < items_.size() ? ",\n" : "\n";
  }
  return o + std::string(static_cast<size_t>(indent), ' ') + "}";
}

Json theoryJson(const Theory& t) {
  Json j;
  j.num("effective_gain_beta_Lgz_over_R", t.effectiveGain)
      .num("T0_h", t.T0 / units::hour)
      .num("max_kappa_per_mm_eq8", t.maxKappa * units::mm)
      .num("wavelength_mm_eq9", t.wavelength / units::mm)
      .num("amplitude_mm_eq10", t.amplitude / units::mm)
      .num("alpha_straight_to_waving_deg_eq12", t.alphaStraightToWave / units::deg)
      .num("alpha_waving_to_coiling_deg_eq13", t.alphaWaveToCoil / units::deg)
      .num("omega_per_h_eq5", t.omega * units::hour)
      .num("omega_T0", t.omegaT0)
      .num("skew_deg_eq14_small_omegaT0", t.skewSmall / units::deg)
      .num("skew_deg_eq15_large_omegaT0", t.skewLarge / units::deg);
  return j;
}

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

}  // namespace rootsim
