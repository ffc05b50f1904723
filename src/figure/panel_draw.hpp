#pragma once
// Drawing a panel: roots on the plate in an axes (at one scale, in a window that bounds them) and the
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

// one root on the plate in an axes of f, window win widened to the axes' aspect: a rendered tile (tube
// with +-d1 stripes) when c has a renderer, otherwise the centreline drawn with the root's width
void addRoot(const Ctx& c, const Figure& f, Axes& ax, const Snapshot& sn, const Case& k, PlateWindow win, Rgb color);

// a line of palette colour `color`
Series line(std::vector<double> x, std::vector<double> y, int color, std::string label, bool dashed = false);
// markers of palette colour `color`
Series points(std::vector<double> x, std::vector<double> y, int color, char marker, std::string label);

}  // namespace rootsim::fig
