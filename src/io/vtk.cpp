// The ParaView files (vtk.hpp): zlib-compressed VTK XML PolyData.
#include "rootsim/vtk.hpp"

#include <zlib.h>

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
  for (const auto& [t, f] : entries_) o << "<DataSet timestep=\"" << numberText(t) << "\" file=\"" << f << "\"/>\n";
  o << "</Collection>\n</VTKFile>\n";
  writeFileAtomic(dir_ / "trajectory.pvd", o.str());
}

}  // namespace rootsim
