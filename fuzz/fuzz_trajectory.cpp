// Fuzz harness: trajectory.csv or trajectory.bin (told apart by the first bytes) -> readTrajectory
// (include/rootsim/outputs.hpp), what `rootsim render` reads. Oracles: a refused file throws SceneError with a one-line message; an accepted file gives at
// least one frame, every frame with at least one element and only finite numbers, positions and radii
// within the trajectory bounds (the renderer's precondition).
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_check.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace {
char gDir[] = "/tmp/rootsim-fuzz-traj-XXXXXX";  // a plain array: still valid in the atexit handler

fs::path file() {
  static const bool made = [] {
    if (!::mkdtemp(gDir)) rootsim::fuzz::fail("mkdtemp failed");
    std::atexit([] { std::error_code ec; fs::remove_all(gDir, ec); });
    return true;
  }();
  (void)made;
  return fs::path(gDir) / "trajectory.csv";
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  {
    std::ofstream out(file(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  std::vector<rootsim::Snapshot> snaps;
  try {
    snaps = rootsim::readTrajectory(file());
  } catch (const rootsim::SceneError& e) {
    rootsim::fuzz::checkMessage(e.what());
    return 0;
  }
  if (snaps.empty()) rootsim::fuzz::fail("accepted trajectory without frames");
  for (const auto& s : snaps) {
    if (s.elements() < 1) rootsim::fuzz::fail("accepted frame without elements");
    if (!s.x.allFinite() || !s.d1.allFinite() || !s.d3.allFinite() || !std::isfinite(s.timeH))
      rootsim::fuzz::fail("accepted frame with non-finite values");
    for (int i = 0; i < s.elements(); ++i)
      if (!std::isfinite(s.radius[i]) || s.radius[i] > rootsim::kMaxTrajectoryRadiusMm * rootsim::units::mm)
        rootsim::fuzz::fail("accepted frame with a non-finite or too large radius");
    // the bounds the renderer relies on (a 1e7 mm coordinate made it grow past 4 GB)
    if (s.x.cwiseAbs().maxCoeff() > rootsim::kMaxTrajectoryCoordMm * rootsim::units::mm)
      rootsim::fuzz::fail("accepted frame with a coordinate beyond the trajectory bounds");
  }
  return 0;
}
