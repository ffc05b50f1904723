// Drawing a panel: roots on the plate (plate coordinates of a snapshot, the window that bounds them, a
// rendered tile or a centreline) and plot series.
#include "panel_draw.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "rootsim/environment.hpp"
#include "rootsim/units.hpp"

namespace rootsim::fig {

namespace {
// plate coordinates [mm] of a snapshot's nodes: lateral x and downhill w (drawn with downhill down)
void plateCoords(const Snapshot& sn, double alphaDeg, std::vector<double>& x, std::vector<double>& w) {
  const PlateFrame f = PlateFrame::tilted(alphaDeg * units::deg);
  x.clear();
  w.clear();
  for (int i = 0; i < sn.x.cols(); ++i) {
    const Vec3 p = f.coords(sn.x.col(i)) / units::mm;
    x.push_back(p.x());
    w.push_back(p.y());
  }
}
}  // namespace

PlateWindow boundingWindow(const std::vector<const Snapshot*>& sns, double alphaDeg, double margin, double minHalfWidth) {
  PlateWindow w{1e9, -1e9, 1e9, -1e9, 0, 0};
  std::vector<double> x, d;
  for (const Snapshot* sn : sns) {
    plateCoords(*sn, alphaDeg, x, d);
    for (size_t i = 0; i < x.size(); ++i) {
      w.lateralMin = std::min(w.lateralMin, x[i]);
      w.lateralMax = std::max(w.lateralMax, x[i]);
      w.downhillMin = std::min(w.downhillMin, d[i]);
      w.downhillMax = std::max(w.downhillMax, d[i]);
    }
  }
  const double cx = 0.5 * (w.lateralMin + w.lateralMax);
  const double hw = std::max(0.5 * (w.lateralMax - w.lateralMin) + margin, minHalfWidth);
  w.lateralMin = cx - hw;
  w.lateralMax = cx + hw;
  w.downhillMin -= margin;
  w.downhillMax += margin;
  return w;
}

void addRoot(const Ctx& c, const Figure& f, Axes& ax, const Snapshot& sn, const Case& k, PlateWindow win, Rgb color) {
  // widen the window to the plot area's aspect, so a rendered tile fills the axes at one scale
  const double aspect = plotAspect(f, ax);
  const double lw = win.lateralMax - win.lateralMin, dh = win.downhillMax - win.downhillMin;
  if (dh / lw > aspect) {
    const double cx = 0.5 * (win.lateralMin + win.lateralMax), half = 0.5 * dh / aspect;
    win.lateralMin = cx - half;
    win.lateralMax = cx + half;
  } else {
    const double cy = 0.5 * (win.downhillMin + win.downhillMax), half = 0.5 * lw * aspect;
    win.downhillMin = cy - half;
    win.downhillMax = cy + half;
  }
  ax.equalAspect = true;
  ax.autoX = ax.autoY = false;
  ax.xmin = win.lateralMin;
  ax.xmax = win.lateralMax;
  ax.ymin = -win.downhillMax;
  ax.ymax = -win.downhillMin;
  if (c.opt.renderTile) {
    PlateWindow px = win;
    const double mmPerPx = 0.02;  // 50 px per mm
    px.width = std::max(2, 2 * static_cast<int>(std::lround(0.5 * (win.lateralMax - win.lateralMin) / mmPerPx)));
    px.height = std::max(2, 2 * static_cast<int>(std::lround(0.5 * (win.downhillMax - win.downhillMin) / mmPerPx)));
    Raster r = c.opt.renderTile(sn, infoOf(c, k), px);
    r.x0 = win.lateralMin;
    r.x1 = win.lateralMax;
    r.y0 = -win.downhillMax;
    r.y1 = -win.downhillMin;
    ax.rasters.push_back(std::move(r));
    ax.grid = false;
    return;
  }
  Shape2D sh;
  sh.color = color;
  sh.width = 0.2;  // 2R [mm]
  std::vector<double> w;
  plateCoords(sn, k.alpha, sh.x, w);
  for (double v : w) sh.y.push_back(-v);
  ax.shapes.push_back(sh);
}

Series line(std::vector<double> x, std::vector<double> y, int color, std::string label, bool dashed) {
  Series s;
  s.x = std::move(x);
  s.y = std::move(y);
  s.color = paletteColor(color);
  s.label = std::move(label);
  s.dashed = dashed;
  return s;
}

Series points(std::vector<double> x, std::vector<double> y, int color, char marker, std::string label) {
  Series s = line(std::move(x), std::move(y), color, std::move(label));
  s.kind = Series::Kind::Markers;
  s.marker = marker;
  return s;
}

}  // namespace rootsim::fig
