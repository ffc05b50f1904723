#pragma once
// Cameras of a movie (docs/cli.md; docs/rendering.md, "Cameras and frames"): `fit` frames the whole root for
// the whole movie (frameFor); `follow` is a window fieldMm wide that follows the growth zone. No GL here.
#include <Eigen/Core>
#include <vector>

#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

enum class CameraMode { Fit, Follow };

struct FollowOptions {
  double fieldMm = 2.0;        // visible plate width [mm]
  double smoothFrames = 2.0;   // time constant of the critically damped follow [frames]
  double keepCentral = 0.12;   // the tip region's centre stays within this fraction of the width
                               // (height) from the picture's centre
};

// centre of the tip region: the arc-length centroid of the last lengthMm of the centreline, in plate
// (u, v) [mm]. It moves continuously while the root grows and does not jump when an element splits
// (a split keeps the centreline).
Eigen::Vector2d tipRegionCentre(const Snapshot& s, const PlateFrame& pf, double lengthMm);

// length of the tip region for a window of w x h mm: 0.25 of the shorter side, so the tip itself
// stays inside the middle of the picture
double tipRegionLength(double widthMm, double heightMm);

// one framing per snapshot for a width x height [px] picture: the window follows tipRegionCentre with
// a critically damped second-order filter (time constant smoothFrames), run forward and then
// backward over the whole movie so it has no lag and no jitter; afterwards the centre is held within
// keepCentral of the target. Throws RenderError on fieldMm <= 0, an empty list or bad sizes.
std::vector<Framing> followFramings(const std::vector<Snapshot>& snaps, const SceneInfo& info, int width,
                                    int height, const FollowOptions& opt);

}  // namespace rootsim
