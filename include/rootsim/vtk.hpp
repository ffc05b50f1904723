#pragma once
// The ParaView files of a run (docs/outputs.md): vtk/step_NNNNNN.vtp and trajectory.pvd, and modes.vtp.
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

// ParaView: vtk/step_NNNNNN.vtp (polyline, per-element d1, d3, radius) and trajectory.pvd
// (VTK XML PolyData, binary appended data compressed with zlib: compressor="vtkZLibDataCompressor",
// header_type="UInt64"; ParaView and VTK's readers read it)
class VtkSeriesWriter {
 public:
  explicit VtkSeriesWriter(const std::filesystem::path& runDir);
  // continues a killed run's series with the entries it had written (a checkpoint's)
  VtkSeriesWriter(const std::filesystem::path& runDir, std::vector<std::pair<double, std::string>> entries);
  void add(const Snapshot& s);
  void close();
  // trajectory.pvd's entries so far: (time_h, file)
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }

 private:
  std::filesystem::path dir_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace rootsim
