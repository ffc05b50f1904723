// trajectory.csv and trajectory.bin: writers and the reader (trajectory.hpp).
#include "rootsim/trajectory.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

#include "rootsim/csv.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim {

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
    o << frames_ << ',' << s.step << ',' << numberText(s.timeH) << ',' << i;
    for (int d = 0; d < 3; ++d) o << ',' << numberText(s.x(d, i) / units::mm);
    if (i < n) {
      for (int d = 0; d < 3; ++d) o << ',' << numberText(s.d1(d, i));
      for (int d = 0; d < 3; ++d) o << ',' << numberText(s.d3(d, i));
      o << ',' << numberText(s.radius[i] / units::mm);
    } else {
      o << ",,,,,,,";
    }
    o << ',' << (k0 ? numberText(s.kappa0[i] * units::mm) : "") << ',' << (pf ? numberText(s.plateForce[i]) : "");
    for (int c = 0; c < 3; ++c) o << ',' << (cf ? numberText(s.contactForce(c, i)) : "");
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
  return std::string(1, axis) + "_mm = " + numberText(v) + " is outside -" + numberText(kMaxTrajectoryCoordMm) + " .. " +
         numberText(kMaxTrajectoryCoordMm) + " mm (positions are bounded to |x|, |y|, |z| <= 10 m)";
}
std::string trajectoryRadiusBound(double r) {
  return "radius_mm = " + numberText(r) + " is above " + numberText(kMaxTrajectoryRadiusMm) + " mm (radii are bounded to 0.1 m)";
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
  std::vector<std::string> f;
  while (readCsvRecord(in, f, lineNo, path.string())) {
    if (f.size() == 1 && f[0].empty()) continue;  // an empty line
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

}  // namespace rootsim
