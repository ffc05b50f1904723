#pragma once
// A ParaView folder (`rootsim export RUN --paraview DIR`, docs/paraview.md): the snapshots as
// step_NNNNNN.vtp (vtk.hpp's snapshotVtp, the run's own format), root.pvd (times in hours), plate.vtp,
// and open_in_paraview.py, a ParaView Python script that shows the root as a striped tube on its plate.
#include <array>
#include <filesystem>
#include <string>
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
std::string paraviewScript(const SceneInfo& info, const std::array<double, 4>& extentMm,
                           const std::filesystem::path& folder);

// writes the folder's files into dir (which exists: a StagedFolder's work folder): step_NNNNNN.vtp of
// each snapshot, root.pvd, plate.vtp (covering every snapshot), open_in_paraview.py naming finalDir (the
// folder's final name; empty: dir) as its folder
void writeParaviewFiles(const std::filesystem::path& dir, const std::vector<Snapshot>& snaps, const SceneInfo& info,
                        const std::filesystem::path& finalDir = {});

}  // namespace rootsim
