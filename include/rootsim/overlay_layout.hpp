#pragma once
// Where a picture's overlays may go: the root's projected footprint (every pixel a tube may cover, with
// a small halo, on a grid of cells) and the one layout step that moves each overlay block (time,
// parameters, legend, scale bar, downhill arrow, colour bar, inset) to free space nearest its preferred
// corner or edge, shrinking it when nothing is free. No GL here.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// the cells of a picture a root's tube may cover (conservative: the tube's projected radius plus a halo
// of haloPx, plus the whiskers' reach when drawn), on square cells of cell() px
class RootFootprint {
 public:
  RootFootprint(int width, int height);
  int width() const { return w_; }
  int height() const { return h_; }
  int cell() const { return cell_; }
  // the snapshot's tubes seen through the camera (view, projection) of a picture of this size
  void add(const Snapshot& snap, const SceneInfo& info, const CameraMatrices& cam, bool whiskers);
  // a capsule from a to b [px] of radius r [px] (the halo added)
  void addCapsule(float ax, float ay, float bx, float by, float r);
  void merge(const RootFootprint& other);
  // the pixel (x, y) lies in an occupied cell
  bool covers(int x, int y) const;
  // occupied cells meeting the pixel rectangle [x0, x1) x [y0, y1)
  int hits(float x0, float y0, float x1, float y1) const;
  bool empty() const;

  static constexpr float haloPx = 3.0f;

 private:
  int w_, h_, cell_, cw_, ch_;
  std::vector<std::uint8_t> occ_;
};

// the footprint of every snapshot in snaps through one camera (a movie's fixed framing)
std::shared_ptr<const RootFootprint> rootFootprint(const std::vector<Snapshot>& snaps, const SceneInfo& info,
                                                   const View& view, const Framing& framing);

// one overlay as drawn at its preferred place; the layout moves (and if need be shrinks) it as a whole
struct OverlayBlock {
  std::vector<OverlayRect> rects;
  std::vector<OverlayLine> lines;
  std::vector<OverlayText> texts;
  bool shrink = true;   // false: its size means something (a scale bar's length)
};

// the box [x0, y0, x1, y1] a block's items cover [px] (texts measured with the font at fontPath)
std::array<float, 4> blockBox(const OverlayBlock& b, const std::string& fontPath);

struct PlacedBlock {
  float dx = 0, dy = 0;   // translation from the preferred place [px]
  float scale = 1;        // about the preferred box's top-left corner, before the translation
  bool free = true;       // false: no free space even shrunk; drawn where it meets the fewest footprint
                          // cells (at the smallest scale), on a translucent backing, under the root (the
                          // painter keeps the footprint)
};

// place boxes (preferred [x0, y0, x1, y1] each, in priority order) in a W x H picture: each goes to the
// free position nearest its preferred one (along the picture's edges first, then rings further in) that
// meets no footprint cell, no box placed before it and no keepClear rectangle; shrunk to 0.8 and 0.64
// when nothing is free at full size (minScale[i]: the smallest scale tried for box i, 1: never shrunk;
// empty: 0.64 for all)
std::vector<PlacedBlock> layoutBoxes(const std::vector<std::array<float, 4>>& boxes, const RootFootprint& fp,
                                     const std::vector<std::array<float, 4>>& keepClear, int width, int height,
                                     float marginPx, const std::vector<float>& minScale = {});

// the block moved and scaled as placed
void applyPlacement(OverlayBlock& b, const std::array<float, 4>& box, const PlacedBlock& p);

}  // namespace rootsim
