// Fig. 4A: final top views for increasing intrinsic twist (the root skews); and the twists of Figs. 4A, 4G.
#include "panels.hpp"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "figure_runs.hpp"
#include "panel_draw.hpp"
#include "panel_text.hpp"
#include "rootsim/plot.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

std::vector<double> tauValues(const Ctx& c) {
  return c.opt.quick ? std::vector<double>{0, 0.1, 0.4} : std::vector<double>{0, 0.05, 0.1, 0.2, 0.4, 0.8};
}

std::string fig4a(const Ctx& c) {
  std::vector<Case> cs;
  for (double t : tauValues(c)) cs.push_back(Case{30, 0.2, 0.1, t, false, c.opt.quick ? 12.0 : 20.0});
  runCases(c, cs);
  std::vector<std::vector<Snapshot>> traj;
  std::vector<const Snapshot*> finals;
  for (const auto& k : cs) traj.push_back(trajectory(c, k));
  for (const auto& t : traj) finals.push_back(&t.back());
  const PlateWindow win = boundingWindow(finals, 30, 0.4, 1.5);
  Figure f;
  f.cols = static_cast<int>(cs.size());
  f.width = 220 * f.cols + 40;
  f.title = "Fig. 4A: skewing with intrinsic twist (α = 30°, β = 0.2, γ = 0.1)";
  {
    Axes sample;
    sample.title = "ω";
    fitHeight(f, sample, plateAspect(win), 420, 1000);
  }
  std::string table = "| R τ | ω T0 | skew ⟨θ⟩ (deg) | pattern |\n|---|---|---|---|\n";
  std::vector<double> skews;
  for (size_t i = 0; i < cs.size(); ++i) {
    const RunResult r = result(c, cs[i]);
    Axes ax;
    if (i == 0) ax.panelLabel = "A";
    ax.title = "ωT_0 = " + fmt3(val(r, "omega_T0"));
    ax.xlabel = "lateral [mm]";
    if (i == 0) ax.ylabel = "downhill [mm]";
    addRoot(c, f, ax, *finals[i], cs[i], win);
    f.axes.push_back(ax);
    skews.push_back(std::abs(val(r, "skew_deg")));
    table += "| " + significantText(cs[i].rTau) + " | " + fmt3(val(r, "omega_T0")) + " | " + fmt3(val(r, "skew_deg")) + " | " +
             r.pattern + " |\n";
  }
  saveFigure(f, (fs::path(c.opt.out) / "fig4a").string(), c.save());
  bool grows = skews.back() > skews.front() + 5;
  c.claims->push_back({"Fig. 4A: intrinsic twist makes the root skew; skew grows with ω T0", "—", "skew grows with ω T0",
                       "skew magnitude from " + fmt3(skews.front()) + "° (τ = 0) to " + fmt3(skews.back()) + "°",
                       "last > first + 5°", grows});
  return md("fig4a", "Final top views for increasing intrinsic twist: the root skews to one side.", table);
}

}  // namespace rootsim::fig
