// The ParaView files (vtk.hpp): zlib-compressed VTK XML PolyData.
#include "rootsim/vtk.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

#include "rootsim/errors.hpp"
#include "rootsim/node_fields.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
// the opening of a ParaView polyline file: the centreline nodes [mm] joined by one line per element; the
// caller adds its point or cell data and closes with vtpClose()
void vtpPolyline(std::ostream& o, const Eigen::Matrix3Xd& x) {
  const long nn = x.cols(), n = nn - 1;
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<PolyData>\n<Piece NumberOfPoints=\"" << nn << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << n
    << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<Points>\n"
    << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (long i = 0; i < nn; ++i) o << numberText(x(0, i) / units::mm) << ' ' << numberText(x(1, i) / units::mm) << ' ' << numberText(x(2, i) / units::mm) << '\n';
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
      o << numberText(m.modes[q][6 * i]) << ' ' << numberText(m.modes[q][6 * i + 1]) << ' ' << numberText(m.modes[q][6 * i + 2]) << '\n';
    o << "</DataArray>\n";
  }
  o << "</PointData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  return o.str();
}

VtkSeriesWriter::VtkSeriesWriter(const fs::path& runDir, const SceneInfo& info) : dir_(runDir), info_(info) {
  std::error_code ec;
  fs::create_directories(dir_ / "vtk", ec);
  if (ec) throw RunError("cannot create " + (dir_ / "vtk").string() + ": " + ec.message());
}

VtkSeriesWriter::VtkSeriesWriter(const fs::path& runDir, const SceneInfo& info,
                                 std::vector<std::pair<double, std::string>> entries)
    : VtkSeriesWriter(runDir, info) {
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

namespace {
// a DataArray element of appended data
struct VtkArrayRef {
  std::string name;
  const char* type;  // "Float64", "Int32", "UInt8"
  int components;
  std::size_t offset;
};
void vtkArrayTag(std::ostream& o, const VtkArrayRef& a) {
  o << "<DataArray type=\"" << a.type << "\"";
  if (!a.name.empty()) o << " Name=\"" << a.name << "\"";
  if (a.components != 1) o << " NumberOfComponents=\"" << a.components << "\"";
  o << " format=\"appended\" offset=\"" << a.offset << "\"/>\n";
}
std::string vtkHead() {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n";
}
template <class T>
std::size_t addArray(VtkAppended& a, const std::vector<T>& v) {
  return a.add(v.data(), v.size() * sizeof(T));
}
std::size_t addArray(VtkAppended& a, const Eigen::Matrix3Xd& m) {
  return a.add(m.data(), static_cast<std::size_t>(m.size()) * sizeof(double));
}
std::size_t addArray(VtkAppended& a, const Eigen::VectorXd& v) {
  return a.add(v.data(), static_cast<std::size_t>(v.size()) * sizeof(double));
}
}  // namespace

std::string snapshotVtp(const Snapshot& s, const SceneInfo& info) {
  const int n = s.elements(), nn = n + 1;
  const double mm = units::mm;
  // the arrays, in ParaView's units (mm) and layout (components interleaved)
  VtkAppended a;
  std::vector<double> pts(static_cast<std::size_t>(3 * nn));
  for (int i = 0; i < nn; ++i)
    for (int d = 0; d < 3; ++d) pts[static_cast<std::size_t>(3 * i + d)] = s.x(d, i) / mm;
  std::vector<std::int32_t> conn(static_cast<std::size_t>(2 * n)), offs(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    conn[static_cast<std::size_t>(2 * i)] = i;
    conn[static_cast<std::size_t>(2 * i + 1)] = i + 1;
    offs[static_cast<std::size_t>(i)] = 2 * (i + 1);
  }
  std::vector<double> rad(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) rad[static_cast<std::size_t>(i)] = s.radius[i] / mm;
  const std::size_t oPts = addArray(a, pts), oConn = addArray(a, conn), oOffs = addArray(a, offs);

  // point data (docs/paraview.md, Point data): the material frame at the nodes, its angle, the strains,
  // the intrinsic curvature, the growth zone, the contact forces
  std::vector<VtkArrayRef> point;
  const std::vector<NodeFrame> frames = nodeFrames(s);
  const PlateFrame plate = PlateFrame::tilted(info.alphaDeg * units::deg);
  Eigen::Matrix3Xd d1(3, nn), d2(3, nn), d3(3, nn);
  Eigen::VectorXd nodeRadius(nn), angle(nn);
  for (int i = 0; i < nn; ++i) {
    const NodeFrame& f = frames[static_cast<std::size_t>(i)];
    d1.col(i) = f.d1, d2.col(i) = f.d2, d3.col(i) = f.t;
    nodeRadius[i] = f.radius / mm;
    angle[i] = materialAngle(f.t, f.d1, plate) / units::deg;
  }
  Eigen::VectorXd curvature(std::max(n - 1, 0)), twist(std::max(n - 1, 0));
  const std::vector<VoronoiBend> bends = voronoiBends(s);
  for (int j = 0; j + 1 < n; ++j) {
    const VoronoiBend& b = bends[static_cast<std::size_t>(j)];
    const double perMm = mm / std::max(b.length, 1e-300);
    curvature[j] = std::hypot(b.kappa.x(), b.kappa.y()) * perMm;
    twist[j] = b.kappa.z() * perMm;
  }
  auto pointArray = [&](const std::string& name, const auto& values, int components) {
    point.push_back({name, "Float64", components, addArray(a, values)});
  };
  pointArray("radius_mm", nodeRadius, 1);
  pointArray("d1", d1, 3);
  pointArray("d2", d2, 3);
  pointArray("d3", d3, 3);
  pointArray("material_angle_deg", angle, 1);
  pointArray("curvature_per_mm", voronoiToNodes(curvature, n), 1);
  pointArray("twist_rad_per_mm", voronoiToNodes(twist, n), 1);
  if (s.kappa0.size() == nn) pointArray("kappa0_per_mm", Eigen::VectorXd(s.kappa0 * mm), 1);
  pointArray("stretch", nodeStretch(s, info.radius), 1);
  {
    const Eigen::VectorXd zone = growthZoneNodes(s, info.radius, info.zoneLength);
    std::vector<std::uint8_t> flag(static_cast<std::size_t>(nn));
    for (int i = 0; i < nn; ++i) flag[static_cast<std::size_t>(i)] = zone[i] > 0 ? 1 : 0;
    point.push_back({"growth_zone", "UInt8", 1, addArray(a, flag)});
  }
  if (s.plateForce.size() == nn) pointArray("plate_force_n", s.plateForce, 1);
  if (s.contactForce.cols() == nn) {
    pointArray("contact_plate_n", Eigen::VectorXd(s.contactForce.row(0).transpose()), 1);
    pointArray("contact_self_n", Eigen::VectorXd(s.contactForce.row(1).transpose()), 1);
    pointArray("contact_obstacle_n", Eigen::VectorXd(s.contactForce.row(2).transpose()), 1);
  }

  // cell data, per element: the radius and the directors as the simulation has them
  const std::vector<VtkArrayRef> cell{{"radius_mm", "Float64", 1, addArray(a, rad)},
                                      {"d1", "Float64", 3, addArray(a, s.d1)},
                                      {"d3", "Float64", 3, addArray(a, s.d3)}};
  std::ostringstream o;
  o << vtkHead() << "<PolyData>\n<Piece NumberOfPoints=\"" << nn << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << n
    << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<Points>\n";
  vtkArrayTag(o, {"", "Float64", 3, oPts});
  o << "</Points>\n<Lines>\n";
  vtkArrayTag(o, {"connectivity", "Int32", 1, oConn});
  vtkArrayTag(o, {"offsets", "Int32", 1, oOffs});
  o << "</Lines>\n<PointData Scalars=\"radius_mm\" Vectors=\"d1\">\n";
  for (const VtkArrayRef& r : point) vtkArrayTag(o, r);
  o << "</PointData>\n<CellData Scalars=\"radius_mm\">\n";
  for (const VtkArrayRef& r : cell) vtkArrayTag(o, r);
  o << "</CellData>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
  std::string text = o.str();
  text += a.data();
  text += "\n</AppendedData>\n</VTKFile>\n";
  return text;
}

std::string vtpFileName(const Snapshot& s) {
  char name[64];
  std::snprintf(name, sizeof name, "step_%06d.vtp", s.step);
  return name;
}

std::string pvdText(const std::vector<std::pair<double, std::string>>& entries) {
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, f] : entries) o << "<DataSet timestep=\"" << numberText(t) << "\" file=\"" << f << "\"/>\n";
  o << "</Collection>\n</VTKFile>\n";
  return o.str();
}

std::string partsPvdText(const std::vector<PvdPart>& parts) {
  std::string o = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (std::size_t r = 0; r < parts.size(); ++r)
    for (const auto& [t, file] : parts[r].entries)
      o += "  <DataSet timestep=\"" + shortestNumber(t) + "\" part=\"" + std::to_string(r) + "\" name=\"" + parts[r].name +
           "\" file=\"" + parts[r].folder + "/" + file + "\"/>\n";
  o += "</Collection>\n</VTKFile>\n";
  return o;
}

std::array<double, 4> plateExtentMm(const SceneInfo& info, const std::vector<Snapshot>& snaps) {
  const PlateFrame plate = PlateFrame::tilted(info.alphaDeg * units::deg);
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;  // the seed's foot (the origin) is always on it
  auto cover = [&](double u, double v, double r) {
    u0 = std::min(u0, u - r), u1 = std::max(u1, u + r);
    v0 = std::min(v0, v - r), v1 = std::max(v1, v + r);
  };
  for (const Snapshot& s : snaps)
    for (int i = 0; i < s.x.cols(); ++i) {
      const Eigen::Vector3d p = plate.toPlateMm(s.x.col(i));
      cover(p.x(), p.y(), 0);
    }
  for (const SceneInfo::ObstacleShape& o : info.obstacles) {
    cover(o.fromU, o.fromV, o.radiusMm);
    cover(o.toU, o.toV, o.radiusMm);
  }
  constexpr double kMarginMm = 2.0;
  return {std::floor(u0 - kMarginMm), std::ceil(u1 + kMarginMm), std::floor(v0 - kMarginMm), std::ceil(v1 + kMarginMm)};
}

std::string plateVtp(const SceneInfo& info, const std::vector<Snapshot>& snaps) {
  const PlateFrame plate = PlateFrame::tilted(info.alphaDeg * units::deg);
  // a point of the top view's plate coordinates (u lateral, v uphill, w height) [mm] in the lab [mm]
  std::vector<double> pts;
  auto point = [&](double u, double v, double w) {
    const Eigen::Vector3d p = u * plate.lateral + v * plate.uphill() + w * plate.normal;
    pts.insert(pts.end(), {p.x(), p.y(), p.z()});
    return static_cast<std::int32_t>(pts.size() / 3 - 1);
  };
  std::vector<std::int32_t> lineConn, lineOffs, polyConn, polyOffs;
  std::vector<std::uint8_t> linePart, polyPart;
  auto line = [&](std::int32_t a, std::int32_t b) {
    lineConn.insert(lineConn.end(), {a, b});
    lineOffs.push_back(static_cast<std::int32_t>(lineConn.size()));
    linePart.push_back(kPlatePartGrid);
  };
  auto poly = [&](const std::vector<std::int32_t>& ids, std::uint8_t part) {
    polyConn.insert(polyConn.end(), ids.begin(), ids.end());
    polyOffs.push_back(static_cast<std::int32_t>(polyConn.size()));
    polyPart.push_back(part);
  };
  if (info.plate) {
    const auto [u0, u1, v0, v1] = plateExtentMm(info, snaps);
    poly({point(u0, v0, 0), point(u1, v0, 0), point(u1, v1, 0), point(u0, v1, 0)}, kPlatePartPlate);
    // the 1 mm grid; the extent is whole millimetres, so the lines meet the plate's edges
    for (double u = u0; u <= u1 + 1e-9; u += 1.0) line(point(u, v0, 0), point(u, v1, 0));
    for (double v = v0; v <= v1 + 1e-9; v += 1.0) line(point(u0, v, 0), point(u1, v, 0));
  }
  // obstacles: prisms of kObstacleHeightMm over their outline (a peg's circle; a wall's segment with
  // rounded ends), side quads and a top
  for (const SceneInfo::ObstacleShape& o : info.obstacles) {
    Eigen::Vector2d from(o.fromU, o.fromV), to(o.toU, o.toV), d(1, 0);
    if ((to - from).norm() > 0) d = (to - from).normalized();
    const Eigen::Vector2d q(-d.y(), d.x());
    constexpr int kHalf = 16;  // outline points on each rounded end
    std::vector<Eigen::Vector2d> outline;
    for (int end = 0; end < 2; ++end)
      for (int k = 0; k <= kHalf; ++k) {
        const double th = units::pi * (end - 0.5 + static_cast<double>(k) / kHalf);
        outline.push_back((end == 0 ? to : from) + o.radiusMm * (std::cos(th) * d + std::sin(th) * q));
      }
    const auto m = static_cast<std::int32_t>(outline.size());
    const std::int32_t bottom = static_cast<std::int32_t>(pts.size() / 3);
    for (const auto& p : outline) point(p.x(), p.y(), 0);
    for (const auto& p : outline) point(p.x(), p.y(), kObstacleHeightMm);
    for (std::int32_t k = 0; k < m; ++k) {
      const std::int32_t k1 = (k + 1) % m;
      poly({bottom + k, bottom + k1, bottom + m + k1, bottom + m + k}, kPlatePartObstacle);
    }
    std::vector<std::int32_t> top;
    for (std::int32_t k = 0; k < m; ++k) top.push_back(bottom + m + k);
    poly(top, kPlatePartObstacle);
  }

  VtkAppended a;
  const std::size_t oPts = addArray(a, pts);
  std::ostringstream o;
  o << vtkHead() << "<PolyData>\n<Piece NumberOfPoints=\"" << pts.size() / 3
    << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << lineOffs.size() << "\" NumberOfStrips=\"0\" NumberOfPolys=\""
    << polyOffs.size() << "\">\n<Points>\n";
  vtkArrayTag(o, {"", "Float64", 3, oPts});
  o << "</Points>\n";
  if (!lineOffs.empty()) {
    o << "<Lines>\n";
    vtkArrayTag(o, {"connectivity", "Int32", 1, addArray(a, lineConn)});
    vtkArrayTag(o, {"offsets", "Int32", 1, addArray(a, lineOffs)});
    o << "</Lines>\n";
  }
  if (!polyOffs.empty()) {
    o << "<Polys>\n";
    vtkArrayTag(o, {"connectivity", "Int32", 1, addArray(a, polyConn)});
    vtkArrayTag(o, {"offsets", "Int32", 1, addArray(a, polyOffs)});
    o << "</Polys>\n";
  }
  // VTK numbers the lines before the polygons
  std::vector<std::uint8_t> part = linePart;
  part.insert(part.end(), polyPart.begin(), polyPart.end());
  o << "<CellData Scalars=\"part\">\n";
  vtkArrayTag(o, {"part", "UInt8", 1, addArray(a, part)});
  o << "</CellData>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
  std::string text = o.str();
  text += a.data();
  text += "\n</AppendedData>\n</VTKFile>\n";
  return text;
}

void VtkSeriesWriter::add(const Snapshot& s) {
  const std::string name = "vtk/" + vtpFileName(s);
  writeFileAtomic(dir_ / name, snapshotVtp(s, info_));
  entries_.emplace_back(s.timeH, name);
}

void VtkSeriesWriter::close() { writeFileAtomic(dir_ / "trajectory.pvd", pvdText(entries_)); }

}  // namespace rootsim
