#pragma once
// Drawing a panel: roots on the plate in an axes (vector tubes at one scale, in a window that bounds them) and the
// line and marker series of a plot.
#include <string>
#include <vector>

#include "figure_cases.hpp"
#include "rootsim/figure.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim::fig {

// the window of the plate [mm] that bounds several snapshots (on a plate tilted by alphaDeg), with a
// margin, at least minHalfWidth to either side of its centre
PlateWindow boundingWindow(const std::vector<const Snapshot*>& sns, double alphaDeg, double margin, double minHalfWidth);

// half the angular width of each +-d1 stripe around its director, as the raster renderer draws it
// (View::stripeHalfWidthDeg, render_scene.hpp)
inline constexpr double kStripeHalfWidthDeg = 38.0;

// a snapshot seen from above on a plate tilted by alphaDeg: the tube in plate coordinates [mm] (lateral,
// downhill), each node's side vector and the lateral extents of its +-d1 stripes where they face the viewer
Tube tubeOf(const Snapshot& sn, double alphaDeg);

// the obstacles of a scene seen from above in plate coordinates [mm] (lateral, downhill)
std::vector<Obstacle2D> obstaclesOf(const SceneInfo& info);

// axes ax of figure f as a plate view of window win: the window widened to the axes' plot aspect (one
// scale), downhill down, axes in mm, the plate's 1 mm grid instead of the axes' grid
void setPlateAxes(const Figure& f, Axes& ax, PlateWindow win);

// one root on the plate in an axes of f (downhill down, axes in mm), window win widened to the axes'
// aspect, on the plate's 1 mm grid with the case's obstacles (the axes' ticks as they are, without their grid)
void addRoot(const Ctx& c, const Figure& f, Axes& ax, const Snapshot& sn, const Case& k, PlateWindow win);

// height / width of a plate window
double plateAspect(const PlateWindow& w);
// sets f.height (within lo..hi) so that axes like `sample` have a plot area of height / width `aspect`:
// plate views framed tightly around their roots
void fitHeight(Figure& f, const Axes& sample, double aspect, int lo, int hi);

// a line of palette colour `color`
Series line(std::vector<double> x, std::vector<double> y, int color, std::string label, bool dashed = false);
// markers of palette colour `color`
Series points(std::vector<double> x, std::vector<double> y, int color, char marker, std::string label);

}  // namespace rootsim::fig
