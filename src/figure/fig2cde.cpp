// Figs. 2C-E: tip angle, growth-zone energies and topology of the waving root and the free organ; Eq. 7's
// turning time and exponent from the free organs.
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
#include "rootsim/theory.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

std::string fig2cde(const Ctx& c) {
  const Case w = wavingCase(c), fr = freeCase(c);
  runCases(c, fig2Runs(c));
  const std::vector<double>& betas = kFreeBetas;
  const std::vector<Case> frees = freeOrgans();
  const CsvColumns sw = series(c, w), sf = series(c, fr);
  const std::vector<double>& t = column(sw, "time_h");
  const std::vector<double>& th = column(sw, "theta_tip_deg");
  const std::vector<double>& wr = column(sw, "Wr");
  const std::vector<double>& tw = column(sw, "Tw");
  const std::vector<double>& tf = column(sf, "time_h");
  const std::vector<double>& thf = column(sf, "theta_tip_deg");
  std::vector<double> eb, et;  // [nJ]
  for (double e : column(sw, "Eb")) eb.push_back(e * 1e9);
  for (double e : column(sw, "Et")) et.push_back(e * 1e9);
  const Theory theo = theoryFor(modelOf(c, w));
  Figure f;
  f.width = 1100;
  f.height = 1050;
  f.rows = 3;
  Axes a, b, d;
  a.panelLabel = "C";
  a.title = "tip angle: root on the plate vs free organ";
  a.xlabel = "time [h]";
  a.ylabel = "θ^{tip} [deg]";
  a.series.push_back(line(t, th, 0, "on the plate: planar tip angle"));
  a.series.push_back(line(tf, thf, 1, "free organ: angle from gravity"));
  a.series.push_back(line({theo.T0 / units::hour, theo.T0 / units::hour}, {-90, 90}, 7, "T_0 (Eq. 7)", true));
  a.legendPos = "se";
  b.panelLabel = "D";
  b.title = "growth-zone energies (no factor 1/2)";
  b.xlabel = "time [h]";
  b.ylabel = "energy [nJ]";
  b.series.push_back(line(t, eb, 0, "bending E_b"));
  b.series.push_back(line(t, et, 1, "twisting E_t"));
  d.panelLabel = "E";
  d.title = "growth-zone topology";
  d.xlabel = "time [h]";
  d.ylabel = "Wr, Tw [turns]";
  d.series.push_back(line(t, wr, 2, "writhe Wr"));
  d.series.push_back(line(t, tw, 3, "twist Tw"));
  f.axes = {a, b, d};
  saveFigure(f, (fs::path(c.opt.out) / "fig2cde").string(), c.save());

  const RunResult r = result(c, w), rf = result(c, fr);
  const double snap = val(r, "first_snap_or_turning_h"), turn = val(rf, "first_snap_or_turning_h");
  // the free organ's oscillation: the largest |theta| between crossings of the vertical
  std::vector<double> lobes;
  for (size_t i = 1; i < thf.size(); ++i) {
    if (thf[i] * thf[i - 1] < 0) lobes.push_back(0);
    if (!lobes.empty()) lobes.back() = std::max(lobes.back(), std::abs(thf[i]));
  }
  const bool decays = lobes.size() >= 3 && lobes[1] < lobes[0];
  double late = 0;  // the waving root's swing in the last third
  for (size_t i = 2 * th.size() / 3; i < th.size(); ++i) late = std::max(late, std::abs(th[i]));
  const double T0h = theo.T0 / units::hour;
  const Model mw = modelOf(c, w);
  const double vtipMmH = mw.growth.rate * mw.growth.zoneLength * units::hour / units::mm;  // v_tip [mm/h]
  c.claims->push_back({"Eq. 7: first sideways snap at the turning time T0 (α = 40°, β = 0.2)", fmt3(T0h) + " h", "≈ T0",
                       fmt3(snap) + " h (ratio " + fmt3(snap / T0h) + ")", kScaleTol, within(snap / T0h, kScaleLo, kScaleHi)});
  // Eq. 7's exponent from the free organs run above
  std::string table = "Free organ (α = 40°, γ = 0.1) reaching the vertical, against Eq. 7:\n\n"
                      "| β | β Lgz/R | T0 Eq. 7 (h) | turning time (h) | ratio |\n|---|---|---|---|---|\n";
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int nfit = 0;
  for (const auto& k : frees) {
    const RunResult rk = result(c, k);
    const double g = val(rk, "effective_gain"), T = val(rk, "first_snap_or_turning_h"), T0k = val(rk, "T0_h");
    table += "| " + significantText(k.beta) + " | " + significantText(g) + " | " + fmt3(T0k) + " | " + fmt3(T) + " | " + fmt3(T / T0k) + " |\n";
    if (!std::isfinite(T)) continue;
    const double x = std::log(g), y = std::log(T);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
    ++nfit;
  }
  const double slope = nfit >= 2 ? (nfit * sxy - sx * sy) / (nfit * sxx - sx * sx) : NAN;
  // turning time / T0 at the ends of the beta range, and the local exponents there
  std::vector<double> Tf, gf;
  for (const auto& k : frees) {
    const RunResult rk = result(c, k);
    Tf.push_back(val(rk, "first_snap_or_turning_h") / val(rk, "T0_h"));
    gf.push_back(val(rk, "effective_gain"));
  }
  auto localExp = [&](size_t i, size_t j) {
    return std::log(Tf[j] / Tf[i]) / std::log(gf[j] / gf[i]) - 0.6;  // Tf is T / T0 and T0 ~ g^-0.6
  };
  const double eLo = localExp(0, 1), eHi = localExp(Tf.size() - 2, Tf.size() - 1);
  const double halfWave = val(r, "wavelength_mm") / (2 * vtipMmH);  // time to grow half a wave [h]
  c.claims->push_back({"Eq. 7: the free organ reaches the vertical at T0 (α = 40°, β = 0.2)", fmt3(T0h) + " h", "≈ T0",
                       fmt3(turn) + " h (ratio " + fmt3(turn / T0h) + ")", kScaleTol, within(turn / T0h, kScaleLo, kScaleHi),
                       "Eq. 7 is a scaling law (the paper writes ∼): its π/2 prefactor and −3/5 exponent are the paper's "
                       "fit to its own free-organ runs (SI 5), derived with γ = 0. On the plate the same root snaps first "
                       "at " + fmt3(snap / T0h) + " T0 and grows half a wave in λ / (2 v_tip) = " + fmt3(halfWave / T0h) +
                       " T0, as Eq. 7's T0 says (Eqs. 7, 9 hold); the free organ crosses the vertical earlier, and its "
                       "turning time / T0 drifts with β from " + fmt3(Tf.front()) + " (β = " + significantText(betas.front()) +
                       ") to " + fmt3(Tf.back()) + " (β = " + significantText(betas.back()) + "; table under fig2cde), so no O(1) "
                       "prefactor makes Eq. 7 hold for all β. The crossing time is interpolated between growth steps; "
                       "docs/claims.md lists the full-resolution runs (γ = 0 and a horizontal start included) that "
                       "give the same picture."});
  c.claims->push_back({"Eq. 7: the free organ's turning time ∝ (β Lgz/R)^(−3/5) (β = 0.05 … 1)", "exponent −0.6",
                       "−3/5 (fit to the paper's free-organ runs, SI 5)",
                       "exponent " + fmt3(slope) + " (least squares over " + std::to_string(nfit) + " runs; ratio " +
                           fmt3(slope / -0.6) + ")",
                       std::string(kScaleTol) + " of the exponent", within(slope / -0.6, kScaleLo, kScaleHi),
                       "The local exponent steepens with the gain: " + fmt3(eLo) + " between β = " + significantText(betas[0]) +
                           " and " + significantText(betas[1]) + ", " + fmt3(eHi) + " between β = " + significantText(betas[betas.size() - 2]) +
                           " and " + significantText(betas.back()) + ". This model, as docs/model.md specifies it, does not reproduce "
                           "the paper's fitted −3/5; not refitted."});
  // Fig. 2C: "both profiles present oscillations with a similar period": the mean time between crossings
  // of theta_tip = 0 (half a period), for the waving root after its first snap and for the free organ
  const double halfW = meanSpacing(zeroCrossings(t, th, snap)), halfF = meanSpacing(zeroCrossings(tf, thf, 0));
  c.claims->push_back({"Fig. 2C: the free organ and the waving root oscillate with a similar period", "ratio 1",
                       "similar period", "half-periods " + fmt3(halfF) + " h (free) / " + fmt3(halfW) + " h (waving): ratio " +
                           fmt3(halfF / halfW),
                       kRatioTol, within(halfF / halfW, kRatioLo, kRatioHi)});
  c.claims->push_back({"Fig. 2C: the free organ's oscillation decays, the waving one does not", "—", "decays / persists",
                       "free lobes " + (lobes.size() >= 2 ? fmt3(lobes[0]) + "°, " + fmt3(lobes[1]) + "°" : std::string("n/a")) +
                           "; waving swing in the last third " + fmt3(late) + "°",
                       "second lobe smaller; waving swing > 20°", decays && late > 20});
  table += "\nMeasured exponent of the turning time against β Lgz/R: " + fmt3(slope) +
           " (Eq. 7: −0.6). Half-periods of θ_tip: free organ " + fmt3(halfF) + " h, waving root " + fmt3(halfW) +
           " h; λ / (2 v_tip) = " + fmt3(val(r, "wavelength_mm") / (2 * vtipMmH)) + " h; T0 = " + fmt3(T0h) + " h.\n";
  return md("fig2cde", "(C) tip angle of the waving root and of the free organ; (D) bending and twisting energy of the "
                       "growth zone; (E) its writhe and twist. Each sideways snap releases bending energy.",
         table);
}

}  // namespace rootsim::fig
