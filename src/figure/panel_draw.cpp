// Drawing a panel: roots on the plate (plate coordinates of a snapshot, the window that bounds them, the
// root as a vector tube) and plot series.
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
  PlateWindow w{1e9, -1e9, 1e9, -1e9};
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

Tube tubeOf(const Snapshot& sn, double alphaDeg) {
  const PlateFrame pf = PlateFrame::tilted(alphaDeg * units::deg);
  const int n = sn.elements();
  Tube tb;
  if (n < 1) return tb;
  const Vec3 view(0, 0, 1);  // the top view: towards the viewer is the plate's normal
  for (int i = 0; i <= n; ++i) {
    // the node's frame from its elements' directors, as the raster renderer's rings (render_scene.cpp)
    Vec3 t = Vec3::Zero(), a = Vec3::Zero();
    double r = 0;
    int cnt = 0;
    for (int e : {i - 1, i}) {
      if (e < 0 || e >= n) continue;
      t += pf.dirToPlate(sn.d3.col(e));
      a += pf.dirToPlate(sn.d1.col(e));
      r += sn.radius[e];
      ++cnt;
    }
    if (t.norm() < 1e-12) t = Vec3::UnitY();
    t.normalize();
    a -= a.dot(t) * t;
    if (a.norm() < 1e-12) a = t.unitOrthogonal();
    a.normalize();
    const Vec3 b = t.cross(a);
    Vec3 side = view.cross(t);  // across the tube in the plate's plane
    if (side.norm() < 1e-9) side = a;  // a root pointing at the viewer
    side.normalize();
    const Vec3 c = pf.toPlateMm(sn.x.col(i));  // lateral, uphill, height [mm]
    tb.x.push_back(c.x());
    tb.y.push_back(-c.y());  // downhill
    tb.z.push_back(c.z());
    tb.r.push_back(r / cnt / units::mm);
    tb.sx.push_back(side.x());
    tb.sy.push_back(-side.y());
    auto arr = [](const Vec3& v) { return std::array<double, 3>{v.x(), v.y(), v.z()}; };
    const double hw = kStripeHalfWidthDeg * units::deg;
    tb.plus.push_back(visibleStripe(arr(a), arr(b), arr(side), arr(view), hw));
    tb.minus.push_back(visibleStripe(arr(-a), arr(-b), arr(side), arr(view), hw));
  }
  return tb;
}

std::vector<Obstacle2D> obstaclesOf(const SceneInfo& info) {
  std::vector<Obstacle2D> out;
  for (const auto& o : info.obstacles) {
    Obstacle2D d;
    d.fromX = o.fromU;
    d.fromY = -o.fromV;  // uphill -> downhill
    d.toX = o.peg ? o.fromU : o.toU;
    d.toY = o.peg ? -o.fromV : -o.toV;
    d.r = o.radiusMm;
    out.push_back(d);
  }
  return out;
}

void setPlateAxes(const Figure& f, Axes& ax, PlateWindow win) {
  // widen the window to the plot area's aspect, so the root fills the axes at one scale
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
  ax.yDown = true;
  ax.autoX = ax.autoY = false;
  ax.xmin = win.lateralMin;
  ax.xmax = win.lateralMax;
  ax.ymin = win.downhillMin;
  ax.ymax = win.downhillMax;
  ax.grid = false;  // the plate's grid instead
  ax.plateGridPitch = 1.0;
}

void addRoot(const Ctx& c, const Figure& f, Axes& ax, const Snapshot& sn, const Case& k, PlateWindow win) {
  setPlateAxes(f, ax, win);
  ax.obstacles = obstaclesOf(infoOf(c, k));
  ax.tubes.push_back(tubeOf(sn, k.alpha));
}

double plateAspect(const PlateWindow& w) {
  return (w.downhillMax - w.downhillMin) / (w.lateralMax - w.lateralMin);
}

void fitHeight(Figure& f, const Axes& sample, double aspect, int lo, int hi) {
  // the plot area's aspect is linear in the figure's height
  f.height = 1000;
  const double a1 = plotAspect(f, sample);
  f.height = 500;
  const double a0 = plotAspect(f, sample);
  const double h = 500 + (aspect - a0) / (a1 - a0) * 500;
  f.height = std::clamp(static_cast<int>(std::lround(h)), lo, hi);
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
