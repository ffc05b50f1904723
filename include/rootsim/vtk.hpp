#pragma once
// The ParaView files of a run (docs/outputs.md): vtk/step_NNNNNN.vtp and trajectory.pvd, and modes.vtp.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <utility>

#include "rootsim/run_dir.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/stability.hpp"

namespace rootsim {

// modes.vtp of `rootsim modes`: the centreline with one point-data vector per mode (modes.csv: csv.hpp)
std::string modesVtp(const RodState& s, const StiffnessModes& m);

// The ParaView file of one snapshot (VTK XML PolyData, binary appended data compressed with zlib:
// compressor="vtkZLibDataCompressor", header_type="UInt64"; ParaView and VTK's readers read it): the
// centreline nodes [mm, lab] joined by one line per element; point data per node (the material frame
// d1, d2, d3 averaged at the node, radius, material-frame angle, curvature, twist, kappa0, stretch,
// growth zone, plate and contact forces: docs/paraview.md, Point data); cell data per element (radius,
// d1, d3 as the simulation has them). info gives the plate tilt, R and Lgz.
std::string snapshotVtp(const Snapshot& s, const SceneInfo& info);
// its file name: step_NNNNNN.vtp (the growth step)
std::string vtpFileName(const Snapshot& s);
// a ParaView collection (.pvd) of (time_h, file) entries: the time slider steps through them in hours
std::string pvdText(const std::vector<std::pair<double, std::string>>& entries);
// several series as the parts of one collection (a plate's plate.pvd: a part per root, named after it),
// each part's files (entries as pvdText's) under its folder
struct PvdPart {
  std::string name, folder;
  std::vector<std::pair<double, std::string>> entries;
};
std::string partsPvdText(const std::vector<PvdPart>& parts);

// plate.vtp's cells carry a cell-data array "part": which piece each cell is
inline constexpr std::uint8_t kPlatePartPlate = 0;     // the plate's rectangle (one polygon)
inline constexpr std::uint8_t kPlatePartGrid = 1;      // a line of the 1 mm grid
inline constexpr std::uint8_t kPlatePartObstacle = 2;  // a face of an obstacle's prism
// obstacles are infinitely tall in the model; plate.vtp draws them this high above the plate [mm]
inline constexpr double kObstacleHeightMm = 1.0;
// the plate's extent in the top view's plate coordinates [mm]: {u0, u1, v0, v1} (u lateral, v uphill),
// whole millimetres covering every node of the snapshots and every obstacle with 2 mm to spare
std::array<double, 4> plateExtentMm(const SceneInfo& info, const std::vector<Snapshot>& snaps);
// plate.vtp: the plate (through the origin, normal PlateFrame::normal) as a rectangle over
// plateExtentMm with a 1 mm grid of lines on it, and the obstacles as prisms, in the lab frame [mm];
// no plate when info.plate is false (obstacles only)
std::string plateVtp(const SceneInfo& info, const std::vector<Snapshot>& snaps);

// A run's ParaView series: vtk/step_NNNNNN.vtp (snapshotVtp) and trajectory.pvd
class VtkSeriesWriter {
 public:
  VtkSeriesWriter(const std::filesystem::path& runDir, const SceneInfo& info);
  // continues a killed run's series with the entries it had written (a checkpoint's)
  VtkSeriesWriter(const std::filesystem::path& runDir, const SceneInfo& info,
                  std::vector<std::pair<double, std::string>> entries);
  void add(const Snapshot& s);
  void close();
  // trajectory.pvd's entries so far: (time_h, file)
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }

 private:
  std::filesystem::path dir_;
  SceneInfo info_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace rootsim
