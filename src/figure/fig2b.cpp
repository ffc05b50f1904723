// Fig. 2B: five top views of the waving root, against Eqs. 9 and 10; and the cases of Figs. 2B-E (the
// waving root, the free organ, the free organs over beta).
#include "panels.hpp"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "figure_runs.hpp"
#include "panel_draw.hpp"
#include "panel_stats.hpp"
#include "panel_text.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/theory.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

Case wavingCase(const Ctx& c) { return Case{40, 0.2, 0.1, 0, false, c.opt.quick ? 13.1 : 31.1}; }
Case freeCase(const Ctx& c) { return Case{40, 0.2, 0.1, 0, true, c.opt.quick ? 7.1 : 13.1}; }

std::vector<Case> freeOrgans() {
  std::vector<Case> f;
  for (double bt : kFreeBetas) f.push_back(Case{40, bt, 0.1, 0, true, 5.1});
  return f;
}

std::vector<Case> fig2Runs(const Ctx& c) {
  std::vector<Case> b = {wavingCase(c), freeCase(c)};
  for (const Case& k : freeOrgans()) b.push_back(k);
  return b;
}

std::string fig2b(const Ctx& c) {
  const Case w = wavingCase(c);
  runCases(c, fig2Runs(c));
  const auto traj = trajectory(c, w);
  // five snapshots, evenly spaced in time after the first one
  std::vector<const Snapshot*> snaps;
  for (int k = 1; k <= 5; ++k) {
    const double t = traj.back().timeH * k / 5.0;
    const Snapshot* best = &traj.front();
    for (const auto& sn : traj)
      if (std::abs(sn.timeH - t) < std::abs(best->timeH - t)) best = &sn;
    snaps.push_back(best);
  }
  const PlateWindow win = boundingWindow(snaps, w.alpha, 0.4, 1.5);
  Figure f;
  f.cols = 5;
  f.width = 5 * 200 + 40;
  f.title = "Fig. 2B: a waving root growing on a plate tilted by 40° (β = 0.2, γ = 0.1)";
  {
    Axes sample;
    sample.title = "t";
    fitHeight(f, sample, plateAspect(win), 420, 1000);
  }
  for (int k = 0; k < 5; ++k) {
    Axes ax;
    if (k == 0) ax.panelLabel = "B";
    ax.title = "t = " + significantText(std::round(snaps[static_cast<size_t>(k)]->timeH)) + " h";
    ax.xlabel = "lateral [mm]";
    if (k == 0) ax.ylabel = "downhill [mm]";
    addRoot(c, f, ax, *snaps[static_cast<size_t>(k)], w, win);
    f.axes.push_back(ax);
  }
  saveFigure(f, (fs::path(c.opt.out) / "fig2b").string(), c.save());
  const RunResult r = result(c, w);
  const Theory t = theoryFor(modelOf(c, w));
  const double lam = val(r, "wavelength_mm"), A = val(r, "amplitude_mm");
  c.claims->push_back({"Fig. 2B: the root waves (α = 40°, β = 0.2)", "waving", "waving", r.pattern, "pattern",
                       r.pattern == "waving"});
  const double rl = lam / (t.wavelength / units::mm), ra = A / (t.amplitude / units::mm);
  c.claims->push_back({"Eq. 9: wavelength λ = 2 T0 v_tip (α = 40°, β = 0.2)", fmt3(t.wavelength / units::mm) + " mm", "—",
                       fmt3(lam) + " mm (ratio " + fmt3(rl) + ")", kScaleTol, within(rl, kScaleLo, kScaleHi)});
  c.claims->push_back({"Eq. 10: amplitude A = T0 v_tip tan(α) / 2, A peak-to-peak (α = 40°, β = 0.2)",
                       fmt3(t.amplitude / units::mm) + " mm", "—", fmt3(A) + " mm (ratio " + fmt3(ra) + ")", kScaleTol,
                       within(ra, kScaleLo, kScaleHi)});
  return md("fig2b", "Five top views of the waving root, evenly spaced in time, at one scale. λ = " + fmt3(lam) +
                         " mm (Eq. 9: " + fmt3(t.wavelength / units::mm) + " mm), A = " + fmt3(A) + " mm peak-to-peak, A/2 = " +
                         fmt3(val(r, "amplitude_half_mm")) + " mm (Eq. 10: " + fmt3(t.amplitude / units::mm) + " mm).");
}

}  // namespace rootsim::fig
