// what `render` and `montage` read from a run directory and how they claim their outputs
#include "run_files.hpp"

#include <cstdint>
#include <cstdio>
#include <utility>

#include "rootsim/errors.hpp"
#include "rootsim/scene.hpp"
#include "rootsim/trajectory.hpp"

namespace fs = std::filesystem;

namespace rootsim::app {

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

std::vector<Snapshot> loadSnapshots(const fs::path& runDir, const std::string& last) {
  if (!isPlateRun(runDir)) {
    if (!last.empty())
      throw SceneError("--root " + last + ": " + runDir.string() + " is a run of one root (--root picks a root of a plate's run)");
    return loadOne(runDir);
  }
  const Scene sc = loadScene((runDir / "scene.toml").string());
  const std::vector<Seedling>& seeds = sc.plate.seedlings;
  std::vector<int> order;
  for (int r = 0; r < static_cast<int>(seeds.size()); ++r)
    if (seeds[static_cast<size_t>(r)].name != last) order.push_back(r);
  if (!last.empty()) {
    if (order.size() == seeds.size()) {
      std::string names;
      for (const Seedling& sd : seeds) names += (names.empty() ? "" : ", ") + sd.name;
      throw SceneError("--root " + last + ": " + runDir.string() + " has no such root (its roots: " + names + ")");
    }
    for (int r = 0; r < static_cast<int>(seeds.size()); ++r)
      if (seeds[static_cast<size_t>(r)].name == last) order.push_back(r);
  }
  // each root's snapshots in plate coordinates (its frame's origin at its seedling's place)
  const PlateFrame pf = sc.model.env.plane.frame();
  std::vector<std::vector<Snapshot>> roots;
  size_t count = SIZE_MAX;
  for (int r : order) {
    const Seedling& sd = seeds[static_cast<size_t>(r)];
    std::vector<Snapshot> snaps = loadOne(runDir / "roots" / sd.name);
    const Vec3 offset = sd.position.x() * pf.lateral + sd.position.y() * pf.downhill;
    for (Snapshot& s : snaps) s.x.colwise() += offset;
    count = std::min(count, snaps.size());
    roots.push_back(std::move(snaps));
  }
  std::vector<Snapshot> merged;
  std::vector<Snapshot> one(roots.size());
  for (size_t k = 0; k < count; ++k) {
    for (size_t r = 0; r < roots.size(); ++r) one[r] = std::move(roots[r][k]);
    merged.push_back(mergeRoots(one));
  }
  return merged;
}

std::vector<double> snapshotTimes(const std::vector<Snapshot>& snaps) {
  std::vector<double> t;
  t.reserve(snaps.size());
  for (const Snapshot& s : snaps) t.push_back(s.timeH);
  return t;
}

std::string flagNumber(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

int snapshotNear(const std::vector<double>& t, double atH, const std::string& range) {
  if (t.empty() || atH < t.front() || atH > t.back())
    throw SceneError("--at-h " + flagNumber(atH) + ": outside the " + range + " snapshots, " +
                     (t.empty() ? std::string("none") : flagNumber(t.front()) + " .. " + flagNumber(t.back()) + " h"));
  return nearestSnapshot(t, atH);
}

Outputs claimOutputs(const std::string& mp4, const fs::path& png, const std::string& pngDir, const WriteRule& rule,
                     const char* pngFlag) {
  Outputs o;
  std::vector<std::pair<const char*, fs::path>> all;
  if (!mp4.empty()) all.emplace_back("--mp4", mp4);
  if (!png.empty()) all.emplace_back(pngFlag, png);
  if (!pngDir.empty()) all.emplace_back("--png-dir", pngDir);
  // no output may be another, or lie inside the frame folder (replaced whole)
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = 0; j < all.size(); ++j) {
      if (i == j) continue;
      const fs::path a = fs::absolute(all[i].second).lexically_normal(), b = fs::absolute(all[j].second).lexically_normal();
      const auto rel = a.lexically_relative(b);
      if (a == b || (std::string(all[j].first) == "--png-dir" && !rel.empty() && *rel.begin() != ".."))
        throw SceneError(std::string(all[i].first) + " " + all[i].second.string() + ": the same path as, or inside, " +
                         all[j].first + " " + all[j].second.string());
    }
  for (const auto& [flag, path] : all) {
    // locked first, then checked: a second process cannot slip in between
    if (std::string(flag) == "--png-dir") {
      checkOutputName(path.string(), flag);
      claimFolder(path, framesFolder(), rule, flag, true);
      continue;  // StagedFolder locks it when the frames are written
    }
    checkOutputName(path.string(), flag);
    const fs::path dir = fs::absolute(path).parent_path();
    if (!fs::is_directory(dir)) throw SceneError(std::string(flag) + " " + path.string() + ": folder " + dir.string() + " not found");
    o.locks.emplace_back(path, flag);
    claimFile(path, rule, flag);
  }
  return o;
}

MovieProgress progressLines(bool quiet, const std::string& what) {
  if (quiet) return {};
  return [what, next = 0](int done, int total) mutable {
    const int percent = 100 * done / total;
    if (percent < next && done != total) return;
    std::fprintf(stderr, "%s: frame %d/%d (%d %%)\n", what.c_str(), done, total, percent);
    next = percent / 10 * 10 + 10;
  };
}

}  // namespace rootsim::app
