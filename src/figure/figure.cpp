// The paper's figure panels (docs/model.md, Paper cases): each panel names its cases (figure_cases.hpp), runs
// them (figure_runs.hpp), then plots them beside theory and adds its claims to the report.
#include "rootsim/figure.hpp"

#include "figure_cases.hpp"
#include "figure_runs.hpp"
#include "panel_draw.hpp"
#include "panel_stats.hpp"
#include "panel_text.hpp"
#include "transitions.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "rootsim/environment.hpp"
#include "rootsim/errors.hpp"
#include "rootsim/write_rule.hpp"
#include "rootsim/outputs.hpp"
#include "rootsim/model.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/results.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/sweep.hpp"
#include "rootsim/theory.hpp"
#include "rootsim/units.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {

using namespace fig;

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
  PlateWindow win{1e9, -1e9, 1e9, -1e9, 0, 0};
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
  f.height = 780;
  f.title = "Fig. 2A: final shapes on the plate (β = γ = 0.1, 1 mm grid; downhill is down)";
  std::string table = "| α (deg) | pattern | λ (mm) | A peak-to-peak (mm) | θ range (deg) |\n|---|---|---|---|---|\n";
  bool straight0 = false;
  for (size_t i = 0; i < cases.size(); ++i) {
    const RunResult r = result(c, cases[i]);
    Axes ax;
    ax.panelLabel = std::string(1, static_cast<char>('a' + i));
    ax.title = "α = " + num(cases[i].alpha) + "°";
    ax.xlabel = r.pattern;
    // centre each root laterally in the common window
    PlateWindow w = win;
    const PlateWindow own = boundingWindow({finals[i]}, cases[i].alpha, 0.4, 1.5);
    const double cx = 0.5 * (own.lateralMin + own.lateralMax);
    w.lateralMin += cx;
    w.lateralMax += cx;
    addRoot(c, f, ax, *finals[i], cases[i], w, {0.3, 0.3, 0.32});
    f.axes.push_back(ax);
    const std::string pat = r.pattern;
    if (cases[i].alpha == 0) straight0 = pat == "straight";
    table += "| " + num(cases[i].alpha) + " | " + pat + " | " + fmt3(val(r, "wavelength_mm")) + " | " +
             fmt3(val(r, "amplitude_mm")) + " | " + num(std::round(val(r, "theta_min_deg"))) + " .. " +
             num(std::round(val(r, "theta_max_deg"))) + " |\n";
  }
  saveFigure(f, (fs::path(c.opt.out) / "fig2a").string());
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
    const std::string meas = std::isfinite(mid) ? fmt3(mid) + "° (bracket " + num(tr.lo) + "° … " + num(tr.hi) + "°, " +
                                                      std::to_string(tr.runs) + " bisection runs)"
                                                : "no bracket on the grid";
    c.claims->push_back({what, fmt3(theoryDeg) + "° (" + eq + ")", paper, meas,
                         "within the phase step (" + num(step) + "°) of " + eq, std::abs(mid - theoryDeg) <= step});
  };
  transitionClaim("Fig. 2A: waving sets in at α_s→w (β = 0.1), by bisection", sw, t.alphaStraightToWave / units::deg, "Eq. 12",
                  "≈ 15°");
  transitionClaim("Fig. 2A: coiling sets in at α_w→c (β = 0.1), by bisection", wc, t.alphaWaveToCoil / units::deg, "Eq. 13",
                  "≈ 50°");
  // the Fig. 2A scene as shipped: a short root that waves
  const RunResult rs = result(c, short40);
  c.claims->push_back({"Fig. 2A: the 10 mm root at α = 40° (β = γ = 0.1) waves", "waving", "waving (Fig. 2A)",
                       rs.pattern + " (" + num(rs.lateralPeaks) + " lateral peaks, θ " +
                           num(std::round(val(rs, "theta_min_deg"))) + "° … " + num(std::round(val(rs, "theta_max_deg"))) +
                           "°, mean angle " + fmt3(val(rs, "skew_deg")) + "°)",
                       "pattern", rs.pattern == "waving"});
  table += "\nTransition angles by bisection (the grid's bracket halved down to " + num(width) +
           "°; each row one run):\n\n| α (deg) | pattern |\n|---|---|\n" + sw.log + wc.log;
  return md("fig2a", "Final top views for increasing tilt. Theory (Eqs. 12, 13) at β Lgz/R = " + num(t.effectiveGain) +
                         ": straight → waving at " + fmt3(t.alphaStraightToWave / units::deg) + "°, waving → coiling at " +
                         fmt3(t.alphaWaveToCoil / units::deg) + "°. Measured by bisection: straight → waving between " +
                         num(sw.lo) + "° and " + num(sw.hi) + "°, waving → coiling between " + num(wc.lo) + "° and " +
                         num(wc.hi) + "°.",
         table);
}

Case wavingCase(const Ctx& c) { return Case{40, 0.2, 0.1, 0, false, c.opt.quick ? 13.1 : 31.1}; }
Case freeCase(const Ctx& c) { return Case{40, 0.2, 0.1, 0, true, c.opt.quick ? 7.1 : 13.1}; }
// free organs over the paper's range of beta (Lgz/R = 10), 20 h of growth each: Eq. 7's exponent
const std::vector<double> kFreeBetas = {0.05, 0.1, 0.2, 0.5, 1.0};
std::vector<Case> freeOrgans() {
  std::vector<Case> f;
  for (double bt : kFreeBetas) f.push_back(Case{40, bt, 0.1, 0, true, 5.1});
  return f;
}
// every run of fig2b and fig2cde, in one batch (so both jobs stay busy)
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
  f.height = 820;
  f.title = "Fig. 2B: a waving root growing on a plate tilted by 40° (β = 0.2, γ = 0.1)";
  for (int k = 0; k < 5; ++k) {
    Axes ax;
    ax.panelLabel = std::string(1, static_cast<char>('a' + k));
    ax.title = "t = " + num(std::round(snaps[static_cast<size_t>(k)]->timeH)) + " h";
    ax.xlabel = "lateral (mm)";
    if (k == 0) ax.ylabel = "downhill (mm)";
    addRoot(c, f, ax, *snaps[static_cast<size_t>(k)], w, win, paletteColor(0));
    f.axes.push_back(ax);
  }
  saveFigure(f, (fs::path(c.opt.out) / "fig2b").string());
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
  a.xlabel = "time (h)";
  a.ylabel = "θ_tip (deg)";
  a.series.push_back(line(t, th, 0, "on the plate: planar tip angle"));
  a.series.push_back(line(tf, thf, 1, "free organ: angle from gravity"));
  a.series.push_back(line({theo.T0 / units::hour, theo.T0 / units::hour}, {-90, 90}, 7, "T0 (Eq. 7)", true));
  a.legendPos = "se";
  b.panelLabel = "D";
  b.title = "growth-zone energies (no factor 1/2)";
  b.xlabel = "time (h)";
  b.ylabel = "energy (nJ)";
  b.series.push_back(line(t, eb, 0, "bending Eb"));
  b.series.push_back(line(t, et, 1, "twisting Et"));
  d.panelLabel = "E";
  d.title = "growth-zone topology";
  d.xlabel = "time (h)";
  d.ylabel = "Wr, Tw";
  d.series.push_back(line(t, wr, 2, "writhe Wr"));
  d.series.push_back(line(t, tw, 3, "twist Tw"));
  f.axes = {a, b, d};
  saveFigure(f, (fs::path(c.opt.out) / "fig2cde").string());

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
    table += "| " + num(k.beta) + " | " + num(g) + " | " + fmt3(T0k) + " | " + fmt3(T) + " | " + fmt3(T / T0k) + " |\n";
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
                       "turning time / T0 drifts with β from " + fmt3(Tf.front()) + " (β = " + num(betas.front()) +
                       ") to " + fmt3(Tf.back()) + " (β = " + num(betas.back()) + "; table under fig2cde), so no O(1) "
                       "prefactor makes Eq. 7 hold for all β. The crossing time is interpolated between growth steps; "
                       "docs/claims.md lists the full-resolution runs (γ = 0 and a horizontal start included) that "
                       "give the same picture."});
  c.claims->push_back({"Eq. 7: the free organ's turning time ∝ (β Lgz/R)^(−3/5) (β = 0.05 … 1)", "exponent −0.6",
                       "−3/5 (fit to the paper's free-organ runs, SI 5)",
                       "exponent " + fmt3(slope) + " (least squares over " + std::to_string(nfit) + " runs; ratio " +
                           fmt3(slope / -0.6) + ")",
                       std::string(kScaleTol) + " of the exponent", within(slope / -0.6, kScaleLo, kScaleHi),
                       "The local exponent steepens with the gain: " + fmt3(eLo) + " between β = " + num(betas[0]) +
                           " and " + num(betas[1]) + ", " + fmt3(eHi) + " between β = " + num(betas[betas.size() - 2]) +
                           " and " + num(betas.back()) + ". This model, as docs/model.md specifies it, does not reproduce "
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

std::vector<Case> scalingCases(const Ctx& c) {
  const std::vector<double> betas = c.opt.quick ? std::vector<double>{0.1, 0.2, 0.5} : std::vector<double>{0.05, 0.1, 0.2, 0.5, 1.0};
  const std::vector<double> alphas = c.opt.quick ? std::vector<double>{30, 40} : std::vector<double>{20, 30, 40};
  std::vector<Case> cs;
  for (double b : betas)
    for (double a : alphas) cs.push_back(Case{a, b, 0.1, 0, false, c.opt.quick ? 14.0 : 20.0});
  return cs;
}

// measured against predicted with the identity line
void identityPlot(const Ctx& c, const std::string& name, const std::string& title, const std::string& xl,
                    const std::string& yl, const std::vector<double>& x, const std::vector<double>& y, int color, char mark,
                    const std::string& label, const std::string& lineLabel) {
  double hi = 0.5;
  for (double v : x) if (std::isfinite(v)) hi = std::max(hi, v);
  for (double v : y) if (std::isfinite(v)) hi = std::max(hi, v);
  Figure f;
  f.width = 700;
  f.height = 640;
  Axes ax;
  ax.title = title;
  ax.xlabel = xl;
  ax.ylabel = yl;
  ax.autoX = ax.autoY = false;
  ax.xmin = ax.ymin = 0;
  ax.xmax = ax.ymax = 1.08 * hi;
  ax.series.push_back(points(x, y, color, mark, label));
  ax.series.push_back(line({0, 1.08 * hi}, {0, 1.08 * hi}, 7, lineLabel, true));
  ax.legendPos = "nw";
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / name).string());
}

std::string fig3a(const Ctx& c) {
  const auto cs = scalingCases(c);
  runCases(c, cs);
  // Eq. 6 is about waving patterns: only the runs that wave are plotted and counted
  std::vector<double> pred, meas, ratio;
  std::string table = "| α | β | pattern | max κ measured (1/mm) | Eq. 8 (1/mm) | ratio |\n|---|---|---|---|---|---|\n";
  for (const auto& k : cs) {
    const RunResult r = result(c, k);
    const double p = val(r, "max_kappa_eq8_per_mm"), mk = val(r, "max_kappa_per_mm");
    table += "| " + num(k.alpha) + " | " + num(k.beta) + " | " + r.pattern + " | " + fmt3(mk) + " | " + fmt3(p) +
             " | " + fmt3(mk / p) + " |\n";
    if (r.pattern != "waving") continue;
    pred.push_back(p);
    meas.push_back(mk);
    ratio.push_back(mk / p);
  }
  identityPlot(c, "fig3a", "Fig. 3A: max curvature vs Eq. 8", "T0 (ε̇0/R) β sin α  (1/mm)", "measured max κ (1/mm)", pred,
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
    table += "| " + num(k.alpha) + " | " + num(k.beta) + " | " + r.pattern + " | " + fmt3(lam) + " | " + fmt3(A) +
             " | " + fmt3(val(r, "amplitude_half_mm")) + " | " + fmt3(pred) + " | " + fmt3(lam / pred) + " | " +
             fmt3(val(r, "wavelength_eq9_mm")) + " | " + fmt3(val(r, "amplitude_eq10_mm")) + " |\n";
    if (r.pattern != "waving" || !std::isfinite(lam) || !std::isfinite(A)) continue;
    x.push_back(pred);
    y.push_back(lam);
    r11.push_back(lam / pred);
    r9.push_back(lam / val(r, "wavelength_eq9_mm"));
    r10.push_back(A / val(r, "amplitude_eq10_mm"));
  }
  identityPlot(c, "fig3b", "Fig. 3B: wavelength vs 4 A cot α (Eq. 11), A peak-to-peak", "4 A cot α  (mm)",
               "wavelength λ (mm)", x, y, 1, 's', "waving simulations", "Eq. 11: λ = 4 A cot α");
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

// a phase diagram over alpha (a grid of c.alphaStep() degrees) and beta Lgz / R, against Eqs. 12-13
// (Fig. 3D: gamma = 0.1, local sensing; the SI's variants: gamma = 1, apical sensing)
// the cells of a phase diagram (phaseDiagram below)
std::vector<Case> phaseCases(const Ctx& c, double gamma, bool apical) {
  // quick: the SI's variants on one column only, beta Lgz / R = 5 (CI time: the fixture must stay
  // under 2 minutes on a shared 2-core machine)
  const bool variantOfSi = gamma != 0.1 || apical;
  const std::vector<double> betas = !c.opt.quick ? std::vector<double>{0.05, 0.1, 0.2, 0.5, 1.0}
                                    : variantOfSi ? std::vector<double>{0.5}
                                                  : std::vector<double>{0.1, 0.2, 0.5};
  std::vector<double> alphas;
  for (double a = 0; a <= 90 + 1e-9; a += c.alphaStep()) alphas.push_back(a);
  std::vector<Case> cs;
  for (double b : betas)
    for (double a : alphas) {
      Case k{a, b, gamma, 0, false, c.opt.quick ? 12.0 : 15.0};
      k.apical = apical;
      cs.push_back(k);
    }
  return cs;
}

std::string phaseDiagram(const Ctx& c, const std::string& name, const std::string& variant, double gamma, bool apical) {
  const std::vector<Case> cs = phaseCases(c, gamma, apical);
  runCases(c, cs);
  const double step = c.alphaStep();
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> byPattern;
  int agree = 0, total = 0;
  std::string far;  // disagreeing cells farther than one step from a boundary of Eqs. 12-13
  int nearMiss = 0, farMiss = 0;
  std::string table = "| β Lgz/R | α | simulated | Eqs. 12-13 |\n|---|---|---|---|\n";
  for (const auto& k : cs) {
    const RunResult r = result(c, k);
    auto& p = byPattern[r.pattern];
    const double g = val(r, "effective_gain");
    p.first.push_back(g);
    p.second.push_back(k.alpha);
    double a12 = val(r, "alpha_s_to_w_eq12_deg");
    if (!std::isfinite(a12)) a12 = 90;  // Eq. 12 without a solution: no waving below coiling
    const double a13 = val(r, "alpha_w_to_c_eq13_deg");
    const std::string th = k.alpha < std::min(a12, a13) ? "straight" : k.alpha < a13 ? "waving" : "coiling";
    ++total;
    const bool ok = r.pattern == th;
    agree += ok;
    if (!ok) {
      // a miss is "near" only when the simulated pattern is the theory's neighbour across a boundary that
      // lies within one step: straight/waving across Eq. 12, waving/coiling (or straight/coiling where
      // Eq. 12 lies above Eq. 13) across Eq. 13
      const std::string& sim = r.pattern;
      auto is = [&](const char* x, const char* y) { return (sim == x && th == y) || (sim == y && th == x); };
      const double b = is("straight", "waving") ? a12
                       : is("waving", "coiling") || (is("straight", "coiling") && a12 >= a13) ? a13
                                                                                            : NAN;
      if (std::isfinite(b) && std::abs(k.alpha - b) <= step) ++nearMiss;
      else {
        ++farMiss;
        far += (far.empty() ? "" : ", ") + std::string("g ") + num(g) + " α " + num(k.alpha) + "°: " + r.pattern +
               " (theory " + th + ")";
      }
    }
    table += "| " + num(g) + " | " + num(k.alpha) + " | " + r.pattern + " | " + th + (ok ? "" : " **≠**") + " |\n";
  }
  Axes ax;
  ax.title = "Fig. 3D: phase diagram (" + variant + "); background: Eqs. 12-13";
  ax.xlabel = "effective gravitropic gain β Lgz / R";
  ax.ylabel = "plate tilt α (deg)";
  ax.autoX = ax.autoY = false;
  ax.xmin = 0;
  ax.xmax = 10.5;
  ax.ymin = -3;
  ax.ymax = 93;
  std::vector<double> g, a12, a13;
  for (double x = 0.05; x <= 10.6; x += 0.05) {
    Model m;
    m.tropism.beta = x * m.rod.radius / m.growth.zoneLength;
    const Theory t = theoryFor(m);
    g.push_back(x);
    a12.push_back(std::isfinite(t.alphaStraightToWave) ? t.alphaStraightToWave / units::deg : 93.0);
    a13.push_back(t.alphaWaveToCoil / units::deg);
  }
  auto band = [&](const std::vector<double>& lo, const std::vector<double>& hi, Rgb col, const std::string& label) {
    Fill fl;
    fl.color = col;
    fl.alpha = 0.35;
    fl.label = label;
    for (size_t i = 0; i < g.size(); ++i) { fl.x.push_back(g[i]); fl.y.push_back(lo[i]); }
    for (size_t i = g.size(); i-- > 0;) { fl.x.push_back(g[i]); fl.y.push_back(hi[i]); }
    ax.fills.push_back(fl);
  };
  const std::vector<double> bottom(g.size(), -3.0), top(g.size(), 93.0);
  std::vector<double> mid(g.size());
  for (size_t i = 0; i < g.size(); ++i) mid[i] = std::min(a12[i], a13[i]);
  band(bottom, mid, paletteColor(5), "straight (theory)");
  band(mid, a13, paletteColor(4), "waving (theory)");
  band(a13, top, paletteColor(2), "coiling (theory)");
  const char* pats[] = {"straight", "waving", "coiling", "skewing"};
  const char marks[] = {'o', 's', '^', 'x'};
  for (int i = 0; i < 4; ++i)
    if (byPattern.count(pats[i]))
      ax.series.push_back(points(byPattern[pats[i]].first, byPattern[pats[i]].second, 7, marks[i],
                                 std::string("simulated: ") + pats[i]));
  ax.legendPos = "ne";
  Figure f;
  f.width = 950;
  f.height = 720;
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / name).string());
  c.claims->push_back({"Fig. 3D (" + variant + "): simulated patterns follow Eqs. 12-13", "the regions of Eqs. 12-13",
                       name == "fig3d" ? "good agreement" : "no qualitative difference (SI 7)",
                       std::to_string(agree) + " of " + std::to_string(total) + " cells agree; " +
                           std::to_string(nearMiss) + " disagree as the neighbouring phase within one step of its boundary, " +
                           std::to_string(farMiss) + " farther" + (far.empty() ? "" : ": " + far),
                       "a disagreement only as the neighbouring phase within the phase step (" + num(step) +
                           "°) of their boundary",
                       farMiss == 0,
                       "Eqs. 12-13 were derived for γ = 0 and local sensing; the paper reports no qualitative difference "
                       "for γ = 1 and apical sensing (SI 7). The cells are listed under the " + name + " panel (≠ marks a "
                       "disagreement); docs/claims.md lists full-resolution runs of the cells the quick report gets "
                       "wrong, which tell a resolution effect from a property of the model."});
  return md(name, "Simulated pattern (symbols) over tilt (" + num(step) + "° grid) and effective gain (" + variant +
                      "), on the regions predicted by Eqs. 12 and 13 (derived for γ = 0 and local sensing).",
         table);
}

std::string fig3d(const Ctx& c) { return phaseDiagram(c, "fig3d", "γ = 0.1", 0.1, false); }
std::string fig3dGamma1(const Ctx& c) { return phaseDiagram(c, "fig3d_gamma1", "γ = 1", 1.0, false); }
std::string fig3dApical(const Ctx& c) { return phaseDiagram(c, "fig3d_apical", "γ = 0.1, apical sensing", 0.1, true); }

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
  f.height = 780;
  f.title = "Fig. 4A: skewing with intrinsic twist (α = 30°, β = 0.2, γ = 0.1)";
  std::string table = "| R τ | ω T0 | skew ⟨θ⟩ (deg) | pattern |\n|---|---|---|---|\n";
  std::vector<double> skews;
  for (size_t i = 0; i < cs.size(); ++i) {
    const RunResult r = result(c, cs[i]);
    Axes ax;
    ax.panelLabel = std::string(1, static_cast<char>('a' + i));
    ax.title = "R τ = " + num(cs[i].rTau);
    ax.xlabel = "ω T0 = " + fmt3(val(r, "omega_T0"));
    addRoot(c, f, ax, *finals[i], cs[i], win, paletteColor(static_cast<int>(i)));
    f.axes.push_back(ax);
    skews.push_back(std::abs(val(r, "skew_deg")));
    table += "| " + num(cs[i].rTau) + " | " + fmt3(val(r, "omega_T0")) + " | " + fmt3(val(r, "skew_deg")) + " | " +
             r.pattern + " |\n";
  }
  saveFigure(f, (fs::path(c.opt.out) / "fig4a").string());
  bool grows = skews.back() > skews.front() + 5;
  c.claims->push_back({"Fig. 4A: intrinsic twist makes the root skew; skew grows with ω T0", "—", "skew grows with ω T0",
                       "skew magnitude from " + fmt3(skews.front()) + "° (τ = 0) to " + fmt3(skews.back()) + "°",
                       "last > first + 5°", grows});
  return md("fig4a", "Final top views for increasing intrinsic twist: the root skews to one side.", table);
}

std::string fig4g(const Ctx& c) {
  const std::vector<double> alphas = c.opt.quick ? std::vector<double>{30} : std::vector<double>{20, 30};
  std::vector<Case> cs;
  for (double a : alphas)
    for (double t : tauValues(c))
      if (t > 0) cs.push_back(Case{a, 0.2, 0.1, t, false, c.opt.quick ? 12.0 : 20.0});
  runCases(c, cs);
  Axes ax;
  ax.title = "Fig. 4G: skewing angle vs apex twist rate";
  ax.xlabel = "ω T0 R / Lgz";
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
      table += "| " + num(k.alpha) + " | " + num(k.rTau) + " | " + fmt3(wt) + " | " + fmt3(val(r, "skew_deg")) + " | " +
               fmt3(y.back()) + " |\n";
    }
    ax.series.push_back(points(x, y, static_cast<int>(ia), ia ? 's' : 'o', "α = " + num(alphas[ia]) + "°"));
  }
  std::vector<double> gx, g14;
  for (double x = 0; x <= 1.1 * xmax + 1e-9; x += xmax / 200) {
    gx.push_back(x);
    g14.push_back(x * 10.0);  // Eq. 14: sin<theta>/tan(alpha) = omega T0 = x Lgz / R
  }
  ax.series.push_back(line(gx, g14, 2, "Eq. 14 (ω T0 ≪ 1)", true));
  ax.series.push_back(line({0, 1.1 * xmax}, {1, 1}, 7, "Eq. 15 (ω T0 ≫ 1)", true));
  ax.autoY = false;
  ax.ymin = -0.05;
  ax.ymax = 1.5;
  ax.legendPos = "se";
  Figure f;
  f.width = 800;
  f.height = 620;
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / "fig4g").string());
  c.claims->push_back({"Eq. 15: sin⟨θ⟩ → tan α for ω T0 ≫ 1", "ratio 1", "≈ 1 (Fig. 4G)",
                       "sin⟨θ⟩ / tan α = " + fmt3(largeRatio) + " at ω T0 = " + fmt3(largeWT), kRatioTol,
                       within(largeRatio, kRatioLo, kRatioHi)});
  return md("fig4g", "Skewing angle against the apex twist rate, with the limits of Eqs. 14 and 15.", table);
}

std::string makeOne(const std::string& name, const Ctx& c) {
  if (name == "fig2a") return fig2a(c);
  if (name == "fig2b") return fig2b(c);
  if (name == "fig2cde") return fig2cde(c);
  if (name == "fig3a") return fig3a(c);
  if (name == "fig3b") return fig3b(c);
  if (name == "fig3d") return fig3d(c);
  if (name == "fig3d_gamma1") return fig3dGamma1(c);
  if (name == "fig3d_apical") return fig3dApical(c);
  if (name == "fig4a") return fig4a(c);
  if (name == "fig4g") return fig4g(c);
  std::string names;
  for (const auto& n : figureNames()) names += " " + n;
  throw SceneError("figure " + name + ": unknown figure (expected all or one of:" + names + ")");
}

}  // namespace

namespace {
// a figure folder: marker .rootsim-figures, the panels (PNG, SVG), report.md and the runs/ sweep folder
bool isFigureEntry(const fs::path& dir, const std::string& name) {
  if (name == ".rootsim-figures" || name == "report.md" || name == "report.md.tmp") return true;
  if (name == "runs") return whyNotOurs(dir / name, sweepFolder()).empty();
  for (const auto& n : figureNames())
    for (const char* ext : {".png", ".svg", ".png.tmp", ".svg.tmp"})
      if (name == n + ext) return true;
  return false;
}
const FolderSpec& figuresFolder() {
  static const FolderSpec s{".rootsim-figures", "rootsim figure folder", isFigureEntry};
  return s;
}
}  // namespace

const std::vector<std::string>& figureNames() {
  static const std::vector<std::string> n = {"fig2a",        "fig2b", "fig2cde", "fig3a", "fig3b",
                                                "fig3d",        "fig3d_gamma1",    "fig3d_apical", "fig4a",
                                                "fig4g"};
  return n;
}

std::string makeFigure(const std::string& name, const FigureOptions& opt,
                       const std::function<void(const std::string&)>& log) {
  // a bad name creates nothing
  const auto& names = figureNames();
  if (name != "all" && std::find(names.begin(), names.end(), name) == names.end()) {
    std::string list;
    for (const auto& n : names) list += " " + n;
    throw SceneError("figure " + name + ": unknown figure (expected all or one of:" + list + ")");
  }
  // the write rule: a new folder or rootsim's figure folder; panels written before are replaced only
  // with --force; locked while this process writes it
  const fs::path out = checkOutputName(opt.out, "--out");
  const OutputLock lock(out, "--out");
  WriteRule rule;
  rule.force = opt.force;
  rule.inputs.push_back(workingFolder());
  claimFolder(out, figuresFolder(), rule, "--out", false);
  std::vector<std::string> writes;
  for (const auto& n : names)
    if (name == "all" || name == n) writes.insert(writes.end(), {n + ".png", n + ".svg"});
  if (name == "all") writes.push_back("report.md");
  std::error_code ec;
  for (const std::string& f : writes)
    if (fs::exists(fs::symlink_status(out / f, ec)) && !opt.force)
      throw SceneError("--out " + out.string() + ": holds " + f + " from an earlier `rootsim figure`; pass --force to replace it");
  createOwnFolder(out, figuresFolder());
  std::vector<Claim> claims;
  Ctx c{opt, log, &claims};
  if (name == "all") {
    std::string report =
        std::string("# rootsim figure report\n\nGenerated by `rootsim figure all") +
        (opt.quick ? " --quick`: coarsened runs (0.1 mm elements, 0.1 h steps, shorter growth; phase diagrams on a 15° "
                     "grid in α, so transition angles are held to 15°)"
                   : "`: 0.05 mm elements, 0.05 h steps; phase diagrams on a 5° grid in α") +
        ". Simulations are in `runs/` (one run directory each).\n\n"
        "Definitions (docs/model.md, Observables): the waves are read from the turning points of the lateral "
        "displacement of the mature part (hysteresis 0.5 R). λ is the mean downhill distance between successive "
        "peaks on the same side; A is the mean lateral distance between neighbouring opposite peaks — the "
        "peak-to-peak excursion, as the paper's Fig. 3B caption measures it (`amplitude_mm`; half of it is "
        "`amplitude_half_mm`). The paper's "
        "triangle argument for Eq. 10 would call that excursion 2A: the paper is inconsistent, and its Fig. 3B plots "
        "the caption's A. A root with lateral peaks but fewer than two full waves is waving: its mean angle is "
        "biased by its incomplete wave, so a skew is judged only without waves or over at least two full waves.\n\n"
        "Tolerances (a referee's, never widened to make a claim pass): a scaling law holds when measured / predicted "
        "is within ±25 %; a ratio the paper says is 1 within 0.75 … 1.33; a transition angle within the phase "
        "diagram's step in α (" +
        num(c.alphaStep()) + "° here).\n\n";
    // the runs of the big panels in one batch, dearest first (runCases), so that both jobs stay busy
    // to its end; each figure then finds its runs done
    {
      std::vector<Case> batch = fig2Runs(c);
      for (const Case& k : scalingCases(c)) batch.push_back(k);
      for (const auto& [gamma, apical] : {std::pair{0.1, false}, std::pair{1.0, false}, std::pair{0.1, true}})
        for (const Case& k : phaseCases(c, gamma, apical)) batch.push_back(k);
      runCases(c, batch);
    }
    std::string sections;
    for (const auto& n : figureNames()) {
      if (log && !opt.quiet) log("figure " + n);
      sections += makeOne(n, c);
    }
    int ok = 0;
    for (const auto& cl : claims) ok += cl.agrees;
    report += "## Claims\n\n" + std::to_string(ok) + " of " + std::to_string(claims.size()) +
              " claims agree within their stated tolerance.\n\n| claim | theory | paper | measured | tolerance | agrees |\n"
              "|---|---|---|---|---|---|\n";
    for (const auto& cl : claims)
      report += "| " + cl.what + " | " + cl.theory + " | " + cl.paper + " | " + cl.measured + " | " + cl.tolerance + " | " +
                yesNo(cl.agrees) + " |\n";
    if (ok < static_cast<int>(claims.size())) {
      report += "\n### Not reproduced\n\n";
      for (const auto& cl : claims)
        if (!cl.agrees)
          report += "- **" + cl.what + "**: measured " + cl.measured + " against " + cl.theory + " (tolerance " +
                    cl.tolerance + "). " + (cl.note.empty() ? "" : cl.note) + "\n";
    }
    report += std::string("\nRoots are drawn ") +
              (opt.renderTile ? "by the OSMesa renderer (tube with +d1 pink / -d1 orange stripes)"
                              : "as centreline strokes of width 2R (this rootsim was built without the renderer)") +
              ".\n\n" + sections;
    writeFileAtomic(fs::path(opt.out) / "report.md", report);
    return report;
  }
  return makeOne(name, c);
}

}  // namespace rootsim
