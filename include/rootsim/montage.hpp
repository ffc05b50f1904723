#pragma once
// Several runs side by side on one scale and one clock (`rootsim montage`).
#include <string>
#include <vector>

#include "rootsim/gl_renderer.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/video_writer.hpp"

namespace rootsim {

struct MontageRun {
  std::vector<Snapshot> snaps;  // time ordered
  SceneInfo info;
  std::string label;            // drawn under the tile (e.g. the parameters that differ)
};
struct MontageJob {
  std::string mp4;        // empty: none
  std::string pngDir;     // empty: none
  View view;              // the whole frame's size; kind, colours, shadows and overlays of every tile
  VideoOptions video;
  RendererOptions renderer;
};
// the montage's clock: every snapshot time of every run, sorted, equal times (within 1e-9 h) merged
std::vector<double> montageClock(const std::vector<MontageRun>& runs);
// the snapshot a run shows at time tH: the last one at or before tH (the first one before it starts;
// a run that ended holds its last frame)
int snapshotAt(const std::vector<Snapshot>& snaps, double tH);
// tiles: columns x rows chosen for the largest common scale; each tile frames its run around its base
// node with the same width in mm, so bases line up and lengths compare
struct MontageLayout {
  int cols = 1, rows = 1;
  int tileW = 0, tileH = 0;   // [px]
  int headerH = 0;            // [px] band with the time at the top
  std::vector<Framing> framing;  // per run
};
MontageLayout montageLayout(const std::vector<MontageRun>& runs, const View& view);
void renderMontage(const std::vector<MontageRun>& runs, const MontageJob& job, const MovieProgress& progress = {});

}  // namespace rootsim
