#pragma once
// Several runs side by side on one scale and one clock (`rootsim montage`).
#include <array>
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
  std::string label;            // drawn under the run's root (e.g. the parameters that differ)
};
struct MontageJob {
  std::string mp4;        // empty: none
  std::string pngDir;     // empty: none
  View view;              // the whole frame's size; kind, colours, shadows and overlays of every tile
  VideoOptions video;
  RendererOptions renderer;
  std::string caption;    // one line in the header after the time (e.g. the values all runs share)
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
  float labelPx = 14;         // text height of the labels, the time and the caption [px]
};
// where run i's label goes in its tile [px from the tile's top-left corner]: the bottom centre of the
// text, under the lowest point the run's root reaches in the movie and centred on its lateral extent
std::array<float, 2> montageLabelAnchor(const MontageRun& run, const View& tileView, const Framing& framing,
                                        float labelWidthPx, float labelPx);
MontageLayout montageLayout(const std::vector<MontageRun>& runs, const View& view);
// the box [x0, y0, x1, y1] px a run's label covers in its tile (anchor from montageLabelAnchor), with a
// margin of 0.3 of its height: kept clear by the tile's overlays (the last tile's colour bar, scale bar)
std::array<float, 4> montageLabelBox(const std::array<float, 2>& anchor, float labelWidthPx, float labelPx);
// the view tile i of n is rendered with (the montage's view at the tile's size, its overlays in the
// labels' size labelPx): no time, parameters, title or legend (the header has them); the scale bar,
// downhill arrow and colour bar on the last tile only (they are common)
// labelBox (montageLabelBox; none when empty) is kept clear by the tile's overlays
View montageTileView(const MontageLayout& l, const View& view, std::size_t i, std::size_t n,
                     const std::array<float, 4>& labelBox = {});
void renderMontage(const std::vector<MontageRun>& runs, const MontageJob& job, const MovieProgress& progress = {});

}  // namespace rootsim
