// the ParaView files (src/io/vtk.cpp's snapshotVtp and plateVtp, src/io/paraview.cpp's folder and script):
// the point data of a real run decoded and checked against its snapshots, the plate and its grid, the
// folder `export --paraview` writes and its script
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "rootsim/environment.hpp"
#include "rootsim/node_fields.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/signature.hpp"
#include "rootsim/write_rule.hpp"
#include "rootsim/units.hpp"
#include "test_support.hpp"
#include "vtk_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
namespace fs = std::filesystem;
using rootsim::test::as;
using rootsim::test::kScene;
using rootsim::test::kSets;
using rootsim::test::Result;
using rootsim::test::run;
using rootsim::test::slurp;
using rootsim::test::vtkArray;
using rootsim::test::vtkOffset;

namespace {
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("paraview", name); }

// a point-data array of a .vtp
template <class T>
std::vector<T> pointArray(const std::string& vtp, const std::string& name) {
  return as<T>(vtkArray(vtp, vtkOffset(vtp, name, "<PointData")));
}
Eigen::Vector3d col3(const std::vector<double>& v, int i) {
  return {v[static_cast<size_t>(3 * i)], v[static_cast<size_t>(3 * i + 1)], v[static_cast<size_t>(3 * i + 2)]};
}
}  // namespace

TEST_CASE("ParaView point data of a real run: frame and angle and stretch and growth zone and kappa0 and forces per node") {
  const fs::path d = scratch("points");
  const fs::path out = d / "r";
  REQUIRE(run("run " + kScene + kSets + " --out " + out.string()).code == 0);
  const SceneInfo info = sceneInfoOf(loadScene(kScene, {"growth.steps=120"}).model);
  const std::vector<Snapshot> snaps = readTrajectory(out / "trajectory.bin");
  REQUIRE(snaps.size() == 13);
  const PlateFrame plate = PlateFrame::tilted(info.alphaDeg * units::deg);
  int zoneSeen = 0;
  for (const Snapshot& s : {snaps[1], snaps.back()}) {
    CAPTURE(s.step);
    // the file of this snapshot as read back from trajectory.bin (what `export` writes), and the run's
    // own: one writer, so the same arrays, equal to round-off (trajectory.bin holds millimetres: a
    // snapshot read back may differ from the run's in the last bit)
    const std::string vtp = snapshotVtp(s, info);
    const std::string ran = slurp(out / "vtk" / vtpFileName(s));
    const std::regex tag("<DataArray type=\"(\\w+)\" Name=\"(\\w+)\"");
    std::vector<std::string> tags, ranTags;
    for (auto it = std::sregex_iterator(vtp.begin(), vtp.end(), tag); it != std::sregex_iterator(); ++it) tags.push_back(it->str());
    for (auto it = std::sregex_iterator(ran.begin(), ran.end(), tag); it != std::sregex_iterator(); ++it) ranTags.push_back(it->str());
    CHECK(tags == ranTags);
    for (const char* name : {"radius_mm", "d1", "d2", "d3", "material_angle_deg", "curvature_per_mm", "twist_rad_per_mm",
                             "kappa0_per_mm", "stretch", "plate_force_n", "contact_self_n"}) {
      CAPTURE(name);
      const auto a = pointArray<double>(vtp, name), b = pointArray<double>(ran, name);
      REQUIRE(a.size() == b.size());
      for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k] == doctest::Approx(b[k]).epsilon(1e-12).scale(1e-12));
    }
    const int n = s.elements(), nn = n + 1;
    const auto radius = pointArray<double>(vtp, "radius_mm");
    const auto d1 = pointArray<double>(vtp, "d1"), d2 = pointArray<double>(vtp, "d2"), d3 = pointArray<double>(vtp, "d3");
    const auto angle = pointArray<double>(vtp, "material_angle_deg");
    const auto curvature = pointArray<double>(vtp, "curvature_per_mm");
    const auto twist = pointArray<double>(vtp, "twist_rad_per_mm");
    const auto kappa0 = pointArray<double>(vtp, "kappa0_per_mm");
    const auto stretch = pointArray<double>(vtp, "stretch");
    const auto zone = pointArray<std::uint8_t>(vtp, "growth_zone");
    const auto plateForce = pointArray<double>(vtp, "plate_force_n");
    const auto cPlate = pointArray<double>(vtp, "contact_plate_n"), cSelf = pointArray<double>(vtp, "contact_self_n"),
               cObst = pointArray<double>(vtp, "contact_obstacle_n");
    for (const auto* a : {&radius, &angle, &curvature, &twist, &kappa0, &stretch, &plateForce, &cPlate, &cSelf, &cObst})
      REQUIRE(a->size() == static_cast<size_t>(nn));
    for (const auto* a : {&d1, &d2, &d3}) REQUIRE(a->size() == static_cast<size_t>(3 * nn));
    REQUIRE(zone.size() == static_cast<size_t>(nn));
    auto lambda = [&](int e) { return std::pow(info.radius / s.radius[e], 2); };
    for (int i = 0; i < nn; ++i) {
      CAPTURE(i);
      const Eigen::Vector3d a = col3(d1, i), b = col3(d2, i), t = col3(d3, i);
      // an orthonormal right-handed frame: d2 = d3 x d1
      CHECK(a.norm() == doctest::Approx(1).epsilon(1e-14));
      CHECK(t.norm() == doctest::Approx(1).epsilon(1e-14));
      CHECK(std::abs(a.dot(t)) < 1e-14);
      CHECK((b - t.cross(a)).norm() < 1e-14);
      // close to the adjacent elements' directors
      const int e = std::min(i, n - 1);
      CHECK(a.dot(s.d1.col(e)) > 0.99);
      CHECK(t.dot(s.d3.col(e)) > 0.99);
      // the radius and stretch (R / r)^2 of the adjacent elements, averaged
      const int ea = std::max(i - 1, 0), eb = std::min(i, n - 1);
      CHECK(radius[static_cast<size_t>(i)] == doctest::Approx(0.5 * (s.radius[ea] + s.radius[eb]) / units::mm).epsilon(1e-14));
      CHECK(stretch[static_cast<size_t>(i)] == doctest::Approx(0.5 * (lambda(ea) + lambda(eb))).epsilon(1e-14));
      // the angle turns the in-plate direction n x d3 (n: the plate normal made normal to d3) about d3
      // into d1
      const double phi = angle[static_cast<size_t>(i)] * units::deg;
      const Eigen::Vector3d ref = (plate.normal - plate.normal.dot(t) * t).normalized().cross(t);
      CHECK((std::cos(phi) * ref + std::sin(phi) * t.cross(ref) - a).norm() < 1e-12);
      CHECK(std::isfinite(curvature[static_cast<size_t>(i)]));
      CHECK(curvature[static_cast<size_t>(i)] >= 0);
      CHECK(kappa0[static_cast<size_t>(i)] == s.kappa0[i] * units::mm);
      CHECK(plateForce[static_cast<size_t>(i)] == s.plateForce[i]);
      CHECK(cPlate[static_cast<size_t>(i)] == s.contactForce(0, i));
      CHECK(cSelf[static_cast<size_t>(i)] == s.contactForce(1, i));
      CHECK(cObst[static_cast<size_t>(i)] == s.contactForce(2, i));
    }
    // the growth zone: the tip's nodes within Lgz of rest length (current length / stretch) of the tip
    double fromTip = 0;
    for (int i = n; i >= 0; --i) {
      if (i < n) fromTip += (s.x.col(i + 1) - s.x.col(i)).norm() / lambda(i);
      CHECK(zone[static_cast<size_t>(i)] == (fromTip <= info.zoneLength * (1 + 1e-9) ? 1 : 0));
      zoneSeen += zone[static_cast<size_t>(i)];
    }
    CHECK(zone.back() == 1);
    // the root is 1.1 mm long at first and grows: the base leaves the 1 mm zone
    CHECK(zone.front() == 0);
  }
  CHECK(zoneSeen > 4);
  fs::remove_all(d);
}

TEST_CASE("plate.vtp: the plate under every snapshot in whole millimetres with its 1 mm grid and the obstacles") {
  const fs::path d = scratch("plate");
  const fs::path out = d / "r";
  REQUIRE(run("run " + kScene + " --set growth.steps=60 --set output.every_steps=20 --quiet --out " + out.string()).code == 0);
  SceneInfo info = sceneInfoOf(loadScene(kScene, {}).model);
  const std::vector<Snapshot> snaps = readTrajectory(out / "trajectory.bin");
  const PlateFrame plate = PlateFrame::tilted(info.alphaDeg * units::deg);
  const auto [u0, u1, v0, v1] = plateExtentMm(info, snaps);
  for (double x : {u0, u1, v0, v1}) CHECK(x == std::round(x));
  for (const Snapshot& s : snaps)
    for (int i = 0; i < s.x.cols(); ++i) {
      const Eigen::Vector3d p = plate.toPlateMm(s.x.col(i));
      CHECK(p.x() >= u0 + 2);
      CHECK(p.x() <= u1 - 2);
      CHECK(p.y() >= v0 + 2);
      CHECK(p.y() <= v1 - 2);
    }
  // a peg beside the root and a wall below it widen the plate
  info.obstacles.push_back({true, u1 + 3, 0.5 * (v0 + v1), u1 + 3, 0.5 * (v0 + v1), 0.4});
  info.obstacles.push_back({false, u0 - 1, v0 - 1, u1, v0 - 1, 0.25});
  const auto e = plateExtentMm(info, snaps);
  CHECK(e[1] >= u1 + 3.4 + 2);
  CHECK(e[2] <= v0 - 1.25 - 2);
  const std::string vtp = plateVtp(info, snaps);
  const auto pts = as<double>(vtkArray(vtp, vtkOffset(vtp, "")));
  const auto part = as<std::uint8_t>(vtkArray(vtp, vtkOffset(vtp, "part", "<CellData")));
  const auto lineOffs = as<std::int32_t>(vtkArray(vtp, vtkOffset(vtp, "offsets", "<Lines")));
  const auto polyConn = as<std::int32_t>(vtkArray(vtp, vtkOffset(vtp, "connectivity", "<Polys")));
  const auto polyOffs = as<std::int32_t>(vtkArray(vtp, vtkOffset(vtp, "offsets", "<Polys")));
  // one grid line per millimetre each way, then the plate, then each obstacle's 34 sides and its top
  const std::size_t grid = static_cast<std::size_t>(e[1] - e[0] + 1 + e[3] - e[2] + 1);
  REQUIRE(lineOffs.size() == grid);
  REQUIRE(polyOffs.size() == 1 + 2 * 35);
  REQUIRE(part.size() == grid + polyOffs.size());
  for (std::size_t c = 0; c < part.size(); ++c)
    CHECK(part[c] == (c < grid ? kPlatePartGrid : c == grid ? kPlatePartPlate : kPlatePartObstacle));
  // the plate's corners are the extent's, in the plate through the origin; obstacles stand on it
  for (std::size_t k = 0; k < pts.size() / 3; ++k) {
    const Eigen::Vector3d p = plate.coords(Eigen::Vector3d(pts[3 * k], pts[3 * k + 1], pts[3 * k + 2]));
    CHECK(p.z() > -1e-12);
    CHECK(p.z() < kObstacleHeightMm + 1e-12);
  }
  const Eigen::Vector3d corner(pts[3 * static_cast<size_t>(polyConn[0])], pts[3 * static_cast<size_t>(polyConn[0]) + 1],
                               pts[3 * static_cast<size_t>(polyConn[0]) + 2]);
  ROOTSIM_CHECK_CLOSE(plate.toPlateMm(corner * units::mm).x(), e[0], kRoundoff);
  ROOTSIM_CHECK_CLOSE(plate.toPlateMm(corner * units::mm).y(), e[2], kRoundoff);
  // a free organ has no plate: the obstacles only
  info.plate = false;
  const std::string free = plateVtp(info, snaps);
  CHECK(free.find("NumberOfLines=\"0\"") != std::string::npos);
  CHECK(free.find("NumberOfPolys=\"70\"") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("the ParaView folder: a .vtp per snapshot and root.pvd in hours and plate.vtp and a Python script") {
  const fs::path d = scratch("folder");
  const fs::path out = d / "r";
  REQUIRE(run("run " + kScene + " --set growth.steps=60 --set output.every_steps=20 --quiet --out " + out.string()).code == 0);
  const SceneInfo info = sceneInfoOf(loadScene(kScene, {}).model);
  const std::vector<Snapshot> snaps = readTrajectory(out / "trajectory.bin");
  REQUIRE(snaps.size() == 4);
  const fs::path pv = d / "pv";
  fs::create_directories(pv);
  writeParaviewFiles(pv, snaps, info);
  std::vector<std::string> names;
  for (const auto& f : fs::directory_iterator(pv)) names.push_back(f.path().filename().string());
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"open_in_paraview.py", "plate.vtp", "root.pvd", "step_000000.vtp",
                                          "step_000020.vtp", "step_000040.vtp", "step_000060.vtp"});
  // every file is one the folder's write rule owns
  for (const std::string& n : names) CHECK(paraviewFolder().owns(pv, n));
  CHECK(!paraviewFolder().owns(pv, "notes.txt"));
  CHECK(!paraviewFolder().owns(pv, "step_12a.vtp"));
  const std::string pvd = slurp(pv / "root.pvd");
  for (const Snapshot& s : snaps) {
    CHECK(pvd.find("timestep=\"" + numberText(s.timeH) + "\" file=\"" + vtpFileName(s) + "\"") != std::string::npos);
    CHECK(slurp(pv / vtpFileName(s)) == snapshotVtp(s, info));
  }
  ROOTSIM_CHECK_CLOSE(snaps.back().timeH, 3.0, kRoundoff);  // 60 steps of 0.05 h
  // the script: this run's plate axes and extent filled in, the renderer's stripe rule, Python that compiles
  const std::string py = slurp(pv / "open_in_paraview.py");
  CHECK(py.find('@') == std::string::npos);
  CHECK(py.find(outputSignatureText()) != std::string::npos);
  const PlateFrame plate = PlateFrame::tilted(info.alphaDeg * units::deg);
  CHECK(py.find("PLATE_NORMAL = (" + numberText(plate.normal.x()) + ", " + numberText(plate.normal.y()) + ", " +
                numberText(plate.normal.z()) + ")") != std::string::npos);
  CHECK(py.find("STRIPE_COS = " + numberText(std::cos(38 * units::deg))) != std::string::npos);
  CHECK(py.find("dot(TubeNormals, d1)") != std::string::npos);
  // where ParaView's GUI (which gives a script no file name) finds the files
  CHECK(py.find("WRITTEN_TO = \"" + fs::absolute(pv).lexically_normal().string() + "\"\n") != std::string::npos);
  // (parsed, not compiled: nothing written into the folder)
  CHECK(rootsim::test::runBinary("python3", "-c 'import ast, sys; ast.parse(open(sys.argv[1]).read())' " +
                                                (pv / "open_in_paraview.py").string()).code == 0);
  // the same snapshots, the same bytes
  const fs::path again = d / "again";
  fs::create_directories(again);
  writeParaviewFiles(again, snaps, info, pv);
  CHECK(rootsim::test::fileTree(again) == rootsim::test::fileTree(pv));
  fs::remove_all(d);
}

TEST_CASE("export --paraview: every snapshot or one written whole and a user's folder never and rootsim's own only with --force") {
  const fs::path d = scratch("export");
  const fs::path out = d / "r";
  REQUIRE(run("run " + kScene + " --set growth.steps=60 --set output.every_steps=20 --quiet --out " + out.string()).code == 0);
  const fs::path pv = d / "pv";
  const std::string exportTo = "export " + out.string() + " --quiet --paraview ";
  REQUIRE(run(exportTo + pv.string()).code == 0);
  CHECK(fs::exists(pv / ".rootsim-paraview"));
  CHECK(!fs::exists(d / "pv.partial"));
  for (const char* f : {"root.pvd", "plate.vtp", "open_in_paraview.py", "step_000000.vtp", "step_000060.vtp"}) CHECK(fs::exists(pv / f));
  const auto before = rootsim::test::fileTree(pv);
  // rootsim's own folder: refused without --force (untouched), replaced whole with it (one snapshot now)
  Result r = run(exportTo + pv.string());
  CHECK(r.code == 2);
  CHECK(r.out.find("--paraview " + pv.string()) != std::string::npos);
  CHECK(rootsim::test::fileTree(pv) == before);
  REQUIRE(run(exportTo + pv.string() + " --force --at-h 1.1").code == 0);
  CHECK(fs::exists(pv / "step_000020.vtp"));
  CHECK(!fs::exists(pv / "step_000000.vtp"));
  CHECK(slurp(pv / "root.pvd").find("timestep=\"1\" file=\"step_000020.vtp\"") != std::string::npos);
  // a file the user added makes it theirs: refused even with --force, and kept
  { std::ofstream(pv / "notes.txt") << "mine"; }
  r = run(exportTo + pv.string() + " --force");
  CHECK(r.code == 2);
  CHECK(r.out.find("notes.txt") != std::string::npos);
  CHECK(slurp(pv / "notes.txt") == "mine");
  // a user's folder, a file, the run directory itself or a folder inside it: refused, nothing written
  const fs::path user = d / "user";
  fs::create_directories(user);
  { std::ofstream(user / "a.vtp") << "mine"; }
  { std::ofstream(d / "file") << "mine"; }
  for (const fs::path& p : {user, d / "file", out, out / "pv"}) {
    CAPTURE(p);
    r = run(exportTo + p.string() + " --force");
    CHECK(r.code == 2);
    CHECK(rootsim::test::oneLine(r.out.substr(0, r.out.size() - 1)));
  }
  CHECK(slurp(user / "a.vtp") == "mine");
  CHECK(slurp(d / "file") == "mine");
  CHECK(!fs::exists(out / "pv"));
  CHECK(!fs::exists(d / "user.partial"));
  fs::remove_all(d);
}
