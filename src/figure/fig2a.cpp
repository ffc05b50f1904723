// Fig. 2A: final shapes on the plate over the tilt, and the transition angles straight -> waving -> coiling
// bracketed on that grid and bisected, against Eqs. 12 and 13.
#include "panels.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "figure_runs.hpp"
#include "panel_draw.hpp"
#include "panel_text.hpp"
#include "transitions.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/theory.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

std::string fig2a(const Ctx& c) {
  // the paper's ten tilts; quick: the quick phase grid, so these runs are shared with fig3d
  std::vector<double> alphas;
  for (double a = 0; a <= 90 + 1e-9; a += c.opt.quick ? c.alphaStep() : 10) alphas.push_back(a);
  const double L = c.opt.quick ? 12 : 15;
  std::vector<Case> cases;
  for (double a : alphas) cases.push_back(Case{a, 0.1, 0.1, 0, false, L});
  // the shipped Fig. 2A scene as it is (scenes/fig2a_alpha40.toml: 10 mm), run in the same batch
  const Case short40{40, 0.1, 0.1, 0, false, 10};
  {
    std::vector<Case> batch = cases;
    batch.push_back(short40);
    runCases(c, batch);
  }
  std::vector<std::vector<Snapshot>> traj;
  std::vector<const Snapshot*> finals;
  for (const auto& k : cases) traj.push_back(trajectory(c, k));
  for (const auto& t : traj) finals.push_back(&t.back());
  // one window for all panels, so the shapes compare at one scale
  PlateWindow win{1e9, -1e9, 1e9, -1e9};
  for (size_t i = 0; i < cases.size(); ++i) {
    const PlateWindow w = boundingWindow({finals[i]}, cases[i].alpha, 0.4, 1.5);
    win.lateralMin = std::min(win.lateralMin, w.lateralMin - 0.5 * (w.lateralMin + w.lateralMax));
    win.lateralMax = std::max(win.lateralMax, w.lateralMax - 0.5 * (w.lateralMin + w.lateralMax));
    win.downhillMin = std::min(win.downhillMin, w.downhillMin);
    win.downhillMax = std::max(win.downhillMax, w.downhillMax);
  }
  Figure f;
  f.cols = static_cast<int>(cases.size());
  f.width = 170 * f.cols + 40;
  f.title = "Fig. 2A: final shapes on the plate (β = γ = 0.1; pink +d_1, orange −d_1; downhill is down)";
  {
    Axes sample;
    sample.title = "α";
    fitHeight(f, sample, plateAspect(win), 420, 1000);
  }
  std::string table = "| α (deg) | pattern | λ (mm) | A peak-to-peak (mm) | θ range (deg) |\n|---|---|---|---|---|\n";
  bool straight0 = false;
  for (size_t i = 0; i < cases.size(); ++i) {
    const RunResult r = result(c, cases[i]);
    Axes ax;
    if (i == 0) ax.panelLabel = "A";
    ax.title = "α = " + significantText(cases[i].alpha) + "°";
    ax.xlabel = "lateral [mm]";
    if (i == 0) ax.ylabel = "downhill [mm]";
    // centre each root laterally in the common window
    PlateWindow w = win;
    const PlateWindow own = boundingWindow({finals[i]}, cases[i].alpha, 0.4, 1.5);
    const double cx = 0.5 * (own.lateralMin + own.lateralMax);
    w.lateralMin += cx;
    w.lateralMax += cx;
    addRoot(c, f, ax, *finals[i], cases[i], w);
    // the pattern found, at the bottom of the view
    ax.notes.push_back({{0.5 * (ax.xmin + ax.xmax), ax.ymax - 0.03 * (ax.ymax - ax.ymin)}, r.pattern});
    f.axes.push_back(ax);
    const std::string pat = r.pattern;
    if (cases[i].alpha == 0) straight0 = pat == "straight";
    table += "| " + significantText(cases[i].alpha) + " | " + pat + " | " + fmt3(val(r, "wavelength_mm")) + " | " +
             fmt3(val(r, "amplitude_mm")) + " | " + significantText(std::round(val(r, "theta_min_deg"))) + " .. " +
             significantText(std::round(val(r, "theta_max_deg"))) + " |\n";
  }
  saveFigure(f, (fs::path(c.opt.out) / "fig2a").string(), c.save());
  const Theory t = theoryFor(modelOf(c, cases[0]));
  c.claims->push_back({"Fig. 2A: α = 0 grows straight", "straight", "straight", straight0 ? "straight" : "not straight",
                       "pattern", straight0});
  // the transition angles: bracketed by the grid above, then bisected to a quarter of the phase step
  std::vector<double> gridA;
  std::vector<std::string> gridP;
  for (const auto& k : cases) {
    gridA.push_back(k.alpha);
    gridP.push_back(result(c, k).pattern);
  }
  Transition sw, wc;
  sw.above = [](const std::string& p) { return p != "straight"; };
  wc.above = [](const std::string& p) { return p == "coiling"; };
  bracket(sw, gridA, gridP);
  bracket(wc, gridA, gridP);
  const double width = c.alphaStep() / 4;
  bisect(c, cases[0], {&sw, &wc}, width);
  const double step = c.alphaStep();
  auto transitionClaim = [&](const std::string& what, const Transition& tr, double theoryDeg, const std::string& eq,
                             const std::string& paper) {
    const double mid = 0.5 * (tr.lo + tr.hi);
    const std::string meas = std::isfinite(mid) ? fmt3(mid) + "° (bracket " + significantText(tr.lo) + "° … " + significantText(tr.hi) + "°, " +
                                                      std::to_string(tr.runs) + " bisection runs)"
                                                : "no bracket on the grid";
    c.claims->push_back({what, fmt3(theoryDeg) + "° (" + eq + ")", paper, meas,
                         "within the phase step (" + significantText(step) + "°) of " + eq, std::abs(mid - theoryDeg) <= step});
  };
  transitionClaim("Fig. 2A: waving sets in at α_s→w (β = 0.1), by bisection", sw, t.alphaStraightToWave / units::deg, "Eq. 12",
                  "≈ 15°");
  transitionClaim("Fig. 2A: coiling sets in at α_w→c (β = 0.1), by bisection", wc, t.alphaWaveToCoil / units::deg, "Eq. 13",
                  "≈ 50°");
  // the Fig. 2A scene as shipped: a short root that waves
  const RunResult rs = result(c, short40);
  c.claims->push_back({"Fig. 2A: the 10 mm root at α = 40° (β = γ = 0.1) waves", "waving", "waving (Fig. 2A)",
                       rs.pattern + " (" + significantText(rs.lateralPeaks) + " lateral peaks, θ " +
                           significantText(std::round(val(rs, "theta_min_deg"))) + "° … " + significantText(std::round(val(rs, "theta_max_deg"))) +
                           "°, mean angle " + fmt3(val(rs, "skew_deg")) + "°)",
                       "pattern", rs.pattern == "waving"});
  table += "\nTransition angles by bisection (the grid's bracket halved down to " + significantText(width) +
           "°; each row one run):\n\n| α (deg) | pattern |\n|---|---|\n" + sw.log + wc.log;
  return md("fig2a", "Final top views for increasing tilt. Theory (Eqs. 12, 13) at β Lgz/R = " + significantText(t.effectiveGain) +
                         ": straight → waving at " + fmt3(t.alphaStraightToWave / units::deg) + "°, waving → coiling at " +
                         fmt3(t.alphaWaveToCoil / units::deg) + "°. Measured by bisection: straight → waving between " +
                         significantText(sw.lo) + "° and " + significantText(sw.hi) + "°, waving → coiling between " + significantText(wc.lo) + "° and " +
                         significantText(wc.hi) + "°.",
         table);
}

}  // namespace rootsim::fig
