// The pictures of `rootsim compare` and `rootsim fit` (docs/experiments.md).
#include "rootsim/compare_panel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "panel_draw.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {

constexpr Rgb kTraceColor{0.05, 0.20, 0.55};  // the trace: a dark blue line over the ivory tube

}  // namespace

void saveComparePanel(const Model& m, const Snapshot& sim, const Eigen::Matrix3Xd& traceMm, const std::string& title,
                      const std::string& caption, const std::string& path) {
  const double alphaDeg = m.env.plane.alpha / units::deg;
  Tube tube = fig::tubeOf(sim, alphaDeg);
  Figure f;
  f.cols = 2;
  f.width = 1200;
  f.title = title + (caption.empty() ? "" : ": " + caption);

  // A: the trace over the simulated root, on the plate
  Axes plate;
  plate.panelLabel = "A";
  plate.title = "on the plate";
  plate.xlabel = "lateral [mm]";
  plate.ylabel = "downhill [mm]";
  Series tr;
  for (int i = 0; i < traceMm.cols(); ++i) {
    tr.x.push_back(traceMm(0, i));
    tr.y.push_back(traceMm(1, i));
  }
  tr.color = kTraceColor;
  tr.width = 1.4;
  tr.label = "trace";
  // the window bounding both, with a margin of 1 mm
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto grow = [&](double x, double y) {
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  };
  for (std::size_t i = 0; i < tube.x.size(); ++i) grow(tube.x[i], tube.y[i]);
  for (std::size_t i = 0; i < tr.x.size(); ++i) grow(tr.x[i], tr.y[i]);
  const PlateWindow win{x0 - 1.0, x1 + 1.0, y0 - 1.0, y1 + 1.0};
  f.axes.push_back(plate);
  fig::fitHeight(f, f.axes[0], std::clamp(fig::plateAspect(win), 0.6, 2.2), 500, 1100);
  Axes& ax = f.axes[0];
  fig::setPlateAxes(f, ax, win);
  ax.obstacles = fig::obstaclesOf(sceneInfoOf(m));
  ax.tubes.push_back(tube);
  ax.series.push_back(tr);
  // the tube's legend entry: a line of its body colour
  Series simKey;
  simKey.color = Rgb{0.80, 0.62, 0.45};
  simKey.label = "simulation";
  ax.series.push_back(simKey);
  ax.legendPos = "sw";

  // B: lateral position along downhill, both roots
  Axes prof;
  prof.panelLabel = "B";
  prof.title = "lateral position along the plate";
  prof.xlabel = "downhill [mm]";
  prof.ylabel = "lateral [mm]";
  Series ts = tr;
  ts.x = tr.y;
  ts.y = tr.x;
  Series ss;
  ss.x = tube.y;
  ss.y = tube.x;
  ss.color = paletteColor(1);
  ss.width = 1.8;
  ss.label = "simulation";
  prof.series.push_back(ss);
  prof.series.push_back(ts);
  prof.legendPos = "ne";
  f.axes.push_back(prof);
  saveFigure(f, path);
}

void savePlateComparePanel(const Model& m, const std::vector<Snapshot>& sims, const std::vector<std::string>& names,
                           const std::vector<Eigen::Matrix3Xd>& tracesMm, const std::vector<std::string>& traceNames,
                           const std::string& title, const std::string& caption, const std::string& path) {
  const double alphaDeg = m.env.plane.alpha / units::deg;
  Figure f;
  f.cols = 2;
  f.width = 1400;
  f.title = title + (caption.empty() ? "" : ": " + caption);
  // one window for both plates: every root and every trace, with a margin of 2 mm
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto grow = [&](double x, double y) {
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  };
  std::vector<Tube> tubes;
  for (const Snapshot& s : sims) {
    tubes.push_back(fig::tubeOf(s, alphaDeg));
    for (std::size_t i = 0; i < tubes.back().x.size(); ++i) grow(tubes.back().x[i], tubes.back().y[i]);
  }
  for (const Eigen::Matrix3Xd& t : tracesMm)
    for (int i = 0; i < t.cols(); ++i) grow(t(0, i), t(1, i));
  const PlateWindow win{x0 - 2.0, x1 + 2.0, y0 - 2.0, y1 + 2.0};
  for (int k = 0; k < 2; ++k) {
    Axes ax;
    ax.panelLabel = k == 0 ? "A" : "B";
    ax.title = k == 0 ? "the simulated plate" : "the traced plate";
    ax.xlabel = "lateral [mm]";
    ax.ylabel = "downhill [mm]";
    f.axes.push_back(ax);
  }
  fig::fitHeight(f, f.axes[0], std::clamp(fig::plateAspect(win), 0.6, 2.2), 500, 1100);
  fig::fitHeight(f, f.axes[1], std::clamp(fig::plateAspect(win), 0.6, 2.2), 500, 1100);
  for (Axes& ax : f.axes) {
    fig::setPlateAxes(f, ax, win);
    ax.obstacles = fig::obstaclesOf(sceneInfoOf(m));
  }
  f.axes[0].tubes = tubes;
  for (std::size_t r = 0; r < sims.size() && r < names.size(); ++r)
    if (!names[r].empty() && !tubes[r].x.empty())
      f.axes[0].notes.push_back({{tubes[r].x.front(), tubes[r].y.front() - 1.0}, literalLabel(names[r])});
  for (std::size_t r = 0; r < tracesMm.size() && r < traceNames.size(); ++r)
    if (!traceNames[r].empty() && tracesMm[r].cols() > 0)
      f.axes[1].notes.push_back({{tracesMm[r](0, 0), tracesMm[r](1, 0) - 1.0}, literalLabel(traceNames[r])});
  for (const Eigen::Matrix3Xd& t : tracesMm) {
    Series tr;
    for (int i = 0; i < t.cols(); ++i) tr.x.push_back(t(0, i)), tr.y.push_back(t(1, i));
    tr.color = kTraceColor;
    tr.width = 1.2;
    f.axes[1].series.push_back(tr);
  }
  saveFigure(f, path);
}

void saveLandscapePanel(const std::vector<LandscapePoint>& pts, const std::string& xKey, const std::string& yKey,
                        double xLo, double xHi, double yLo, double yHi, int gridLevels, double bestX, double bestY,
                        const Eigen::Matrix2d* cov, double zoomX, double zoomY, const std::string& title,
                        const std::string& path) {
  double best = std::numeric_limits<double>::infinity();
  for (const LandscapePoint& p : pts) best = std::min(best, p.chi2);
  // classes of chi2 - chi2_min: 1, 2, 5 and 10 sigma of one parameter
  struct Band {
    double upTo;
    const char* label;
    Rgb color;
  };
  const Band bands[] = {{1, "Δχ² < 1", {0.13, 0.29, 0.53}},
                        {4, "Δχ² 1–4", {0.26, 0.52, 0.73}},
                        {25, "Δχ² 4–25", {0.55, 0.74, 0.87}},
                        {100, "Δχ² 25–100", {0.80, 0.88, 0.94}},
                        {std::numeric_limits<double>::infinity(), "Δχ² ≥ 100", {0.95, 0.96, 0.97}}};
  auto bandOf = [&](double c) {
    int b = 0;
    while (!(c - best < bands[b].upTo) && b < 4) ++b;
    return b;
  };
  // one axes: the design's cells (the whole box only), every later run as a disc of its band's colour,
  // the 1-sigma ellipse and the best point
  auto panel = [&](bool whole, double x0, double x1, double y0, double y1) {
    Axes ax;
    ax.panelLabel = whole ? "A" : "B";
    ax.title = whole ? "the whole box" : "around the minimum";
    ax.xlabel = literalLabel(xKey);
    ax.ylabel = literalLabel(yKey);
    ax.autoX = ax.autoY = false;
    ax.xmin = x0;
    ax.xmax = x1;
    ax.ymin = y0;
    ax.ymax = y1;
    ax.grid = false;
    bool labelled[5] = {false, false, false, false, false};
    const double cw = (xHi - xLo) / gridLevels, ch = (yHi - yLo) / gridLevels;
    if (whole)
      for (const LandscapePoint& p : pts) {
        if (!p.design) continue;
        const int b = bandOf(p.chi2);
        Fill fl;
        fl.x = {p.x - cw / 2, p.x + cw / 2, p.x + cw / 2, p.x - cw / 2};
        fl.y = {p.y - ch / 2, p.y - ch / 2, p.y + ch / 2, p.y + ch / 2};
        fl.color = bands[b].color;
        if (!labelled[b]) fl.label = bands[b].label;
        labelled[b] = true;
        ax.fills.push_back(fl);
      }
    for (int b = 4; b >= 0; --b) {
      Series s;
      s.kind = Series::Kind::Markers;
      s.marker = 'o';
      s.color = bands[b].color;
      for (const LandscapePoint& p : pts)
        if ((!whole || !p.design) && bandOf(p.chi2) == b && p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1) {
          s.x.push_back(p.x);
          s.y.push_back(p.y);
        }
      if (s.x.empty()) continue;
      if (!labelled[b]) s.label = std::string("run: ") + bands[b].label;
      labelled[b] = true;
      ax.series.push_back(s);
    }
    if (cov) {
      // the 1-sigma ellipse: the points x with (x - best)' C^-1 (x - best) = 1
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(*cov);
      Series el;
      el.color = Rgb{0.85, 0.10, 0.10};
      el.width = 1.6;
      el.label = "1σ";
      for (int i = 0; i <= 96; ++i) {
        const double t = 2.0 * std::numbers::pi * i / 96.0;
        const Eigen::Vector2d u(std::cos(t), std::sin(t));
        const Eigen::Vector2d v = eig.eigenvectors() * (eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() * u);
        el.x.push_back(bestX + v.x());
        el.y.push_back(bestY + v.y());
      }
      ax.series.push_back(el);
    }
    Series star;
    star.kind = Series::Kind::Markers;
    star.marker = 'D';
    star.color = Rgb{0.85, 0.10, 0.10};
    star.label = "fit";
    star.x = {bestX};
    star.y = {bestY};
    ax.series.push_back(star);
    ax.legendPos = whole ? "ne" : "none";
    return ax;
  };
  Figure f;
  f.title = title;
  f.axes.push_back(panel(true, xLo, xHi, yLo, yHi));
  if (zoomX > 0 && zoomY > 0) {
    f.cols = 2;
    f.width = 1500;
    f.height = 750;
    f.axes.push_back(panel(false, bestX - zoomX, bestX + zoomX, bestY - zoomY, bestY + zoomY));
  } else {
    f.width = 900;
    f.height = 800;
  }
  saveFigure(f, path);
}

}  // namespace rootsim
