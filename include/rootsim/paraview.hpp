#pragma once
// A ParaView folder (`rootsim export RUN --paraview DIR`, docs/paraview.md): the snapshots as
// step_NNNNNN.vtp (vtk.hpp's snapshotVtp, the run's own format), root.pvd (times in hours), plate.vtp,
// and open_in_paraview.py, a ParaView Python script that shows the root as a striped tube on its plate.
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "rootsim/snapshot.hpp"

namespace rootsim {

// the stripes as the renderer draws them (render_scene.hpp: View::stripeHalfWidthDeg and
// RenderScene::Material; a render test checks they agree): the surface whose normal lies within
// halfWidthDeg of +d1 is pink, of -d1 orange, the rest ivory (sRGB 0..1)
struct StripeStyle {
  double halfWidthDeg = 38.0;
  std::array<double, 3> body{0.95, 0.93, 0.86};
  std::array<double, 3> plus{0.90, 0.20, 0.55};
  std::array<double, 3> minus{0.98, 0.52, 0.05};
};

// open_in_paraview.py for a run of this scene whose snapshots cover extentMm (plateExtentMm): the plate's
// axes and extent for the top camera, the stripe rule and colours, and `folder` (made absolute), where
// the script finds its files when ParaView's GUI runs it without its own file name
// roots: each root's name and .pvd file (one root: "root", root.pvd)
std::string paraviewScript(const SceneInfo& info, const std::array<double, 4>& extentMm,
                           const std::filesystem::path& folder,
                           const std::vector<std::pair<std::string, std::string>>& roots = {{"root", "root.pvd"}});

// writes the folder's files into dir (which exists: a StagedFolder's work folder): step_NNNNNN.vtp of
// each snapshot, root.pvd, plate.vtp (covering every snapshot), open_in_paraview.py naming finalDir (the
// folder's final name; empty: dir) as its folder
void writeParaviewFiles(const std::filesystem::path& dir, const std::vector<Snapshot>& snaps, const SceneInfo& info,
                        const std::filesystem::path& finalDir = {});
// a plate's folder (docs/paraview.md, A plate): for each root NAME/step_NNNNNN.vtp and NAME.pvd (times in
// hours; a root that emerged after the plate's first snapshot lists empty.vtp, a line of no points, for
// the plate's snapshots before it), plate.vtp (covering every root's snapshots) and open_in_paraview.py showing every root striped.
// timesH: the plate's snapshot times, each root's firstFrame an index into them.
void writeParaviewPlateFiles(const std::filesystem::path& dir, const std::vector<RootSeries>& roots,
                             const std::vector<double>& timesH, const SceneInfo& info,
                             const std::filesystem::path& finalDir = {});

}  // namespace rootsim
