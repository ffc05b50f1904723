// Figs. 3A and 3B: the scaling runs over beta and alpha, measured max curvature against Eq. 8 and
// wavelength against 4 A cot alpha (Eq. 11), each on an identity plot.
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

std::vector<Case> scalingCases(const Ctx& c) {
  const std::vector<double> betas = c.opt.quick ? std::vector<double>{0.1, 0.2, 0.5} : std::vector<double>{0.05, 0.1, 0.2, 0.5, 1.0};
  const std::vector<double> alphas = c.opt.quick ? std::vector<double>{30, 40} : std::vector<double>{20, 30, 40};
  std::vector<Case> cs;
  for (double b : betas)
    for (double a : alphas) cs.push_back(Case{a, b, 0.1, 0, false, c.opt.quick ? 14.0 : 20.0});
  return cs;
}

namespace {
// measured against predicted with the identity line
void identityPlot(const Ctx& c, const std::string& name, const std::string& letter, const std::string& title, const std::string& xl,
                  const std::string& yl, const std::vector<double>& x, const std::vector<double>& y, int color, char mark,
                  const std::string& label, const std::string& lineLabel) {
  double hi = 0.5;
  for (double v : x) if (std::isfinite(v)) hi = std::max(hi, v);
  for (double v : y) if (std::isfinite(v)) hi = std::max(hi, v);
  Figure f;
  f.width = 700;
  f.height = 640;
  f.title = title;
  Axes ax;
  ax.panelLabel = letter;
  ax.xlabel = xl;
  ax.ylabel = yl;
  ax.autoX = ax.autoY = false;
  ax.xmin = ax.ymin = 0;
  ax.xmax = ax.ymax = 1.08 * hi;
  ax.series.push_back(points(x, y, color, mark, label));
  ax.series.push_back(line({0, 1.08 * hi}, {0, 1.08 * hi}, 7, lineLabel, true));
  ax.legendPos = "nw";
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / name).string(), c.save());
}
}  // namespace

std::string fig3a(const Ctx& c) {
  const auto cs = scalingCases(c);
  runCases(c, cs);
  // Eq. 6 is about waving patterns: only the runs that wave are plotted and counted
  std::vector<double> pred, meas, ratio;
  std::string table = "| α | β | pattern | max κ measured (1/mm) | Eq. 8 (1/mm) | ratio |\n|---|---|---|---|---|---|\n";
  for (const auto& k : cs) {
    const RunResult r = result(c, k);
    const double p = val(r, "max_kappa_eq8_per_mm"), mk = val(r, "max_kappa_per_mm");
    table += "| " + significantText(k.alpha) + " | " + significantText(k.beta) + " | " + r.pattern + " | " + fmt3(mk) + " | " + fmt3(p) +
             " | " + fmt3(mk / p) + " |\n";
    if (r.pattern != "waving") continue;
    pred.push_back(p);
    meas.push_back(mk);
    ratio.push_back(mk / p);
  }
  identityPlot(c, "fig3a", "A", "Fig. 3A: max curvature vs Eq. 8", "max κ_f^0 = T_0 (ε̇_0/R) β sin α [1/mm]", "measured max κ [1/mm]", pred,
               meas, 0, 'o', "waving simulations (γ = 0.1)", "y = x");
  const double med = median(ratio);
  c.claims->push_back({"Eq. 8 (Fig. 3A): max κ ≈ T0 (ε̇0/R) β sin α", "ratio 1", "ratio ≈ 1",
                       "median ratio " + fmt3(med) + " over " + std::to_string(ratio.size()) + " waving runs (" +
                           countWithin(ratio, kScaleLo, kScaleHi) + " ±25 %)",
                       kScaleTol, within(med, kScaleLo, kScaleHi)});
  return md("fig3a", "Measured maximum projected curvature of the final shape against Eq. 8 (waving runs only: Eq. 6 is "
                     "about waving patterns).", table);
}

std::string fig3b(const Ctx& c) {
  const auto cs = scalingCases(c);
  runCases(c, cs);
  std::vector<double> x, y, r11, r9, r10;
  std::string table = "| α | β | pattern | λ (mm) | A (mm) | A/2 (mm) | 4A cot α (mm) | λ / 4A cot α | Eq. 9 λ (mm) | "
                      "Eq. 10 A (mm) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& k : cs) {
    const RunResult r = result(c, k);
    const double lam = val(r, "wavelength_mm"), A = val(r, "amplitude_mm");
    const double pred = 4 * A / std::tan(k.alpha * units::deg);
    table += "| " + significantText(k.alpha) + " | " + significantText(k.beta) + " | " + r.pattern + " | " + fmt3(lam) + " | " + fmt3(A) +
             " | " + fmt3(val(r, "amplitude_half_mm")) + " | " + fmt3(pred) + " | " + fmt3(lam / pred) + " | " +
             fmt3(val(r, "wavelength_eq9_mm")) + " | " + fmt3(val(r, "amplitude_eq10_mm")) + " |\n";
    if (r.pattern != "waving" || !std::isfinite(lam) || !std::isfinite(A)) continue;
    x.push_back(pred);
    y.push_back(lam);
    r11.push_back(lam / pred);
    r9.push_back(lam / val(r, "wavelength_eq9_mm"));
    r10.push_back(A / val(r, "amplitude_eq10_mm"));
  }
  identityPlot(c, "fig3b", "B", "Fig. 3B: wavelength vs 4 A cot α (Eq. 11), A peak-to-peak", "4 A cot α [mm]",
               "wavelength λ [mm]", x, y, 1, 's', "waving simulations", "Eq. 11: λ = 4 A cot α");
  const std::string over = " over " + std::to_string(r11.size()) + " waving runs (";
  const double m11 = median(r11), m9 = median(r9), m10 = median(r10);
  c.claims->push_back({"Eq. 11 (Fig. 3B): λ ≈ 4 A cot α, A peak-to-peak", "ratio 1", "ratio ≈ 1",
                       "median λ / (4 A cot α) " + fmt3(m11) + over + countWithin(r11, kRatioLo, kRatioHi) + ")",
                       kRatioTol, within(m11, kRatioLo, kRatioHi)});
  c.claims->push_back({"Eq. 9 over the Fig. 3 runs: λ ≈ 2 T0 v_tip", "ratio 1", "tested in SI 5",
                       "median ratio " + fmt3(m9) + over + countWithin(r9, kScaleLo, kScaleHi) + " ±25 %)", kScaleTol,
                       within(m9, kScaleLo, kScaleHi)});
  c.claims->push_back({"Eq. 10 over the Fig. 3 runs: A ≈ T0 v_tip tan(α) / 2, A peak-to-peak", "ratio 1", "tested in SI 5",
                       "median ratio " + fmt3(m10) + over + countWithin(r10, kScaleLo, kScaleHi) + " ±25 %)", kScaleTol,
                       within(m10, kScaleLo, kScaleHi)});
  return md("fig3b", "Wavelength against 4 A cot α for the runs that wave. λ is the mean downhill distance between "
                     "successive lateral peaks on the same side; A is the mean lateral distance between neighbouring "
                     "(opposite) peaks, the peak-to-peak excursion, as the paper's Fig. 3B caption measures it "
                     "(\"distances between neighboring peaks ... normal to the downhill direction\"); A/2 is listed "
                     "beside it. The paper's triangle argument for Eq. 10 would call that excursion 2A; with A/2 in "
                     "place of A, λ / (4 A cot α) would double. This is the paper's own inconsistency (docs/model.md, "
                     "Observables); the caption's definition is the one its Fig. 3B plots.",
         table);
}

}  // namespace rootsim::fig
