// A root tile for the figure panels (figure_tile.hpp).
#include "rootsim/figure_tile.hpp"

#include <array>

#include "rootsim/gl_renderer.hpp"
#include "rootsim/render_scene.hpp"

namespace rootsim::app {

Raster renderFigureTile(const Snapshot& sn, const SceneInfo& info, const PlateWindow& w) {
  View v;
  v.kind = View::Kind::Top;
  v.width = w.width;
  v.height = w.height;
  v.overlays = false;
  v.marginMm = 0.0;
  // plate coordinates of the renderer: u lateral, v uphill = -downhill
  v.centreMm = std::array<double, 2>{0.5 * (w.lateralMin + w.lateralMax), -0.5 * (w.downhillMin + w.downhillMax)};
  v.widthMm = w.lateralMax - w.lateralMin;
  const Framing fr = frameFor({sn}, info, v);
  GlRenderer gl(v.width, v.height);
  const Image im = gl.render(buildRenderScene(sn, info, v, fr));
  Raster r;
  r.width = im.width;
  r.height = im.height;
  r.rgba.assign(im.rgba.begin(), im.rgba.end());
  return r;
}

}  // namespace rootsim::app
