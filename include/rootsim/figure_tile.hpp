#pragma once
// A root tile for the figure panels (figure_tile.cpp): the renderer's top view of exactly the plate window
// a panel asks for (the figure library's TileRenderer; the CLI hands it to `rootsim figure`).
#include "rootsim/figure.hpp"

namespace rootsim::app {

// the tube with its +-d1 stripes and the 1 mm grid, without overlays (the panel's axes carry the labels)
Raster renderFigureTile(const Snapshot& sn, const SceneInfo& info, const PlateWindow& w);

}  // namespace rootsim::app
