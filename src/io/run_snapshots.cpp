// a run directory's snapshots: one root's trajectory, or a plate's roots merged in plate coordinates
#include "rootsim/run_snapshots.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/trajectory.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {
std::vector<Snapshot> loadOne(const fs::path& runDir) {
  const fs::path traj = trajectoryPath(runDir);  // trajectory.bin, or trajectory.csv
  if (!fs::is_regular_file(traj))
    throw SceneError(traj.string() + ": not found (a run directory written with output.trajectory = true)");
  std::vector<Snapshot> snaps = readTrajectory(traj);
  if (snaps.empty()) throw SceneError(traj.string() + ": no snapshots to render");
  return snaps;
}
}  // namespace

bool isPlateRun(const fs::path& runDir) {
  std::error_code ec;
  return fs::is_directory(runDir / "roots", ec) && fs::is_regular_file(runDir / "scene.toml", ec) &&
         loadScene((runDir / "scene.toml").string()).isPlate();
}

std::vector<PlateRoot> plateRoots(const fs::path& runDir) {
  const Scene sc = loadScene((runDir / "scene.toml").string());
  std::vector<std::string> names;
  for (const Seedling& sd : sc.plate.seedlings) names.push_back(sd.name);
  // the lateral roots: the folders that are no seedling's (a lateral's name is its parent's and ".K")
  std::vector<std::string> laterals;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(runDir / "roots", ec)) {
    const std::string n = e.path().filename().string();
    if (std::find(names.begin(), names.end(), n) == names.end()) laterals.push_back(n);
  }
  std::sort(laterals.begin(), laterals.end());
  names.insert(names.end(), laterals.begin(), laterals.end());
  std::vector<PlateRoot> out;
  for (const std::string& n : names) {
    PlateRoot r;
    r.name = n;
    r.dir = runDir / "roots" / n;
    const Scene own = loadScene((r.dir / "scene.toml").string());
    if (own.plate.seedlings.size() != 1)
      throw SceneError((r.dir / "scene.toml").string() + ": not the scene of one root of a plate");
    r.seedling = own.plate.seedlings.front();
    const auto dot = n.rfind('.');
    if (dot != std::string::npos) r.parent = n.substr(0, dot);
    out.push_back(std::move(r));
  }
  return out;
}

Vec3 plateOffset(const PlateFrame& plate, const PlateRoot& root) {
  return root.seedling.position.x() * plate.lateral + root.seedling.position.y() * plate.downhill;
}

std::vector<Snapshot> loadSnapshots(const fs::path& runDir, const std::string& last) {
  if (!isPlateRun(runDir)) {
    if (!last.empty())
      throw SceneError("--root " + last + ": " + runDir.string() + " is a run of one root (--root picks a root of a plate's run)");
    return loadOne(runDir);
  }
  std::vector<PlateRoot> roots = plateRoots(runDir);
  if (!last.empty()) {
    auto it = std::find_if(roots.begin(), roots.end(), [&](const PlateRoot& r) { return r.name == last; });
    if (it == roots.end()) {
      std::string names;
      for (const PlateRoot& r : roots) names += (names.empty() ? "" : ", ") + r.name;
      throw SceneError("--root " + last + ": " + runDir.string() + " has no such root (its roots: " + names + ")");
    }
    std::rotate(it, it + 1, roots.end());  // the followed root last
  }
  // each root's snapshots in plate coordinates (its frame's origin at its place on the plate); a lateral
  // root's snapshots are the plate's last ones (it was recorded from the first output step after it emerged)
  const PlateFrame pf = loadScene((runDir / "scene.toml").string()).model.env.plane.frame();
  std::vector<std::vector<Snapshot>> snaps;
  size_t count = 0;
  for (const PlateRoot& r : roots) {
    std::vector<Snapshot> s = loadOne(r.dir);
    const Vec3 offset = plateOffset(pf, r);
    for (Snapshot& one : s) one.x.colwise() += offset;
    count = std::max(count, s.size());
    snaps.push_back(std::move(s));
  }
  std::vector<Snapshot> merged;
  for (size_t k = 0; k < count; ++k) {
    std::vector<Snapshot> present;
    for (const std::vector<Snapshot>& s : snaps)
      if (k + s.size() >= count) present.push_back(s[k + s.size() - count]);
    Snapshot m = mergeRoots(present);
    m.timeH = present.front().timeH;
    merged.push_back(std::move(m));
  }
  return merged;
}

std::vector<double> snapshotTimes(const std::vector<Snapshot>& snaps) {
  std::vector<double> t;
  t.reserve(snaps.size());
  for (const Snapshot& s : snaps) t.push_back(s.timeH);
  return t;
}


int snapshotNear(const std::vector<double>& t, double atH, const std::string& range) {
  if (t.empty() || atH < t.front() || atH > t.back())
    throw SceneError("--at-h " + significantText(atH) + ": outside the " + range + " snapshots, " +
                     (t.empty() ? std::string("none") : significantText(t.front()) + " .. " + significantText(t.back()) + " h"));
  return nearestSnapshot(t, atH);
}

}  // namespace rootsim
