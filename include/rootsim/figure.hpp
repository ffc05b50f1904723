#pragma once
// The paper's figure panels (`rootsim figure NAME|all [--quick] [--out DIR]`): each panel runs the
// simulations it needs (resumably, into DIR/runs/), then writes DIR/NAME.pdf, DIR/NAME.svg (vector, roots
// as paths) and DIR/NAME.png (rasterised from the same drawing at FigureOptions::dpi), and
// `all` writes DIR/report.md with every panel and the measured-vs-theory tables.
#include <functional>
#include <string>
#include <vector>

#include "rootsim/plot.hpp"

namespace rootsim {

// a window of the plate in plate coordinates [mm]: lateral (x) and downhill (along g_par); the picture
// shows downhill pointing down
struct PlateWindow {
  double lateralMin = -2, lateralMax = 2, downhillMin = 0, downhillMax = 10;
};

struct FigureOptions {
  bool quick = false;   // coarsened runs (0.1 mm elements, 0.1 h steps, shorter growth, 15 deg phase grid): for CI
  std::string out = "figures";
  int jobs = 2;         // parallel simulations
  bool force = false;   // replace panels (and rerun figure runs of other scenes) rootsim wrote earlier in out
  bool quiet = false;
  double dpi = 300;      // PNG resolution, stored in the PNG (pHYs)
  double widthMm = 0;    // physical width of every panel (85 or 180 mm: a journal column); 0: 96 layout units per inch
  bool titles = true;    // false: panels without a figure title
};

// fig2a, fig2b, fig2cde, fig3a, fig3b, fig3d, fig3d_gamma1, fig3d_apical, fig4a, fig4g
const std::vector<std::string>& figureNames();

// makes one panel (or "all" plus report.md); returns a markdown section describing it;
// throws SceneError for an unknown name
std::string makeFigure(const std::string& name, const FigureOptions& opt,
                       const std::function<void(const std::string&)>& log);

}  // namespace rootsim
