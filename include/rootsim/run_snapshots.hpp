#pragma once
// a run directory's snapshots as the commands that read a run see them (render, montage, export, compare,
// fit): one root's trajectory, or a plate's roots merged in plate coordinates
#include <filesystem>
#include <string>
#include <vector>

#include "rootsim/plate.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// the run's trajectory (trajectory.bin, or trajectory.csv); SceneError when it is missing or empty.
// A plate's run (docs/plate.md): every root's trajectory in plate coordinates, merged per snapshot
// (Snapshot::rootStarts), the root named `last` drawn last (the follow camera follows the last root;
// "": the seedlings' order); SceneError naming --root for a root the plate does not have, or for a
// run of one root
std::vector<Snapshot> loadSnapshots(const std::filesystem::path& runDir, const std::string& last = "");
// true for a plate's run directory (a plate scene with its roots/ folder)
bool isPlateRun(const std::filesystem::path& runDir);
// a plate run's roots (docs/plate.md, Outputs): the seedlings in the scene's order, then the lateral roots
// by name; each with its folder, its parent's name ("" for a seedling) and its seedling as its folder's
// scene.toml describes it (place, angle, model)
struct PlateRoot {
  std::string name, parent;
  std::filesystem::path dir;
  Seedling seedling;
};
std::vector<PlateRoot> plateRoots(const std::filesystem::path& runDir);
// where a plate root's own frame lies in the plate's lab frame: its seedling's place on the plate (a
// root's folder holds its snapshots with its base's foot at the origin)
Vec3 plateOffset(const PlateFrame& plate, const PlateRoot& root);

// the growth times of the snapshots [h]
std::vector<double> snapshotTimes(const std::vector<Snapshot>& snaps);
// the snapshot nearest atH (ties to the earlier one): `render --png --at-h`, `export --at-h`. A time
// outside timesH's range is refused: SceneError "--at-h H: outside the <range> snapshots, A .. B h"
// (range: "run's", or "window's" for render's --from-h/--to-h window)
int snapshotNear(const std::vector<double>& timesH, double atH, const std::string& range = "run's");

}  // namespace rootsim
