// Fig. 4G: the skewing angle against the apex twist rate, with the limits of Eqs. 14 and 15.
#include "panels.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "figure_runs.hpp"
#include "panel_draw.hpp"
#include "panel_stats.hpp"
#include "panel_text.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

std::string fig4g(const Ctx& c) {
  const std::vector<double> alphas = c.opt.quick ? std::vector<double>{30} : std::vector<double>{20, 30};
  std::vector<Case> cs;
  for (double a : alphas)
    for (double t : tauValues(c))
      if (t > 0) cs.push_back(Case{a, 0.2, 0.1, t, false, c.opt.quick ? 12.0 : 20.0});
  runCases(c, cs);
  Axes ax;
  ax.panelLabel = "G";
  ax.xlabel = "ωT_0 · R/L_{gz}";
  ax.ylabel = "sin⟨θ⟩ / tan α";
  std::string table = "| α | R τ | ω T0 | skew (deg) | sin⟨θ⟩ / tan α |\n|---|---|---|---|---|\n";
  double xmax = 0, largeRatio = NAN, largeWT = 0;
  for (size_t ia = 0; ia < alphas.size(); ++ia) {
    std::vector<double> x, y;
    for (const auto& k : cs) {
      if (k.alpha != alphas[ia]) continue;
      const RunResult r = result(c, k);
      const double wt = val(r, "omega_T0"), sk = val(r, "skew_deg") * units::deg;
      x.push_back(wt * 0.1);  // R / Lgz = 0.1
      y.push_back(std::abs(std::sin(sk)) / std::tan(k.alpha * units::deg));
      xmax = std::max(xmax, x.back());
      if (wt > largeWT) { largeWT = wt; largeRatio = y.back(); }
      table += "| " + significantText(k.alpha) + " | " + significantText(k.rTau) + " | " + fmt3(wt) + " | " + fmt3(val(r, "skew_deg")) + " | " +
               fmt3(y.back()) + " |\n";
    }
    ax.series.push_back(points(x, y, static_cast<int>(ia), ia ? 's' : 'o', "α = " + significantText(alphas[ia]) + "°"));
  }
  std::vector<double> gx, g14;
  for (double x = 0; x <= 1.1 * xmax + 1e-9; x += xmax / 200) {
    gx.push_back(x);
    g14.push_back(x * 10.0);  // Eq. 14: sin<theta>/tan(alpha) = omega T0 = x Lgz / R
  }
  ax.series.push_back(line(gx, g14, 2, "Eq. 14 (ωT_0 ≪ 1)", true));
  ax.series.push_back(line({0, 1.1 * xmax}, {1, 1}, 7, "Eq. 15 (ωT_0 ≫ 1)", true));
  ax.autoY = false;
  ax.ymin = -0.05;
  ax.ymax = 1.5;
  ax.legendPos = "se";
  Figure f;
  f.title = "Fig. 4G: skewing angle vs apex twist rate";
  f.width = 800;
  f.height = 620;
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / "fig4g").string(), c.save());
  c.claims->push_back({"Eq. 15: sin⟨θ⟩ → tan α for ω T0 ≫ 1", "ratio 1", "≈ 1 (Fig. 4G)",
                       "sin⟨θ⟩ / tan α = " + fmt3(largeRatio) + " at ω T0 = " + fmt3(largeWT), kRatioTol,
                       within(largeRatio, kRatioLo, kRatioHi)});
  return md("fig4g", "Skewing angle against the apex twist rate, with the limits of Eqs. 14 and 15.", table);
}

}  // namespace rootsim::fig
