// The paper's figure panels (MODEL.md section 10): run what a panel needs, then plot it beside theory.
#include "rootsim/figure.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "rootsim/errors.hpp"
#include "rootsim/model.hpp"
#include "rootsim/plot.hpp"
#include "rootsim/run_dir.hpp"
#include "rootsim/sweep.hpp"
#include "rootsim/theory.hpp"

namespace fs = std::filesystem;

namespace rootsim {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// one simulated root of a panel
struct Case {
  double alpha = 40, beta = 0.1, gamma = 0.1, rTau = 0;
  bool free = false;        // free organ: no plate, no adhesion
  double lengthMm = 10;     // grown to this length
};

struct Ctx {
  const FigureOptions& opt;
  const std::function<void(const std::string&)>& log;
  fs::path runs() const { return fs::path(opt.out) / "runs"; }
  double h() const { return opt.quick ? 0.1 : 0.05; }   // element length [mm]
  double dt() const { return opt.quick ? 0.1 : 0.05; }  // growth step [h]
};

std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string dirOf(const Ctx& c, const Case& k) {
  return std::string(c.opt.quick ? "quick" : "full") + "_a" + num(k.alpha) + "_b" + num(k.beta) + "_g" +
         num(k.gamma) + "_t" + num(k.rTau) + (k.free ? "_free" : "") + "_L" + num(k.lengthMm);
}

std::vector<std::string> setsOf(const Ctx& c, const Case& k) {
  const int steps = static_cast<int>(std::lround((k.lengthMm - 1.1) / (0.2 * c.dt())));
  std::vector<std::string> s = {
      "plane.alpha_deg=" + num(k.alpha),     "tropism.beta=" + num(k.beta),
      "tropism.gamma=" + num(k.gamma),       "tropism.twist_r_tau=" + num(k.rTau),
      "root.element_length_mm=" + num(c.h()), "growth.step_h=" + num(c.dt()),
      "growth.steps=" + std::to_string(steps), "output.vtk=false",
      "output.every_steps=" + std::to_string(std::max(1, static_cast<int>(std::lround(0.5 / c.dt()))))};
  if (k.free) {
    s.push_back("plane.enabled=false");
    s.push_back("adhesion.enabled=false");
  }
  return s;
}

// runs every case not yet complete (in parallel), throws RunError if one fails
void runCases(const Ctx& c, const std::vector<Case>& cases) {
  std::error_code ec;
  fs::create_directories(c.runs(), ec);
  const fs::path base = c.runs() / "base.toml";
  if (!fs::exists(base)) writeFileAtomic(base, "# figure runs: defaults of MODEL.md section 2, overridden per run\n");
  SweepPlan plan;
  plan.scenePath = base.string();
  for (const auto& k : cases) {
    SweepPoint p;
    p.index = static_cast<int>(plan.points.size());
    p.overrides = setsOf(c, k);
    p.dirName = dirOf(c, k);
    bool dup = false;
    for (const auto& q : plan.points) dup |= q.dirName == p.dirName;
    if (!dup) plan.points.push_back(p);
  }
  SweepOptions so;
  so.jobs = c.opt.jobs;
  so.out = c.runs().string();
  const SweepResult r = runSweep(plan, so, c.opt.quiet ? std::function<void(const std::string&)>() : c.log);
  if (r.failed > 0) throw RunError(std::to_string(r.failed) + " figure run(s) failed; see " + c.runs().string());
}

using Row = std::map<std::string, std::string>;

std::vector<Row> readCsv(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw RunError("cannot read " + p.string());
  std::string line;
  std::getline(in, line);
  std::vector<std::string> head;
  {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) head.push_back(cell);
  }
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row r;
    std::stringstream ss(line);
    std::string cell;
    for (size_t i = 0; i < head.size() && std::getline(ss, cell, ','); ++i) r[head[i]] = cell;
    rows.push_back(r);
  }
  return rows;
}

double val(const Row& r, const std::string& k) {
  auto it = r.find(k);
  if (it == r.end() || it->second.empty()) return NAN;
  return std::stod(it->second);
}

Row result(const Ctx& c, const Case& k) { return readCsv(c.runs() / dirOf(c, k) / "result.csv").at(0); }
std::vector<Row> series(const Ctx& c, const Case& k) { return readCsv(c.runs() / dirOf(c, k) / "timeseries.csv"); }

// final shape on the plate: lateral x [mm] and downhill coordinate (pointing down the picture)
Shape2D plateShape(const Ctx& c, const Case& k, Rgb color) {
  const auto rows = readCsv(c.runs() / dirOf(c, k) / "shape.csv");
  const double a = k.alpha * kDeg;
  Shape2D s;
  s.color = color;
  s.width = 0.2;  // 2R [mm]
  for (const auto& r : rows) {
    const double x = val(r, "x_mm"), y = val(r, "y_mm"), z = val(r, "z_mm");
    s.x.push_back(x);
    // downhill coordinate w = p . (0, -sin a, -cos a); drawn with downhill pointing down
    s.y.push_back(-(-std::sin(a) * y - std::cos(a) * z));
  }
  return s;
}

Series line(std::vector<double> x, std::vector<double> y, int color, std::string label, bool dashed = false) {
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

Model modelOf(const Case& k) {
  Model m;
  m.env.plane.alpha = k.alpha * kDeg;
  m.tropism.beta = k.beta;
  m.tropism.gamma = k.gamma;
  m.tropism.rTau = k.rTau;
  return m;
}

std::string md(const Ctx& c, const std::string& name, const std::string& caption, const std::string& body = "") {
  (void)c;
  return "## " + name + "\n\n![" + name + "](" + name + ".png)\n\n" + caption + "\n\n" + body + "\n";
}

// ---------------------------------------------------------------------------------------------------

std::string fig2a(const Ctx& c) {
  const std::vector<double> alphas = c.opt.quick ? std::vector<double>{0, 20, 40, 60, 80}
                                                 : std::vector<double>{0, 10, 20, 30, 40, 50, 60, 70, 80, 90};
  const double L = c.opt.quick ? 12 : 15;
  std::vector<Case> cases;
  for (double a : alphas) cases.push_back(Case{a, 0.1, 0.1, 0, false, L});
  runCases(c, cases);
  Figure f;
  f.cols = static_cast<int>(cases.size());
  f.width = 190 * f.cols + 40;
  f.height = 760;
  f.title = "Fig. 2A: final shapes on the plate, beta = gamma = 0.1 (downhill is down; mm)";
  std::string table = "| alpha (deg) | pattern | wavelength (mm) | amplitude (mm) | theta range (deg) |\n|---|---|---|---|---|\n";
  for (size_t i = 0; i < cases.size(); ++i) {
    const Row r = result(c, cases[i]);
    Axes ax;
    ax.title = "alpha = " + num(cases[i].alpha);
    ax.xlabel = r.at("pattern");
    ax.equalAspect = true;
    ax.autoX = false;
    ax.xmin = -3.5;
    ax.xmax = 3.5;
    ax.shapes.push_back(plateShape(c, cases[i], {0.3, 0.3, 0.32}));
    f.axes.push_back(ax);
    table += "| " + num(cases[i].alpha) + " | " + r.at("pattern") + " | " + r.at("wavelength_mm") + " | " +
             r.at("amplitude_mm") + " | " + num(std::round(val(r, "theta_min_deg"))) + " .. " +
             num(std::round(val(r, "theta_max_deg"))) + " |\n";
  }
  saveFigure(f, (fs::path(c.opt.out) / "fig2a").string());
  const Theory t = theoryFor(modelOf(cases[0]));
  return md(c, "fig2a", "Straight at 0 deg, waving at moderate tilt, coiling at large tilt. Theory (Eqs. 12, 13) for beta Lgz/R = " +
                            num(t.effectiveGain) + ": straight->waving at " + num(std::round(t.alphaStraightToWave / kDeg * 10) / 10) +
                            " deg, waving->coiling at " + num(std::round(t.alphaWaveToCoil / kDeg * 10) / 10) + " deg.",
            table);
}

Case wavingCase(const Ctx& c) { return Case{40, 0.2, 0.1, 0, false, c.opt.quick ? 13.1 : 31.1}; }
Case freeCase(const Ctx& c) { return Case{40, 0.2, 0.1, 0, true, c.opt.quick ? 7.1 : 13.1}; }

std::string fig2b(const Ctx& c) {
  const Case w = wavingCase(c), fr = freeCase(c);
  runCases(c, {w, fr});
  const auto sw = series(c, w), sf = series(c, fr);
  std::vector<double> tw, thw, tf, thf;
  for (const auto& r : sw) { tw.push_back(val(r, "time_h")); thw.push_back(val(r, "theta_tip_deg")); }
  for (const auto& r : sf) { tf.push_back(val(r, "time_h")); thf.push_back(val(r, "theta_tip_deg")); }
  Figure f;
  f.width = 1100;
  f.height = 520;
  Axes ax;
  ax.title = "Fig. 2B: tip angle, waving root vs free organ (alpha = 40, beta = 0.2, gamma = 0.1)";
  ax.xlabel = "time (h)";
  ax.ylabel = "theta_tip (deg)";
  ax.series.push_back(line(tw, thw, 0, "on the plate: planar tip angle"));
  ax.series.push_back(line(tf, thf, 1, "free organ: angle from gravity"));
  const Theory t = theoryFor(modelOf(w));
  ax.series.push_back(line({t.T0 / 3600, t.T0 / 3600}, {-90, 90}, 7, "T0 (Eq. 7)", true));
  ax.legendPos = "se";
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / "fig2b").string());
  const Row r = result(c, w), rf = result(c, fr);
  return md(c, "fig2b", "The waving root's tip keeps swinging; the free organ's oscillation decays. First sideways snap at " +
                            r.at("first_snap_or_turning_h") + " h; the free organ first reaches the vertical at " +
                            rf.at("first_snap_or_turning_h") + " h; T0 (Eq. 7) = " + num(t.T0 / 3600) + " h.");
}

std::string fig2cde(const Ctx& c) {
  const Case w = wavingCase(c);
  runCases(c, {w});
  const auto s = series(c, w);
  std::vector<double> t, eb, et, wr, tw;
  for (const auto& r : s) {
    t.push_back(val(r, "time_h"));
    eb.push_back(val(r, "Eb") * 1e9);
    et.push_back(val(r, "Et") * 1e9);
    wr.push_back(val(r, "Wr"));
    tw.push_back(val(r, "Tw"));
  }
  Figure f;
  f.width = 1100;
  f.height = 800;
  f.rows = 2;
  Axes a, b;
  a.title = "Fig. 2C-D: growth-zone energies";
  a.xlabel = "time (h)";
  a.ylabel = "energy (nJ)";
  a.series.push_back(line(t, eb, 0, "bending Eb"));
  a.series.push_back(line(t, et, 1, "twisting Et"));
  b.title = "Fig. 2E: growth-zone topology";
  b.xlabel = "time (h)";
  b.ylabel = "Wr, Tw";
  b.series.push_back(line(t, wr, 2, "writhe Wr"));
  b.series.push_back(line(t, tw, 3, "twist Tw"));
  f.axes = {a, b};
  saveFigure(f, (fs::path(c.opt.out) / "fig2cde").string());
  return md(c, "fig2cde", "Bending and twisting energy of the growth zone (no factor 1/2), and its writhe and twist: each sideways "
                          "snap converts bending into twist and writhe.");
}

std::vector<Case> scalingCases(const Ctx& c) {
  const std::vector<double> betas = c.opt.quick ? std::vector<double>{0.1, 0.2, 0.5} : std::vector<double>{0.05, 0.1, 0.2, 0.5, 1.0};
  const std::vector<double> alphas = c.opt.quick ? std::vector<double>{30, 40} : std::vector<double>{20, 30, 40};
  std::vector<Case> cs;
  for (double b : betas)
    for (double a : alphas) cs.push_back(Case{a, b, 0.1, 0, false, c.opt.quick ? 14.0 : 20.0});
  return cs;
}

std::string fig3a(const Ctx& c) {
  const auto cs = scalingCases(c);
  runCases(c, cs);
  std::vector<double> pred, meas;
  std::string table = "| alpha | beta | max kappa measured (1/mm) | Eq. 8 (1/mm) |\n|---|---|---|---|\n";
  for (const auto& k : cs) {
    const Row r = result(c, k);
    pred.push_back(val(r, "max_kappa_eq8_per_mm"));
    meas.push_back(val(r, "max_kappa_per_mm"));
    table += "| " + num(k.alpha) + " | " + num(k.beta) + " | " + r.at("max_kappa_per_mm") + " | " + r.at("max_kappa_eq8_per_mm") + " |\n";
  }
  double hi = 0;
  for (double v : pred) hi = std::max(hi, v);
  for (double v : meas) hi = std::max(hi, v);
  Figure f;
  f.width = 700;
  f.height = 640;
  Axes ax;
  ax.title = "Fig. 3A: max curvature vs Eq. 8";
  ax.xlabel = "T0 (eps0/R) beta sin(alpha)  (1/mm)";
  ax.ylabel = "measured max kappa (1/mm)";
  ax.series.push_back(points(pred, meas, 0, 'o', "simulations (gamma = 0.1)"));
  ax.series.push_back(line({0, 1.05 * hi}, {0, 1.05 * hi}, 7, "y = x", true));
  ax.legendPos = "nw";
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / "fig3a").string());
  return md(c, "fig3a", "Measured maximum projected curvature of the final shape against the prediction of Eq. 8.", table);
}

std::string fig3b(const Ctx& c) {
  const auto cs = scalingCases(c);
  runCases(c, cs);
  std::vector<double> x, y;
  std::string table = "| alpha | beta | pattern | lambda (mm) | A (mm) | 4A cot(alpha) (mm) | Eq. 9 lambda (mm) |\n|---|---|---|---|---|---|---|\n";
  for (const auto& k : cs) {
    const Row r = result(c, k);
    const double lam = val(r, "wavelength_mm"), A = val(r, "amplitude_mm");
    table += "| " + num(k.alpha) + " | " + num(k.beta) + " | " + r.at("pattern") + " | " + r.at("wavelength_mm") + " | " +
             r.at("amplitude_mm") + " | " + num(4 * A / std::tan(k.alpha * kDeg)) + " | " + r.at("wavelength_eq9_mm") + " |\n";
    if (r.at("pattern") != "waving" || !std::isfinite(lam) || !std::isfinite(A)) continue;
    x.push_back(4 * A / std::tan(k.alpha * kDeg));
    y.push_back(lam);
  }
  double hi = 1;
  for (double v : x) hi = std::max(hi, v);
  for (double v : y) hi = std::max(hi, v);
  Figure f;
  f.width = 700;
  f.height = 640;
  Axes ax;
  ax.title = "Fig. 3B: wavelength vs 4 A cot(alpha) (Eq. 11)";
  ax.xlabel = "4 A cot(alpha)  (mm)";
  ax.ylabel = "wavelength lambda (mm)";
  ax.series.push_back(points(x, y, 1, 's', "waving simulations"));
  ax.series.push_back(line({0, 1.05 * hi}, {0, 1.05 * hi}, 7, "Eq. 11: lambda = 4 A cot(alpha)", true));
  ax.legendPos = "nw";
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / "fig3b").string());
  return md(c, "fig3b", "Wavelength against four times the amplitude times cot(alpha), for the runs that wave.", table);
}

std::string fig3d(const Ctx& c) {
  const std::vector<double> betas = c.opt.quick ? std::vector<double>{0.1, 0.2, 0.5} : std::vector<double>{0.05, 0.1, 0.2, 0.5, 1.0};
  const std::vector<double> alphas = c.opt.quick ? std::vector<double>{0, 20, 40, 60, 80}
                                                 : std::vector<double>{0, 10, 20, 30, 40, 50, 60, 70, 80, 90};
  std::vector<Case> cs;
  for (double b : betas)
    for (double a : alphas) cs.push_back(Case{a, b, 0.1, 0, false, c.opt.quick ? 12.0 : 15.0});
  runCases(c, cs);
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> byPattern;
  for (const auto& k : cs) {
    const Row r = result(c, k);
    auto& p = byPattern[r.at("pattern")];
    p.first.push_back(val(r, "effective_gain"));
    p.second.push_back(k.alpha);
  }
  Axes ax;
  ax.title = "Fig. 3D: phase diagram (gamma = 0.1)";
  ax.xlabel = "effective gravitropic gain beta Lgz / R";
  ax.ylabel = "plate tilt alpha (deg)";
  ax.autoY = false;
  ax.ymin = -5;
  ax.ymax = 95;
  const char* pats[] = {"straight", "waving", "coiling", "skewing"};
  const char marks[] = {'o', 's', '^', 'x'};
  for (int i = 0; i < 4; ++i)
    if (byPattern.count(pats[i]))
      ax.series.push_back(points(byPattern[pats[i]].first, byPattern[pats[i]].second, i, marks[i], pats[i]));
  std::vector<double> g, a12, a13;
  for (double x = 0.4; x <= 11; x *= 1.05) {
    Model m;
    m.tropism.beta = x * m.rod.radius / m.growth.zoneLength;
    const Theory t = theoryFor(m);
    g.push_back(x);
    a12.push_back(t.alphaStraightToWave / kDeg);
    a13.push_back(t.alphaWaveToCoil / kDeg);
  }
  ax.series.push_back(line(g, a12, 0, "Eq. 12: straight -> waving", true));
  ax.series.push_back(line(g, a13, 2, "Eq. 13: waving -> coiling", true));
  ax.legendPos = "nw";
  Figure f;
  f.width = 900;
  f.height = 700;
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / "fig3d").string());
  return md(c, "fig3d", "Simulated pattern over tilt and effective gain, with the transition lines of Eqs. 12 and 13.");
}

std::vector<double> tauValues(const Ctx& c) {
  return c.opt.quick ? std::vector<double>{0, 0.1, 0.4} : std::vector<double>{0, 0.05, 0.1, 0.2, 0.4, 0.8};
}

std::string fig4a(const Ctx& c) {
  std::vector<Case> cs;
  for (double t : tauValues(c)) cs.push_back(Case{30, 0.2, 0.1, t, false, c.opt.quick ? 12.0 : 20.0});
  runCases(c, cs);
  Figure f;
  f.cols = static_cast<int>(cs.size());
  f.width = 220 * f.cols + 40;
  f.height = 760;
  f.title = "Fig. 4A: skewing with intrinsic twist (alpha = 30, beta = 0.2, gamma = 0.1)";
  std::string table = "| R tau | omega T0 | skew (deg) | pattern |\n|---|---|---|---|\n";
  for (size_t i = 0; i < cs.size(); ++i) {
    const Row r = result(c, cs[i]);
    Axes ax;
    ax.title = "R tau = " + num(cs[i].rTau);
    ax.xlabel = "omega T0 = " + num(std::round(val(r, "omega_T0") * 10) / 10);
    ax.equalAspect = true;
    ax.shapes.push_back(plateShape(c, cs[i], paletteColor(static_cast<int>(i))));
    f.axes.push_back(ax);
    table += "| " + num(cs[i].rTau) + " | " + r.at("omega_T0") + " | " + r.at("skew_deg") + " | " + r.at("pattern") + " |\n";
  }
  saveFigure(f, (fs::path(c.opt.out) / "fig4a").string());
  return md(c, "fig4a", "Final shapes for increasing intrinsic twist: the root skews to one side.", table);
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
  ax.xlabel = "omega T0 R / Lgz";
  ax.ylabel = "sin<theta> / tan(alpha)";
  std::string table = "| alpha | R tau | omega T0 | skew (deg) | sin<theta>/tan(alpha) |\n|---|---|---|---|---|\n";
  double xmax = 0;
  for (size_t ia = 0; ia < alphas.size(); ++ia) {
    std::vector<double> x, y;
    for (const auto& k : cs) {
      if (k.alpha != alphas[ia]) continue;
      const Row r = result(c, k);
      const double wt = val(r, "omega_T0"), sk = val(r, "skew_deg") * kDeg;
      x.push_back(wt * 0.1);  // R / Lgz = 0.1
      y.push_back(std::sin(sk) / std::tan(k.alpha * kDeg));
      xmax = std::max(xmax, x.back());
      table += "| " + num(k.alpha) + " | " + num(k.rTau) + " | " + r.at("omega_T0") + " | " + r.at("skew_deg") + " | " + num(y.back()) + " |\n";
    }
    ax.series.push_back(points(x, y, static_cast<int>(ia), ia ? 's' : 'o', "alpha = " + num(alphas[ia])));
  }
  std::vector<double> gx, g14;
  for (double x = 0; x <= 1.1 * xmax + 1e-9; x += xmax / 100) {
    gx.push_back(x);
    g14.push_back(x * 10.0);  // Eq. 14: sin<theta>/tan(alpha) = omega T0 = x Lgz / R
  }
  ax.series.push_back(line(gx, g14, 2, "Eq. 14 (omega T0 << 1)", true));
  ax.series.push_back(line({0, 1.1 * xmax}, {1, 1}, 7, "Eq. 15 (omega T0 >> 1)", true));
  ax.autoY = false;
  ax.ymin = -0.1;
  ax.ymax = 1.5;
  ax.legendPos = "se";
  Figure f;
  f.width = 800;
  f.height = 620;
  f.axes.push_back(ax);
  saveFigure(f, (fs::path(c.opt.out) / "fig4g").string());
  return md(c, "fig4g", "Skewing angle against the apex twist rate, with the small- and large-omega T0 limits of Eqs. 14 and 15.", table);
}

}  // namespace

const std::vector<std::string>& figureNames() {
  static const std::vector<std::string> n = {"fig2a", "fig2b", "fig2cde", "fig3a", "fig3b", "fig3d", "fig4a", "fig4g"};
  return n;
}

std::string makeFigure(const std::string& name, const FigureOptions& opt,
                       const std::function<void(const std::string&)>& log) {
  std::error_code ec;
  fs::create_directories(opt.out, ec);
  if (ec) throw SceneError("--out " + opt.out + ": cannot create: " + ec.message());
  Ctx c{opt, log};
  if (name == "all") {
    std::string report = std::string("# rootsim figure report\n\nGenerated by `rootsim figure all") +
                         (opt.quick ? " --quick`: coarsened runs (0.1 mm elements, 0.1 h steps, shorter growth)"
                                    : "`: 0.05 mm elements, 0.05 h steps") +
                         ". Simulations are in `runs/` (one run directory each).\n\n";
    for (const auto& n : figureNames()) {
      if (log && !opt.quiet) log("figure " + n);
      report += makeFigure(n, opt, log);
    }
    writeFileAtomic(fs::path(opt.out) / "report.md", report);
    return report;
  }
  if (name == "fig2a") return fig2a(c);
  if (name == "fig2b") return fig2b(c);
  if (name == "fig2cde") return fig2cde(c);
  if (name == "fig3a") return fig3a(c);
  if (name == "fig3b") return fig3b(c);
  if (name == "fig3d") return fig3d(c);
  if (name == "fig4a") return fig4a(c);
  if (name == "fig4g") return fig4g(c);
  std::string names;
  for (const auto& n : figureNames()) names += " " + n;
  throw SceneError("figure " + name + ": unknown figure (expected all or one of:" + names + ")");
}

}  // namespace rootsim
