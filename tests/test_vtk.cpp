// The ParaView files (src/io/vtk.cpp): zlib-compressed binary VTK XML PolyData that decodes to the
// run's snapshots, trajectory.bin and trajectory.csv agreeing with them.
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rootsim/outputs.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/units.hpp"
#include "test_support.hpp"
#include "vtk_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
using rootsim::test::kSets;
using rootsim::test::runScene;
using rootsim::test::slurp;
using rootsim::test::as;
using rootsim::test::vtkArray;
using rootsim::test::vtkOffset;
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("vtk", name); }
}  // namespace

TEST_CASE("ParaView files are zlib-compressed binary that decodes to the snapshot and trajectory.bin reads as the CSV") {
  const fs::path d = scratch("formats");
  const fs::path out = d / "r";
  runScene(out, kSets);
  const std::vector<rootsim::Snapshot> csv = rootsim::readTrajectory(out / "trajectory.csv");
  const std::vector<rootsim::Snapshot> bin = rootsim::readTrajectory(out / "trajectory.bin");
  REQUIRE(csv.size() == 13);
  REQUIRE(bin.size() == csv.size());
  CHECK(rootsim::trajectoryPath(out) == out / "trajectory.bin");
  // bit for bit: the renderer sees the same snapshots from either file
  for (std::size_t f = 0; f < csv.size(); ++f) {
    CAPTURE(f);
    const rootsim::Snapshot &a = csv[f], &b = bin[f];
    CHECK(a.step == b.step);
    CHECK(a.timeH == b.timeH);
    CHECK(a.x == b.x);
    CHECK(a.d1 == b.d1);
    CHECK(a.d3 == b.d3);
    CHECK(a.radius == b.radius);
    CHECK(a.kappa0 == b.kappa0);
    CHECK(a.plateForce == b.plateForce);
    CHECK(a.contactForce == b.contactForce);
  }
  CHECK(fs::file_size(out / "trajectory.bin") * 2 < fs::file_size(out / "trajectory.csv"));

  // the last ParaView file against the last snapshot
  const rootsim::Snapshot& s = bin.back();
  const std::string vtp = slurp(out / "vtk" / "step_000120.vtp");
  CHECK(vtp.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos);
  CHECK(vtp.find("header_type=\"UInt64\"") != std::string::npos);
  CHECK(vtp.find("format=\"ascii\"") == std::string::npos);
  const int n = s.elements();
  CHECK(vtp.find("NumberOfPoints=\"" + std::to_string(n + 1) + "\"") != std::string::npos);
  const auto pts = as<double>(vtkArray(vtp, vtkOffset(vtp, "")));
  REQUIRE(pts.size() == static_cast<std::size_t>(3 * (n + 1)));
  for (int i = 0; i <= n; ++i)
    for (int c = 0; c < 3; ++c) CHECK(pts[static_cast<std::size_t>(3 * i + c)] * rootsim::units::mm == s.x(c, i));
  const auto conn = as<std::int32_t>(vtkArray(vtp, vtkOffset(vtp, "connectivity")));
  const auto offs = as<std::int32_t>(vtkArray(vtp, vtkOffset(vtp, "offsets")));
  REQUIRE(conn.size() == static_cast<std::size_t>(2 * n));
  REQUIRE(offs.size() == static_cast<std::size_t>(n));
  CHECK(conn[0] == 0);
  CHECK(conn.back() == n);
  CHECK(offs.back() == 2 * n);
  const auto rad = as<double>(vtkArray(vtp, vtkOffset(vtp, "radius_mm", "<CellData")));
  const auto d1 = as<double>(vtkArray(vtp, vtkOffset(vtp, "d1", "<CellData")));
  const auto d3 = as<double>(vtkArray(vtp, vtkOffset(vtp, "d3", "<CellData")));
  REQUIRE(rad.size() == static_cast<std::size_t>(n));
  REQUIRE(d1.size() == static_cast<std::size_t>(3 * n));
  REQUIRE(d3.size() == static_cast<std::size_t>(3 * n));
  for (int i = 0; i < n; ++i) {
    CHECK(rad[static_cast<std::size_t>(i)] * rootsim::units::mm == s.radius[i]);
    for (int c = 0; c < 3; ++c) {
      CHECK(d1[static_cast<std::size_t>(3 * i + c)] == s.d1(c, i));
      CHECK(d3[static_cast<std::size_t>(3 * i + c)] == s.d3(c, i));
    }
  }
  fs::remove_all(d);
}

TEST_CASE("a collection of parts lists each part's snapshots under its folder, numbered and named after it") {
  const std::vector<PvdPart> parts = {{"A", "roots/A", {{0.0, "vtk/step_000000.vtp"}, {0.5, "vtk/step_000010.vtp"}}},
                                      {"A.1", "roots/A.1", {{0.5, "vtk/step_000010.vtp"}}}};
  CHECK(partsPvdText(parts) ==
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n"
        "  <DataSet timestep=\"0.0\" part=\"0\" name=\"A\" file=\"roots/A/vtk/step_000000.vtp\"/>\n"
        "  <DataSet timestep=\"0.5\" part=\"0\" name=\"A\" file=\"roots/A/vtk/step_000010.vtp\"/>\n"
        "  <DataSet timestep=\"0.5\" part=\"1\" name=\"A.1\" file=\"roots/A.1/vtk/step_000010.vtp\"/>\n"
        "</Collection>\n</VTKFile>\n");
  CHECK(partsPvdText({}) == pvdText({}));
}
