// The pictures of `rootsim compare` and `rootsim fit` (docs/experiments.md).
#include "rootsim/compare_panel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

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
  saveGroupComparePanel(m, {sim}, {traceMm}, {"trace"}, title, caption, path);
}

void saveGroupComparePanel(const Model& m, const std::vector<Snapshot>& sims, const std::vector<Eigen::Matrix3Xd>& tracesMm,
                           const std::vector<std::string>& traceNames, const std::string& title, const std::string& caption,
                           const std::string& path) {
  const double alphaDeg = m.env.plane.alpha / units::deg;
  std::vector<Tube> tubes;
  for (const Snapshot& s : sims) tubes.push_back(fig::tubeOf(s, alphaDeg));
  // one trace: the dark blue line; several: a colour each (the simulation's own colour, 1, left out), and
  // one run per trace drawn in its trace's colour, dashed, beside them
  const bool several = tracesMm.size() > 1;
  const bool paired = several && sims.size() == tracesMm.size();
  auto traceColor = [&](std::size_t i) { return several ? paletteColor(i == 0 ? 0 : static_cast<int>(i) + 1) : kTraceColor; };
  Figure f;
  f.cols = 2;
  f.width = 1200;
  f.title = title + (caption.empty() ? "" : ": " + caption);

  // A: the traces over the simulated roots, on the plate
  Axes plate;
  plate.panelLabel = "A";
  plate.title = "on the plate";
  plate.xlabel = "lateral [mm]";
  plate.ylabel = "downhill [mm]";
  std::vector<Series> trs;
  for (std::size_t k = 0; k < tracesMm.size(); ++k) {
    Series tr;
    for (int i = 0; i < tracesMm[k].cols(); ++i) {
      tr.x.push_back(tracesMm[k](0, i));
      tr.y.push_back(tracesMm[k](1, i));
    }
    tr.color = traceColor(k);
    tr.width = several ? 1.2 : 1.4;
    tr.label = k < traceNames.size() ? literalLabel(traceNames[k]) : std::string();
    trs.push_back(tr);
  }
  // the window bounding both, with a margin of 1 mm
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto grow = [&](double x, double y) {
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  };
  for (const Tube& tube : tubes)
    for (std::size_t i = 0; i < tube.x.size(); ++i) grow(tube.x[i], tube.y[i]);
  for (const Series& tr : trs)
    for (std::size_t i = 0; i < tr.x.size(); ++i) grow(tr.x[i], tr.y[i]);
  const PlateWindow win{x0 - 1.0, x1 + 1.0, y0 - 1.0, y1 + 1.0};
  f.axes.push_back(plate);
  fig::fitHeight(f, f.axes[0], std::clamp(fig::plateAspect(win), 0.6, 2.2), 500, 1100);
  Axes& ax = f.axes[0];
  fig::setPlateAxes(f, ax, win);
  ax.obstacles = fig::obstaclesOf(sceneInfoOf(m));
  ax.tubes = tubes;
  for (const Series& tr : trs) ax.series.push_back(tr);
  // the tube's legend entry: a line of its body colour
  Series simKey;
  simKey.color = Rgb{0.80, 0.62, 0.45};
  simKey.label = paired ? "simulation (one per trace)" : "simulation";
  ax.series.push_back(simKey);
  ax.legendPos = "sw";

  // B: lateral position along downhill, the roots of both
  Axes prof;
  prof.panelLabel = "B";
  prof.title = "lateral position along the plate";
  prof.xlabel = "downhill [mm]";
  prof.ylabel = "lateral [mm]";
  for (std::size_t k = 0; k < tubes.size(); ++k) {
    Series ss;
    ss.x = tubes[k].y;
    ss.y = tubes[k].x;
    ss.color = paired ? traceColor(k) : paletteColor(1);
    ss.dashed = paired;
    ss.width = paired ? 1.2 : 1.8;
    ss.label = k == 0 ? (paired ? "simulation (dashed, its trace's colour)" : "simulation") : std::string();
    prof.series.push_back(ss);
  }
  for (const Series& tr : trs) {
    Series ts = tr;
    ts.x = tr.y;
    ts.y = tr.x;
    prof.series.push_back(ts);
  }
  prof.legendPos = "ne";
  f.axes.push_back(prof);
  saveFigure(f, path);
}

void saveGroupKeysPanel(const std::vector<std::string>& keys, const std::vector<double>& lo, const std::vector<double>& hi,
                        const std::vector<std::vector<GroupKeyValue>>& perKey, const std::string& title,
                        const std::string& dotsLabel, const std::string& path) {
  Figure f;
  f.cols = static_cast<int>(keys.size());
  f.width = 520 * f.cols;
  f.height = 560;
  f.title = title;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    Axes ax;
    ax.panelLabel = std::string(1, static_cast<char>('A' + k % 26));
    ax.title = literalLabel(keys[k]);
    const std::vector<GroupKeyValue>& gs = perKey[k];
    // the groups along a categorical x axis, each named under its column
    for (std::size_t g = 0; g < gs.size(); ++g) ax.xCategories.emplace_back(static_cast<double>(g), literalLabel(gs[g].group));
    ax.xlabel = "group";
    ax.ylabel = literalLabel(keys[k]);
    ax.autoX = ax.autoY = false;
    ax.xmin = -0.6;
    ax.xmax = static_cast<double>(gs.size()) - 0.4;
    // the key's box, widened to any value outside it (a seedling's)
    double y0 = lo[k], y1 = hi[k];
    for (const GroupKeyValue& g : gs)
      for (double v : g.seedlings)
        if (std::isfinite(v)) y0 = std::min(y0, v), y1 = std::max(y1, v);
    const double pad = 0.05 * (y1 - y0);
    ax.ymin = y0 - pad;
    ax.ymax = y1 + pad;
    Series dots, best;
    dots.kind = best.kind = Series::Kind::Markers;
    dots.marker = 'o';
    dots.color = paletteColor(0);
    dots.width = 1.2;
    dots.label = dotsLabel;
    best.marker = 's';
    best.color = paletteColor(1);
    best.width = 2.2;
    best.label = "the group's fit ± σ";
    for (std::size_t g = 0; g < gs.size(); ++g) {
      const double xg = static_cast<double>(g);
      best.x.push_back(xg);
      best.y.push_back(gs[g].value);
      if (std::isfinite(gs[g].sigma)) {
        Series bar;
        bar.x = {xg, xg};
        bar.y = {gs[g].value - gs[g].sigma, gs[g].value + gs[g].sigma};
        bar.color = best.color;
        bar.width = 2.0;
        ax.series.push_back(bar);
      } else {
        ax.notes.push_back({{xg + 0.08, gs[g].value}, "flat"});
      }
      // the seedlings a little to the right of their group's value, spread so that equal values stay apart
      const std::size_t n = gs[g].seedlings.size();
      for (std::size_t i = 0; i < n; ++i) {
        dots.x.push_back(xg + 0.18 + 0.16 * (n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0));
        dots.y.push_back(gs[g].seedlings[i]);
      }
    }
    ax.series.push_back(best);
    ax.series.push_back(dots);
    ax.legendPos = "ne";
    f.axes.push_back(ax);
  }
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

Figure landscapeFigure(const std::vector<LandscapePoint>& pts, const std::string& xKey, const std::string& yKey,
                       double xLo, double xHi, double yLo, double yHi, int gridLevels, double bestX, double bestY,
                       const Eigen::Matrix2d* cov, double zoomX, double zoomY, const std::string& title) {
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
  // the zoom lies inside the box: no wider than it, shifted into it; none when it would be the whole box
  auto window = [](double centre, double half, double lo, double hi) {
    half = std::min(half, 0.5 * (hi - lo));
    const double a = std::clamp(centre - half, lo, hi - 2.0 * half);
    return std::pair<double, double>{a, a + 2.0 * half};
  };
  const auto [zx0, zx1] = window(bestX, zoomX, xLo, xHi);
  const auto [zy0, zy1] = window(bestY, zoomY, yLo, yHi);
  const bool wholeBox = zx1 - zx0 >= (xHi - xLo) * (1 - 1e-9) && zy1 - zy0 >= (yHi - yLo) * (1 - 1e-9);
  if (zoomX > 0 && zoomY > 0 && !wholeBox) {
    f.cols = 2;
    f.width = 1500;
    f.height = 750;
    f.axes.push_back(panel(false, zx0, zx1, zy0, zy1));
  } else {
    f.width = 900;
    f.height = 800;
  }
  return f;
}

void saveLandscapePanel(const std::vector<LandscapePoint>& pts, const std::string& xKey, const std::string& yKey,
                        double xLo, double xHi, double yLo, double yHi, int gridLevels, double bestX, double bestY,
                        const Eigen::Matrix2d* cov, double zoomX, double zoomY, const std::string& title,
                        const std::string& path) {
  saveFigure(landscapeFigure(pts, xKey, yKey, xLo, xHi, yLo, yHi, gridLevels, bestX, bestY, cov, zoomX, zoomY, title), path);
}

}  // namespace rootsim
