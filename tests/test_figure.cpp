// figure panels: `rootsim figure all --quick` (run by the figures_quick ctest fixture) made every panel
// as PDF, SVG and PNG, the vector files draw the roots as paths (no images), the PNG carries its dpi, the
// PDF's text is text, each PNG has drawn content, and the quick runs show the paper's patterns
#include <doctest/doctest.h>

#include <map>

#include <cairo.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <cctype>
#include <chrono>
#include <thread>

#include "rootsim/figure.hpp"
#include "rootsim/plot.hpp"
#include "test_support.hpp"

using rootsim::test::kRoundoff;

namespace fs = std::filesystem;

namespace {
using rootsim::test::slurp;
// fraction of pixels that are not (near) white; also returns the size
double inkFraction(const fs::path& png, int* width = nullptr, int* height = nullptr) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
  const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
  if (width) *width = w;
  if (height) *height = h;
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* d = cairo_image_surface_get_data(s);
  long ink = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = d + y * stride + 4 * x;
      if (p[0] < 200 || p[1] < 200 || p[2] < 200) ++ink;
    }
  cairo_surface_destroy(s);
  return static_cast<double>(ink) / (static_cast<double>(w) * h);
}
const fs::path kOut = ROOTSIM_FIGURE_DIR;

// stdout of a shell command
std::string capture(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

// a PDF's page size [pt] (pdfinfo)
std::array<double, 2> pageSizePt(const fs::path& pdf) {
  const std::string info = capture("pdfinfo '" + pdf.string() + "' 2>&1");
  const size_t p = info.find("Page size:");
  REQUIRE(p != std::string::npos);
  std::array<double, 2> wh{0, 0};
  REQUIRE(std::sscanf(info.c_str() + p, "Page size: %lf x %lf", &wh[0], &wh[1]) == 2);
  return wh;
}

// the pHYs chunk of a PNG: pixels per metre along x and y and the unit byte; {-1, -1, -1} if none
std::array<long, 3> physOf(const fs::path& png) {
  const std::string b = slurp(png);
  size_t p = 8;
  while (p + 12 <= b.size()) {
    auto u32 = [&](size_t q) {
      return (static_cast<long>(static_cast<unsigned char>(b[q])) << 24) | (static_cast<unsigned char>(b[q + 1]) << 16) |
             (static_cast<unsigned char>(b[q + 2]) << 8) | static_cast<unsigned char>(b[q + 3]);
    };
    const long len = u32(p);
    const std::string type = b.substr(p + 4, 4);
    if (type == "pHYs" && len == 9) return {u32(p + 8), u32(p + 12), static_cast<unsigned char>(b[p + 16])};
    if (type == "IDAT") break;
    p += 12 + static_cast<size_t>(len);
  }
  return {-1, -1, -1};
}
}  // namespace

TEST_CASE("every panel exists as PDF, SVG and PNG with drawn content") {
  for (const auto& n : rootsim::figureNames()) {
    INFO(n);
    REQUIRE(fs::exists(kOut / (n + ".png")));
    REQUIRE(fs::exists(kOut / (n + ".svg")));
    REQUIRE(fs::exists(kOut / (n + ".pdf")));
    CHECK(slurp(kOut / (n + ".svg")).find("<svg") != std::string::npos);
    CHECK(slurp(kOut / (n + ".pdf")).rfind("%PDF-", 0) == 0);
    int w = 0, h = 0;
    const double ink = inkFraction(kOut / (n + ".png"), &w, &h);
    CHECK(ink > 0.005);  // not blank
    CHECK(ink < 0.95);   // fig3d is mostly coloured background
    // the panels' layout sizes (src/figure/fig*.cpp), 96 layout units per inch, at 300 dpi
    const double lw = w * 96.0 / 300.0, lh = h * 96.0 / 300.0;
    CHECK(lw >= 600);
    CHECK(lw <= 2200);
    CHECK(lh >= 400);
    CHECK(lh <= 1100);
  }
  CHECK(slurp(kOut / "report.md").find("## fig4g") != std::string::npos);
}

TEST_CASE("quick report: straight at 0 deg, waving in the middle, coiling at high alpha, and skew grows with omega T0") {
  const std::string r = slurp(kOut / "report.md");
  // the Fig. 2A table (quick: the 15-degree phase grid)
  CHECK(r.find("| 0 | straight |") != std::string::npos);
  CHECK(r.find("| 30 | waving |") != std::string::npos);
  CHECK(r.find("| 75 | coiling |") != std::string::npos);
  const auto p = r.find("| Fig. 4A: intrinsic twist makes the root skew; skew grows with ω T0 |");
  REQUIRE(p != std::string::npos);
  const std::string row = r.substr(p, r.find('\n', p) - p);
  INFO(row);
  CHECK(row.size() > 8);
  CHECK(row.substr(row.size() - 7) == "| yes |");
}

// the claims table of report.md: rows "| claim | theory | paper | measured | tolerance | agrees |"
std::vector<std::string> claimRows(const std::string& r) {
  std::vector<std::string> rows;
  const auto a = r.find("| claim | theory | paper | measured | tolerance | agrees |");
  REQUIRE(a != std::string::npos);
  size_t p = r.find('\n', r.find('\n', a) + 1) + 1;  // after the header and its |---| line
  while (p < r.size() && r[p] == '|') {
    const size_t e = r.find('\n', p);
    rows.push_back(r.substr(p, e - p));
    p = e + 1;
  }
  return rows;
}
std::string rowOf(const std::vector<std::string>& rows, const std::string& start) {
  for (const auto& row : rows)
    if (row.rfind("| " + start, 0) == 0) return row;
  return "";
}
bool agrees(const std::string& row) { return row.size() > 8 && row.substr(row.size() - 7) == "| yes |"; }

TEST_CASE("quick report: every claim is there with its referee tolerance, and the count of agreeing claims is right") {
  const std::string r = slurp(kOut / "report.md");
  const auto rows = claimRows(r);
  const char* expected[] = {
      "Fig. 2A: α = 0 grows straight",
      "Fig. 2A: waving sets in at α_s→w (β = 0.1), by bisection",
      "Fig. 2A: coiling sets in at α_w→c (β = 0.1), by bisection",
      "Fig. 2A: the 10 mm root at α = 40° (β = γ = 0.1) waves",
      "Fig. 2B: the root waves",
      "Eq. 9: wavelength λ = 2 T0 v_tip",
      "Eq. 10: amplitude A = T0 v_tip tan(α) / 2, A peak-to-peak",
      "Eq. 7: first sideways snap at the turning time T0",
      "Eq. 7: the free organ reaches the vertical at T0",
      "Eq. 7: the free organ's turning time ∝ (β Lgz/R)^(−3/5)",
      "Fig. 2C: the free organ and the waving root oscillate with a similar period",
      "Fig. 2C: the free organ's oscillation decays, the waving one does not",
      "Eq. 8 (Fig. 3A)",
      "Eq. 11 (Fig. 3B): λ ≈ 4 A cot α, A peak-to-peak",
      "Eq. 9 over the Fig. 3 runs",
      "Eq. 10 over the Fig. 3 runs",
      "Fig. 3D (γ = 0.1):",
      "Fig. 3D (γ = 1):",
      "Fig. 3D (γ = 0.1, apical sensing):",
      "Fig. 4A: intrinsic twist makes the root skew",
      "Eq. 15: sin⟨θ⟩ → tan α for ω T0 ≫ 1",
  };
  CHECK(rows.size() == std::size(expected));
  int yes = 0;
  for (const auto& row : rows) yes += agrees(row);
  CHECK(r.find(std::to_string(yes) + " of " + std::to_string(rows.size()) + " claims agree") != std::string::npos);
  for (const char* e : expected) {
    INFO(e);
    CHECK(!rowOf(rows, e).empty());
  }
  // the tolerances a referee would accept, never "a factor 2" or one 20-degree step
  CHECK(rowOf(rows, "Eq. 9: wavelength").find("±25 % (0.75 … 1.25)") != std::string::npos);
  CHECK(rowOf(rows, "Eq. 11 (Fig. 3B)").find("| 0.75 … 1.33 |") != std::string::npos);
  CHECK(rowOf(rows, "Eq. 15:").find("| 0.75 … 1.33 |") != std::string::npos);
  CHECK(rowOf(rows, "Fig. 2A: waving sets in").find("within the phase step (15°) of Eq. 12") != std::string::npos);
  CHECK(rowOf(rows, "Fig. 3D (γ = 0.1):").find("within the phase step (15°)") != std::string::npos);
  CHECK(r.find("factor 2") == std::string::npos);
  // the short alpha = 40 root waves, and the bisection bracket is a quarter of the phase step wide
  CHECK(agrees(rowOf(rows, "Fig. 2A: the 10 mm root at α = 40°")));
  const std::string sw = rowOf(rows, "Fig. 2A: waving sets in");
  CHECK(sw.find("2 bisection runs") != std::string::npos);  // 15 -> 7.5 -> 3.75 degrees
  // every failing claim is listed, with its measured value, under "Not reproduced"
  const auto nr = r.find("### Not reproduced");
  for (const auto& row : rows) {
    if (agrees(row)) continue;
    INFO(row);
    REQUIRE(nr != std::string::npos);
    const std::string what = row.substr(2, row.find(" |") - 2);
    CHECK(r.find("- **" + what + "**: measured ", nr) != std::string::npos);
  }
}

TEST_CASE("quick report: A is the peak-to-peak excursion, stated with the reason, and A/2 is listed beside it") {
  const std::string r = slurp(kOut / "report.md");
  CHECK(r.find("the peak-to-peak excursion, as the paper's Fig. 3B caption measures it") != std::string::npos);
  CHECK(r.find("`amplitude_half_mm`") != std::string::npos);
  CHECK(r.find("the paper is inconsistent") != std::string::npos);
  CHECK(r.find("| A/2 (mm) |") != std::string::npos);
  // the 40-degree root of Fig. 3B at beta = 0.2 falls on Eq. 11 once A is the peak-to-peak excursion
  const auto rows = claimRows(r);
  CHECK(agrees(rowOf(rows, "Eq. 11 (Fig. 3B)")));
  CHECK(agrees(rowOf(rows, "Eq. 10: amplitude")));
}

TEST_CASE("a plot draws a line where its data are") {
  rootsim::Figure f;
  f.width = 400;
  f.height = 300;
  rootsim::Axes a;
  a.grid = false;
  a.autoX = a.autoY = false;
  a.xmin = 0;
  a.xmax = 1;
  a.ymin = 0;
  a.ymax = 1;
  rootsim::Series s;
  s.x = {0, 1};
  s.y = {0.5, 0.5};
  s.color = {1, 0, 0};
  s.width = 3;
  a.series.push_back(s);
  f.axes.push_back(a);
  const fs::path base = rootsim::test::scratchDir("plot", "test") / "figure";
  rootsim::SaveOptions so;
  so.dpi = 96;  // one pixel a layout unit
  rootsim::saveFigure(f, base.string(), so);
  cairo_surface_t* img = cairo_image_surface_create_from_png((base.string() + ".png").c_str());
  REQUIRE(cairo_surface_status(img) == CAIRO_STATUS_SUCCESS);
  const int stride = cairo_image_surface_get_stride(img);
  const unsigned char* d = cairo_image_surface_get_data(img);
  // plot area: x in [64, 386], y in [12, 254]; y = 0.5 maps to row 133; BGRA in memory
  auto px = [&](int x, int y) { return d + y * stride + 4 * x; };
  CHECK(px(200, 133)[2] > 200);  // red
  CHECK(px(200, 133)[1] < 80);
  CHECK(px(200, 60)[2] > 200);   // white above the line
  CHECK(px(200, 60)[1] > 200);
  cairo_surface_destroy(img);
}

TEST_CASE("the panels are vector drawings: no raster images in their SVG or PDF") {
  for (const auto& n : rootsim::figureNames()) {
    INFO(n);
    const std::string svg = slurp(kOut / (n + ".svg"));
    CHECK(svg.find("<image") == std::string::npos);
    // cairo writes the PDF's object dictionaries uncompressed: an image would be an XObject /Subtype /Image
    const std::string pdf = slurp(kOut / (n + ".pdf"));
    CHECK(pdf.find("/Image") == std::string::npos);
    // and poppler lists none
    const std::string list = capture("pdfimages -list '" + (kOut / (n + ".pdf")).string() + "' 2>&1");
    INFO(list);
    CHECK(list.find("page") != std::string::npos);  // the header: pdfimages ran
    size_t lines = 0;
    for (char ch : list) lines += ch == '\n';
    CHECK(lines == 2);  // header and rule only
  }
  // the plate views draw their roots as paths: many of them
  const std::string svg = slurp(kOut / "fig2a.svg");
  size_t paths = 0;
  for (size_t p = svg.find("<path"); p != std::string::npos; p = svg.find("<path", p + 1)) ++paths;
  CHECK(paths > 500);
}

TEST_CASE("the PNG carries its resolution: pHYs = dpi / 0.0254 pixels per metre") {
  for (const auto& n : rootsim::figureNames()) {
    INFO(n);
    const auto ph = physOf(kOut / (n + ".png"));
    CHECK(ph[0] == std::lround(300 / 0.0254));
    CHECK(ph[1] == std::lround(300 / 0.0254));
    CHECK(ph[2] == 1);
  }
  // --dpi and --width-mm: a journal column of 85 mm at 600 dpi
  rootsim::Figure f;
  f.width = 500;
  f.height = 400;
  rootsim::Axes a;
  a.series.push_back(rootsim::Series{});
  a.series.back().x = {0, 1};
  a.series.back().y = {0, 1};
  f.axes.push_back(a);
  const fs::path base = rootsim::test::scratchDir("plot", "dpi") / "figure";
  rootsim::SaveOptions so;
  so.dpi = 600;
  so.widthMm = 85;
  rootsim::saveFigure(f, base.string(), so);
  int w = 0, h = 0;
  inkFraction(base.string() + ".png", &w, &h);
  CHECK(w == std::lround(85 / 25.4 * 600));
  CHECK(physOf(base.string() + ".png")[0] == std::lround(600 / 0.0254));
  // the PDF's page is 85 mm wide (points), and the PNG has the page's proportions
  const auto page = pageSizePt(base.string() + ".pdf");
  CHECK(page[0] == doctest::Approx(85 / 25.4 * 72).epsilon(1e-5));
  CHECK(h == std::lround(w * page[1] / page[0]));
}

namespace {
// the words of a PDF with their font size [pt]: pdftotext -bbox gives each word's box, across the line as
// high as the font's ascent + descent, which for DejaVu Sans (the panels' font) is 1.164 em (0.928 +
// 0.236). A rotated word (a y axis label) has that extent along x: a word of three or more characters is
// longer along its line than across it, so its size is the box's smaller side; one or two characters
// (subscripts, digits) are never wider than 1.164 em along a horizontal line unless they are rotated, so
// theirs is the larger side
std::vector<std::pair<std::string, double>> wordSizesPt(const fs::path& pdf) {
  const std::string xml = capture("pdftotext -bbox '" + pdf.string() + "' - 2>&1");
  std::vector<std::pair<std::string, double>> out;
  for (size_t p = xml.find("<word "); p != std::string::npos; p = xml.find("<word ", p + 1)) {
    auto attr = [&](const std::string& k) { return std::stod(xml.substr(xml.find(k + "=\"", p) + k.size() + 2)); };
    const size_t a = xml.find('>', p) + 1;
    const std::string word = xml.substr(a, xml.find('<', a) - a);
    size_t chars = 0;
    for (char ch : word) chars += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
    const double w = attr("xMax") - attr("xMin"), h = attr("yMax") - attr("yMin");
    out.emplace_back(word, (chars >= 3 ? std::min(w, h) : std::max(w, h)) / 1.164);
  }
  return out;
}

// a panel like the paper's rows of roots: tiles sharing their y axis (fixed y range, a y label on the
// first only), tubes, titles and notes with subscripts, a long figure title; and a plot with a legend
rootsim::Figure journalPanel() {
  rootsim::Figure f;
  f.cols = 6;
  f.width = 170 * f.cols + 40;
  f.height = 600;
  f.title = "Fig. 2A: final shapes on the plate (β = γ = 0.1; pink +d_1, orange −d_1; downhill is down)";
  for (int i = 0; i < f.cols; ++i) {
    rootsim::Axes a;
    if (i == 0) a.panelLabel = "A";
    a.title = "α = " + std::to_string(15 * i) + "°";
    a.xlabel = "lateral [mm]";
    if (i == 0) a.ylabel = "downhill [mm]";
    a.autoX = a.autoY = false;
    a.equalAspect = a.yDown = true;
    a.xmin = -2;
    a.xmax = 2;
    a.ymin = -0.5;
    a.ymax = 12;
    rootsim::Tube tb;
    for (int k = 0; k <= 40; ++k) {
      tb.x.push_back(0.8 * std::sin(0.3 * k * i / 5.0));
      tb.y.push_back(0.3 * k);
      tb.r.push_back(0.1);
      tb.sx.push_back(1);
      tb.sy.push_back(0);
    }
    a.tubes.push_back(tb);
    a.notes.push_back({{0, 11.5}, "κ_{f}^{0} L_{gz}"});
    f.axes.push_back(a);
  }
  return f;
}
}  // namespace

TEST_CASE("at --width-mm 85 and 180 the panel is that wide and its text is at least 6 pt") {
  rootsim::Figure plot;
  plot.width = 800;
  plot.height = 620;
  rootsim::Axes pa;
  pa.title = "sin⟨θ⟩ / tan α over β L_{gz} / R";
  pa.xlabel = "effective gravitropic gain βL_{gz}/R";
  pa.ylabel = "θ^{tip} [deg]";
  pa.series.push_back(rootsim::Series{});
  pa.series.back().x = {0, 1, 2};
  pa.series.back().y = {0, 1, 0.5};
  pa.series.back().label = "E_{b} (zone)";
  plot.axes.push_back(pa);
  for (const auto& panel : {std::pair{"rows", journalPanel()}, std::pair{"plot", plot}})
    for (double mm : {85.0, 180.0}) {
      const char* name = panel.first;
      const rootsim::Figure& fig = panel.second;
      INFO(name << " at " << mm << " mm");
      const fs::path base = rootsim::test::scratchDir("plot", "journal_" + std::string(name)) / "figure";
      rootsim::SaveOptions so;
      so.widthMm = mm;
      rootsim::saveFigure(fig, base.string(), so);
      const auto page = pageSizePt(base.string() + ".pdf");
      CHECK(page[0] == doctest::Approx(mm / 25.4 * 72).epsilon(1e-5));
      const auto words = wordSizesPt(base.string() + ".pdf");
      CHECK(words.size() > 10);
      double smallest = 1e9;
      for (const auto& word : words) {
        const double size = word.second;
        INFO(word.first << " " << size << " pt");
        CHECK(size >= 5.95);
        smallest = std::min(smallest, size);
      }
      // the tick labels are 7 pt and the sub- and superscripts 6 pt, at either width
      CHECK(smallest == doctest::Approx(6).epsilon(0.03));
      // the PNG draws the same page
      int w = 0, h = 0;
      inkFraction(base.string() + ".png", &w, &h);
      CHECK(h == std::lround(w * page[1] / page[0]));
    }
  // without --width-mm the same panel at 85 mm would be scaled as a whole: its text far below 6 pt
  const fs::path base = rootsim::test::scratchDir("plot", "journal_scaled") / "figure";
  rootsim::saveFigure(journalPanel(), base.string(), rootsim::SaveOptions{});
  double smallest = 1e9;
  for (const auto& [w, size] : wordSizesPt(base.string() + ".pdf")) smallest = std::min(smallest, size);
  CHECK(smallest * 85 / (pageSizePt(base.string() + ".pdf")[0] / 72 * 25.4) < 4);
}

TEST_CASE("the PDF's text is text: pdftotext finds the axis titles with their units") {
  auto text = [](const std::string& n) { return capture("pdftotext '" + (kOut / (n + ".pdf")).string() + "' - 2>&1"); };
  const std::string a2 = text("fig2a");
  CHECK(a2.find("lateral [mm]") != std::string::npos);
  CHECK(a2.find("downhill [mm]") != std::string::npos);
  const std::string a4 = text("fig4a");
  CHECK(a4.find("lateral [mm]") != std::string::npos);
  CHECK(a4.find("downhill [mm]") != std::string::npos);
  CHECK(text("fig2b").find("downhill [mm]") != std::string::npos);
  CHECK(text("fig2cde").find("time [h]") != std::string::npos);
  const std::string d3 = text("fig3d");
  CHECK(d3.find("plate tilt α [deg]") != std::string::npos);
  CHECK(d3.find("effective gravitropic gain βL") != std::string::npos);  // L, then the subscript gz
  CHECK(text("fig3b").find("wavelength λ [mm]") != std::string::npos);
  CHECK(text("fig4g").find("sin⟨θ⟩ / tan α") != std::string::npos);
}

namespace {
// the raster renderer's rule (shaders/tube.frag): a surface point whose direction around the axis is
// cos(phi) d1 + sin(phi) d2 is in the +d1 stripe where cos(phi) > cos(half width). Seen from above, the
// pixel at lateral offset u (units of r) across the tube shows the point with normal u side + sqrt(1 - u^2) up.
bool rasterPlus(const std::array<double, 3>& d1, double u) {
  const double c = u * d1[0] + std::sqrt(1 - u * u) * d1[2];  // side = x, up = z
  return c > std::cos(38.0 * M_PI / 180);
}
}  // namespace

TEST_CASE("the vector root's stripes sit where the raster renderer draws them") {
  const std::array<double, 3> side{1, 0, 0}, up{0, 0, 1}, t{0, 1, 0};
  auto cross = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
    return std::array<double, 3>{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
  };
  const double hw = 38.0 * M_PI / 180;
  // d1 facing the viewer: the stripe on the tube's centre line, symmetric about it
  {
    const auto s = rootsim::visibleStripe(up, cross(t, up), side, up, hw);
    CHECK(s[0] == doctest::Approx(-std::sin(hw)).epsilon(1e-3));
    CHECK(s[1] == doctest::Approx(std::sin(hw)).epsilon(1e-3));
  }
  // d1 facing away: no stripe seen
  {
    const std::array<double, 3> down{0, 0, -1};
    const auto s = rootsim::visibleStripe(down, cross(t, down), side, up, hw);
    CHECK(std::isnan(s[0]));
  }
  // d1 turned about the axis by psi: the stripe's extent holds exactly the pixels the raster rule stripes
  for (double psiDeg : {0.0, 20.0, 45.0, 70.0, 90.0, 110.0, -30.0, -80.0}) {
    const double psi = psiDeg * M_PI / 180;
    const std::array<double, 3> d1{std::sin(psi), 0, std::cos(psi)};
    const auto s = rootsim::visibleStripe(d1, cross(t, d1), side, up, hw);
    for (double u = -0.98; u <= 0.98; u += 0.07) {
      INFO("psi " << psiDeg << " u " << u);
      const bool vec = std::isfinite(s[0]) && u >= s[0] && u <= s[1];
      // away from the stripe's edges (the sampled extent is exact to a few 1e-3)
      bool nearEdge = std::isfinite(s[0]) && (std::abs(u - s[0]) < 0.02 || std::abs(u - s[1]) < 0.02);
      if (!nearEdge) CHECK(vec == rasterPlus(d1, u));
    }
  }
  // drawn: a straight tube with d1 up shows pink on its centre line, body colour at its flanks
  rootsim::Figure f;
  f.width = 300;
  f.height = 300;
  rootsim::Axes a;
  a.grid = false;
  a.frameOnly = true;
  a.autoX = a.autoY = false;
  a.xmin = -1;
  a.xmax = 1;
  a.ymin = 0;
  a.ymax = 2;
  a.yDown = true;
  rootsim::Tube tb;
  for (int i = 0; i <= 10; ++i) {
    tb.x.push_back(0);
    tb.y.push_back(0.2 * i);
    tb.z.push_back(0.2);
    tb.r.push_back(0.3);
    tb.sx.push_back(1);
    tb.sy.push_back(0);
    tb.plus.push_back(rootsim::visibleStripe(up, cross(t, up), side, up, hw));
    tb.minus.push_back(rootsim::visibleStripe({0, 0, -1}, cross(t, {0, 0, -1}), side, up, hw));
  }
  a.tubes.push_back(tb);
  f.axes.push_back(a);
  const fs::path base = rootsim::test::scratchDir("plot", "tube") / "figure";
  rootsim::SaveOptions so;
  so.dpi = 96;
  rootsim::saveFigure(f, base.string(), so);
  cairo_surface_t* img = cairo_image_surface_create_from_png((base.string() + ".png").c_str());
  REQUIRE(cairo_surface_status(img) == CAIRO_STATUS_SUCCESS);
  const int stride = cairo_image_surface_get_stride(img);
  const unsigned char* d = cairo_image_surface_get_data(img);
  auto px = [&](int x, int y) { return d + y * stride + 4 * x; };  // BGRA
  // plot area x 64..286 (2 units: 111 px a unit), centre line at x = 175, y mid 133
  const unsigned char* c = px(175, 133);
  CHECK(c[2] > 200);  // pink (0.90, 0.20, 0.55)
  CHECK(c[1] < 90);
  const unsigned char* flank = px(175 + 27, 133);  // u = 0.8: outside the stripe (sin 38 = 0.62)
  CHECK(flank[1] > 150);  // body (ivory, shaded), not pink
  cairo_surface_destroy(img);
  CHECK(slurp(base.string() + ".svg").find("<image") == std::string::npos);
}

TEST_CASE("root views draw the plate's obstacles (a peg, a wall with round ends) on a light 1 mm grid") {
  rootsim::Figure f;
  f.width = 300;
  f.height = 300;
  rootsim::Axes a;
  a.grid = false;
  a.frameOnly = true;
  a.autoX = a.autoY = false;
  a.xmin = -1;
  a.xmax = 1;
  a.ymin = 0;
  a.ymax = 2;
  a.yDown = true;
  a.plateGridPitch = 0.5;
  rootsim::Obstacle2D peg;
  peg.fromX = peg.toX = 0.5;
  peg.fromY = peg.toY = 1.0;
  peg.r = 0.2;
  rootsim::Obstacle2D wall;
  wall.fromX = wall.toX = -0.6;
  wall.fromY = 0.3;
  wall.toY = 1.7;
  wall.r = 0.08;
  a.obstacles = {peg, wall};
  f.axes.push_back(a);
  const fs::path base = rootsim::test::scratchDir("plot", "obstacles") / "figure";
  rootsim::SaveOptions so;
  so.dpi = 96;  // one pixel a layout unit
  rootsim::saveFigure(f, base.string(), so);
  cairo_surface_t* img = cairo_image_surface_create_from_png((base.string() + ".png").c_str());
  REQUIRE(cairo_surface_status(img) == CAIRO_STATUS_SUCCESS);
  const int stride = cairo_image_surface_get_stride(img);
  const unsigned char* d = cairo_image_surface_get_data(img);
  // plot area x 64..286 (111 px a unit), y 12..254 (121 px a unit, downhill down); BGRA in memory
  auto px = [&](double x, double y) {
    return d + static_cast<int>(12 + y * 121) * stride + 4 * static_cast<int>(64 + (x + 1) * 111);
  };
  auto slate = [](const unsigned char* p) { return std::abs(p[2] - 143) < 6 && std::abs(p[1] - 158) < 6 && std::abs(p[0] - 184) < 6; };
  CHECK(slate(px(0.5, 1.0)));          // the peg's centre
  CHECK(slate(px(0.5 + 0.12, 1.05)));  // inside its radius
  CHECK(px(0.5 + 0.3, 1.1)[1] > 240);  // outside it: plate
  CHECK(slate(px(-0.6, 1.0)));         // the wall's middle
  CHECK(slate(px(-0.6, 1.75)));        // its round end, beyond the segment
  CHECK(px(-0.6, 1.85)[1] > 240);      // and no further
  CHECK(px(-0.6 + 0.15, 1.0)[1] > 240);
  // the grid: lines every 0.5 units (x = 0 at pixel column 175), white between them
  int darkest = 255;
  for (int x = 172; x <= 178; ++x) darkest = std::min<int>(darkest, d[200 * stride + 4 * x + 1]);
  CHECK(darkest < 245);
  CHECK(darkest > 200);  // light
  CHECK(d[200 * stride + 4 * 147 + 1] == 255);
  cairo_surface_destroy(img);
  // no grid without a pitch
  a.plateGridPitch = 0;
  f.axes = {a};
  rootsim::saveFigure(f, base.string(), so);
  img = cairo_image_surface_create_from_png((base.string() + ".png").c_str());
  d = cairo_image_surface_get_data(img);
  darkest = 255;
  for (int x = 172; x <= 178; ++x) darkest = std::min<int>(darkest, d[200 * stride + 4 * x + 1]);
  CHECK(darkest == 255);
  cairo_surface_destroy(img);
}

TEST_CASE("a straight tube's PNG has no seams across it where its pieces meet") {
  // a tube along y with nodes every 0.137 units (15.2 px: piece boundaries fall inside pixels), no
  // stripes: every pixel column across the body must keep one colour along the tube
  rootsim::Figure f;
  f.width = 300;
  f.height = 300;
  rootsim::Axes a;
  a.grid = false;
  a.frameOnly = true;
  a.autoX = a.autoY = false;
  a.xmin = -1;
  a.xmax = 1;
  a.ymin = 0;
  a.ymax = 2;
  a.yDown = true;
  rootsim::Tube tb;
  for (int i = 0; i <= 14; ++i) {
    tb.x.push_back(0.0);
    tb.y.push_back(0.05 + 0.137 * i);
    tb.z.push_back(0.3 + 1e-9 * ((i * 7) % 5));  // lying on the plate, heights with rounding noise
    tb.r.push_back(0.3);
    tb.sx.push_back(1);
    tb.sy.push_back(0);
  }
  a.tubes.push_back(tb);
  f.axes.push_back(a);
  const fs::path base = rootsim::test::scratchDir("plot", "seams") / "figure";
  rootsim::SaveOptions so;
  so.dpi = 96;
  rootsim::saveFigure(f, base.string(), so);
  cairo_surface_t* img = cairo_image_surface_create_from_png((base.string() + ".png").c_str());
  REQUIRE(cairo_surface_status(img) == CAIRO_STATUS_SUCCESS);
  const int stride = cairo_image_surface_get_stride(img);
  const unsigned char* d = cairo_image_surface_get_data(img);
  // plot area x 64..286 (111 px a unit): the body spans x = 175 -+ 33 px; rows from y = 0.2 to 1.8 units
  // (12 + 121 y px) stay clear of the root's start and its cap
  int worst = 0;
  for (int x = 175 - 31; x <= 175 + 31; ++x) {
    const unsigned char* ref = d + 100 * stride + 4 * x;
    for (int y = 40; y <= 220; ++y)
      for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::abs(d[y * stride + 4 * x + ch] - ref[ch]));
  }
  CHECK(worst <= 2);
  // and the centre of the body is the body colour (ivory 0.95, 0.93, 0.86)
  const unsigned char* c = d + 130 * stride + 4 * 175;
  CHECK(std::abs(c[2] - 242) <= 2);
  CHECK(std::abs(c[1] - 237) <= 2);
  CHECK(std::abs(c[0] - 219) <= 2);
  cairo_surface_destroy(img);
}

TEST_CASE("label layout: a sub- and a superscript in a row stack (kappa_f^0), others run side by side") {
  using rootsim::layoutLabel;
  const auto base = layoutLabel("κ", 12);
  const auto f = layoutLabel("f", 0.7 * 12), zero = layoutLabel("0", 0.7 * 12);
  const auto k = layoutLabel("κ_f^0", 12);
  REQUIRE(k.runs.size() == 3);
  CHECK(k.runs[0].text == "κ");
  CHECK(k.runs[1].text == "f");
  CHECK(k.runs[1].level == -1);
  CHECK(k.runs[2].text == "0");
  CHECK(k.runs[2].level == 1);
  ROOTSIM_CHECK_CLOSE(k.runs[1].x, base.width, kRoundoff);     // the f after the κ
  ROOTSIM_CHECK_CLOSE(k.runs[2].x, k.runs[1].x, kRoundoff);    // the 0 above the f, not beside it
  CHECK(k.runs[2].y < k.runs[1].y - 0.5 * 0.7 * 12);     // above by more than half the script's size
  ROOTSIM_CHECK_CLOSE(k.runs[1].size, 0.7 * 12, kRoundoff);
  ROOTSIM_CHECK_CLOSE(k.width, base.width + std::max(f.width, zero.width), kRoundoff);
  // the other order stacks too, with braces
  const auto k2 = layoutLabel("κ^{0}_{f} [1/mm]", 12);
  REQUIRE(k2.runs.size() == 4);
  ROOTSIM_CHECK_CLOSE(k2.runs[2].x, k2.runs[1].x, kRoundoff);
  ROOTSIM_CHECK_CLOSE(k2.runs[3].x, base.width + std::max(f.width, zero.width), kRoundoff);
  // a lone superscript and a base run after it: side by side
  const auto t = layoutLabel("θ^{tip} [deg]", 12);
  REQUIRE(t.runs.size() == 3);
  ROOTSIM_CHECK_CLOSE(t.runs[2].x, t.runs[1].x + layoutLabel("tip", 0.7 * 12).width, kRoundoff);
  // a third script does not stack on a stacked pair: it follows it
  const auto three = layoutLabel("x_a^b_c", 12);
  REQUIRE(three.runs.size() == 4);
  CHECK(three.runs[3].x > three.runs[2].x);
  // scripts no smaller than the floor asked for (the physical layout's 6 pt)
  ROOTSIM_CHECK_CLOSE(layoutLabel("L_{gz}", 7, false, 6).runs[1].size, 6, kRoundoff);
}

TEST_CASE("same figure, same bytes: PDF (no CreationDate stamped), SVG and PNG saved a second later are identical") {
  const rootsim::Figure f = journalPanel();
  const fs::path a = rootsim::test::scratchDir("plot", "same_a") / "figure", b = rootsim::test::scratchDir("plot", "same_b") / "figure";
  rootsim::saveFigure(f, a.string());
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // the PDF date's resolution is a second
  rootsim::saveFigure(f, b.string());
  // cairo numbers SVG surfaces with a counter per process ("surface7"): each rootsim run starts it
  // afresh, within this test process it has moved on, so the number is left out of the comparison
  auto svgWithoutSurfaceIds = [](std::string t) {
    for (size_t p = t.find("id=\"surface"); p != std::string::npos; p = t.find("id=\"surface", p + 1)) {
      size_t e = p + 11;  // after id="surface
      while (e < t.size() && std::isdigit(static_cast<unsigned char>(t[e]))) ++e;
      t.erase(p + 11, e - (p + 11));
    }
    return t;
  };
  CHECK(slurp(a.string() + ".pdf") == slurp(b.string() + ".pdf"));
  CHECK(slurp(a.string() + ".png") == slurp(b.string() + ".png"));
  CHECK(svgWithoutSurfaceIds(slurp(a.string() + ".svg")) == svgWithoutSurfaceIds(slurp(b.string() + ".svg")));
  CHECK(slurp(a.string() + ".pdf").find("/CreationDate") == std::string::npos);
}

TEST_CASE("figure titles break between phrases and never inside a formula, at 85 and 180 mm") {
  const std::string title = "Fig. 2A: final shapes on the plate (β = γ = 0.1; pink +d_1, orange −d_1; downhill is down)";
  const auto chunks = rootsim::titleChunks(title);
  bool formulaWhole = false;
  for (const std::string& c : chunks) {
    INFO(c);
    for (const char* op : {"=", "/", "+", "−"}) {
      CHECK(c.rfind(op, 0) != 0);
      CHECK(c.compare(c.size() - std::min(c.size(), std::string(op).size()), std::string::npos, op) != 0);
    }
    formulaWhole = formulaWhole || c.find("β = γ = 0.1;") != std::string::npos;
    CHECK(c.rfind("2A", 0) != 0);  // "Fig. 2A" stays together
  }
  CHECK(formulaWhole);
  CHECK(chunks.size() >= 6);
  // a formula with symbols side by side breaks only between its phrases
  const auto inner = rootsim::titleChunks("sin⟨θ⟩ / tan α over β L_{gz} / R, at 40° (the mean)", true);
  CHECK(inner.front() == "sin⟨θ⟩ / tan α over β L_{gz} / R,");
  CHECK(inner.back() == "mean)");
  // in the PDF: the title's lines at 85 mm; the line that holds β also holds γ and 0.1
  for (double mm : {85.0, 180.0}) {
    INFO(mm << " mm");
    const fs::path base = rootsim::test::scratchDir("plot", "title_break") / "figure";
    rootsim::SaveOptions so;
    so.widthMm = mm;
    rootsim::saveFigure(journalPanel(), base.string(), so);
    const std::string xml = capture("pdftotext -bbox '" + base.string() + ".pdf' - 2>&1");
    std::map<long, std::string> lines;  // yMin (0.1 pt) -> words
    for (size_t p = xml.find("<word "); p != std::string::npos; p = xml.find("<word ", p + 1)) {
      const double y = std::stod(xml.substr(xml.find("yMin=\"", p) + 6));
      const size_t a = xml.find('>', p) + 1;
      lines[std::lround(10 * y)] += xml.substr(a, xml.find('<', a) - a) + " ";
    }
    bool seen = false;
    for (const auto& [y, text] : lines)
      if (text.find("β") != std::string::npos && text.find("0.1;") != std::string::npos) seen = true;
    CHECK(seen);
    for (const auto& line : lines) {
      const std::string& text = line.second;
      INFO(text);
      CHECK(text.rfind("= ", 0) != 0);
      CHECK(text.find(" = \n") == std::string::npos);
      CHECK(!(text.size() >= 3 && text.compare(text.size() - 3, 3, " = ") == 0));
    }
  }
}

TEST_CASE("at 85 and 180 mm no two words of a panel overlap (pdftotext -bbox)") {
  rootsim::Figure plot;
  plot.width = 800;
  plot.height = 620;
  rootsim::Axes pa;
  pa.title = "sin⟨θ⟩ / tan α over β L_{gz} / R";
  pa.xlabel = "effective gravitropic gain βL_{gz}/R";
  pa.ylabel = "θ^{tip} [deg]";
  for (int k = 0; k < 3; ++k) {
    rootsim::Series s;
    s.x = {0, 1, 2, 3};
    s.y = {0.0 + k, 1.0 + k, 0.5 + k, 1.5 + k};
    s.label = "E_{b} (zone " + std::to_string(k) + ")";
    pa.series.push_back(s);
  }
  plot.axes.push_back(pa);
  for (const auto& panel : {std::pair{"rows", journalPanel()}, std::pair{"plot", plot}})
    for (double mm : {85.0, 180.0}) {
      const char* name = panel.first;
      const rootsim::Figure& fig = panel.second;
      INFO(name << " at " << mm << " mm");
      const fs::path base = rootsim::test::scratchDir("plot", "overlap_" + std::string(name)) / "figure";
      rootsim::SaveOptions so;
      so.widthMm = mm;
      rootsim::saveFigure(fig, base.string(), so);
      const std::string xml = capture("pdftotext -bbox '" + base.string() + ".pdf' - 2>&1");
      struct Box {
        std::string w;
        double x0, y0, x1, y1;
      };
      std::vector<Box> boxes;
      for (size_t p = xml.find("<word "); p != std::string::npos; p = xml.find("<word ", p + 1)) {
        auto attr = [&](const std::string& k) { return std::stod(xml.substr(xml.find(k + "=\"", p) + k.size() + 2)); };
        const size_t a = xml.find('>', p) + 1;
        boxes.push_back({xml.substr(a, xml.find('<', a) - a), attr("xMin"), attr("yMin"), attr("xMax"), attr("yMax")});
      }
      CHECK(boxes.size() > 10);
      int overlaps = 0;
      for (size_t i = 0; i < boxes.size(); ++i)
        for (size_t j = i + 1; j < boxes.size(); ++j) {
          const Box &a = boxes[i], &b = boxes[j];
          // a subscript and a superscript stacked at one x (κ_f^0) share their column by design
          auto chars = [](const std::string& w) {
            size_t n = 0;
            for (char ch : w) n += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
            return n;
          };
          if (chars(a.w) <= 2 && chars(b.w) <= 2 && std::abs(a.x0 - b.x0) < 0.05) continue;
          // the boxes' overlap, less 0.3 pt (a script's box reaches into its base's)
          const double ox = std::min(a.x1, b.x1) - std::max(a.x0, b.x0), oy = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
          if (ox > 0.3 && oy > 0.3) {
            INFO(a.w << " [" << a.x0 << ", " << a.y0 << "] and " << b.w << " [" << b.x0 << ", " << b.y0 << "]");
            ++overlaps;
            CHECK(false);
          }
        }
      CHECK(overlaps == 0);
    }
}

TEST_CASE("a legend leaves the corner its curve runs through") {
  // a curve from the lower left corner to the upper right one: the legend asked for "ne" goes to a
  // corner the curve does not cross (upper left or lower right)
  rootsim::Figure f;
  f.width = 600;
  f.height = 450;
  rootsim::Axes a;
  a.xlabel = "x";
  a.ylabel = "y";
  rootsim::Series s;
  for (int k = 0; k <= 50; ++k) s.x.push_back(k / 50.0), s.y.push_back(k / 50.0);
  s.label = "diagonal";
  a.series.push_back(s);
  a.legendPos = "ne";
  f.axes.push_back(a);
  const fs::path base = rootsim::test::scratchDir("plot", "legend_off") / "figure";
  rootsim::saveFigure(f, base.string(), rootsim::SaveOptions{});
  const std::string xml = capture("pdftotext -bbox '" + base.string() + ".pdf' - 2>&1");
  const auto page = pageSizePt(base.string() + ".pdf");
  const size_t p = xml.find(">diagonal<");
  REQUIRE(p != std::string::npos);
  const size_t w = xml.rfind("<word ", p);
  auto attr = [&](const std::string& k) { return std::stod(xml.substr(xml.find(k + "=\"", w) + k.size() + 2)); };
  const double cx = 0.5 * (attr("xMin") + attr("xMax")) / page[0], cy = 0.5 * (attr("yMin") + attr("yMax")) / page[1];
  INFO("legend label at " << cx << ", " << cy << " of the page (y down)");
  // upper left (x small, y small) or lower right (x large, y large): not on the diagonal's corners
  CHECK(((cx < 0.5 && cy < 0.5) || (cx > 0.5 && cy > 0.5)));
}

TEST_CASE("a note placed on the frame's edge is drawn inside the frame, clear of its line") {
  // a note at the bottom edge (y = ymin) above the x tick label 0: its box ends well above that label
  rootsim::Figure f;
  f.width = 600;
  f.height = 450;
  rootsim::Axes a;
  a.autoX = a.autoY = false;
  a.xmin = -1, a.xmax = 1, a.ymin = 0, a.ymax = 1;
  a.notes.push_back({{0.0, 0.0}, "coiling"});
  f.axes.push_back(a);
  const fs::path base = rootsim::test::scratchDir("plot", "note_inside") / "figure";
  rootsim::saveFigure(f, base.string(), rootsim::SaveOptions{});
  const std::string xml = capture("pdftotext -bbox '" + base.string() + ".pdf' - 2>&1");
  std::array<double, 2> note{-1, -1};
  double tickTop = -1;  // the lowest "0" on the page: the x tick label (the y axis' 0 sits beside the frame)
  for (size_t p = xml.find("<word "); p != std::string::npos; p = xml.find("<word ", p + 1)) {
    auto attr = [&](const std::string& k) { return std::stod(xml.substr(xml.find(k + "=\"", p) + k.size() + 2)); };
    const size_t at = xml.find('>', p) + 1;
    const std::string w = xml.substr(at, xml.find('<', at) - at);
    if (w == "coiling") note = {attr("yMin"), attr("yMax")};
    if (w == "0") tickTop = std::max(tickTop, attr("yMin"));
  }
  REQUIRE(note[0] > 0);
  REQUIRE(tickTop > 0);
  INFO("note " << note[0] << " .. " << note[1] << " pt, tick label from " << tickTop << " pt");
  // centred on the frame's line, the note's lower half would reach within a point of the tick label
  CHECK(tickTop - note[1] > 0.5 * (note[1] - note[0]));
}

TEST_CASE("a row of root tiles at 85 mm shares one x label when equal labels would crowd each other") {
  for (double mm : {85.0, 180.0}) {
    INFO(mm << " mm");
    const fs::path base = rootsim::test::scratchDir("plot", "row_xlabel") / "figure";
    rootsim::SaveOptions so;
    so.widthMm = mm;
    rootsim::saveFigure(journalPanel(), base.string(), so);
    const std::string xml = capture("pdftotext -bbox '" + base.string() + ".pdf' - 2>&1");
    // each x label's "lateral" and "[mm]" boxes, by line
    std::map<long, std::vector<std::array<double, 2>>> labels;  // yMin -> [xMin of "lateral", xMax of its "[mm]"]
    for (size_t p = xml.find("<word "); p != std::string::npos; p = xml.find("<word ", p + 1)) {
      auto attr = [&](const std::string& k) { return std::stod(xml.substr(xml.find(k + "=\"", p) + k.size() + 2)); };
      const size_t at = xml.find('>', p) + 1;
      const std::string w = xml.substr(at, xml.find('<', at) - at);
      const long y = std::lround(attr("yMin"));
      if (w == "lateral") labels[y].push_back({attr("xMin"), attr("xMax")});
      if (w == "[mm]" && labels.count(y) && !labels[y].empty()) labels[y].back()[1] = attr("xMax");
    }
    REQUIRE(!labels.empty());
    int count = 0;
    for (auto& labelsAtY : labels) {
      auto& row = labelsAtY.second;
      std::sort(row.begin(), row.end());
      count += static_cast<int>(row.size());
      for (size_t k = 1; k < row.size(); ++k) {
        INFO("labels at " << row[k - 1][1] << " and " << row[k][0] << " pt");
        CHECK(row[k][0] - row[k - 1][1] >= 7.0);  // at least an em of the 7 pt labels apart
      }
    }
    if (mm == 85.0) CHECK(count < 6);  // six tiles, fewer labels: a row's one
  }
}

namespace {
// three dense plots shaped like Figs. 2C-E (a square wave swinging over the whole height with a decaying
// wave and a vertical line through it; sharp peaks over a low curve; a sawtooth over a flat line), with
// the panels' legends
rootsim::Figure densePanels() {
  rootsim::Figure f;
  f.width = 1100;
  f.height = 1050;
  f.rows = 3;
  rootsim::Axes c, d, e;
  auto curve = [](auto fn, int color, const std::string& label, bool dashed = false) {
    rootsim::Series s;
    for (int k = 0; k <= 240; ++k) s.x.push_back(0.25 * k), s.y.push_back(fn(0.25 * k));
    s.color = rootsim::paletteColor(color);
    s.label = label;
    s.dashed = dashed;
    return s;
  };
  c.title = "tip angle";
  c.xlabel = "time [h]";
  c.ylabel = "θ^{tip} [deg]";
  c.series.push_back(curve([](double t) { return t < 5 ? 0.0 : 53 * std::tanh(3 * std::sin(0.46 * (t - 5) - 1.2)); }, 0,
                           "on the plate: planar tip angle"));
  c.series.push_back(curve([](double t) { return -40 * std::exp(-t / 6) * std::cos(0.5 * t) + 20 * std::sin(0.2 * t); }, 1,
                           "free organ: angle from gravity"));
  c.series.push_back(curve([](double t) { return 95 * std::sin(0.9 * t); }, 2, "a third curve"));
  rootsim::Series t0;
  t0.x = {5.3, 5.3};
  t0.y = {-90, 90};
  t0.dashed = true;
  t0.color = rootsim::paletteColor(7);
  t0.label = "T_0 (Eq. 7)";
  c.series.push_back(t0);
  c.legendPos = "se";
  d.title = "growth-zone energies";
  d.xlabel = "time [h]";
  d.ylabel = "energy [nJ]";
  d.series.push_back(curve([](double t) { return 250 + 450 * std::pow(0.5 + 0.5 * std::sin(0.95 * t), 8); }, 0, "bending E_{b}"));
  d.series.push_back(curve([](double t) { return 40 + 35 * std::sin(0.95 * t); }, 1, "twisting E_{t}"));
  e.title = "growth-zone topology";
  e.xlabel = "time [h]";
  e.ylabel = "Wr, Tw [turns]";
  e.series.push_back(curve([](double t) { return 0.001 * std::sin(0.5 * t); }, 2, "writhe Wr"));
  e.series.push_back(curve([](double t) { return 0.02 * (2 * std::fmod(0.15 * t, 1.0) - 1); }, 3, "twist Tw"));
  e.series.back().kind = rootsim::Series::Kind::LineMarkers;
  f.axes = {c, d, e};
  return f;
}
}  // namespace

TEST_CASE("a legend lies where no curve or marker passes, else under the axes, at 85 and 180 mm") {
  const rootsim::Figure f = densePanels();
  for (double mm : {85.0, 180.0}) {
    INFO(mm << " mm");
    rootsim::SaveOptions so;
    so.widthMm = mm;
    const auto lay = rootsim::figureLayout(f, so);
    REQUIRE(lay.size() == f.axes.size());
    const double pt = 7.0 / 12.0;  // points per layout unit at --width-mm
    for (size_t i = 0; i < lay.size(); ++i) {
      const auto& l = lay[i];
      const auto& box = l.legend;
      INFO("axes " << i << ", legend at " << box[0] << ", " << box[1] << " (" << box[2] << " x " << box[3]
                   << " pt), " << (l.legendInside ? "inside" : "under the axes"));
      REQUIRE(box[2] > 0);
      if (!l.legendInside) {
        // under the plot area, clear of it
        CHECK(box[1] >= l.plot[1] + l.plot[3] + 1);
        continue;
      }
      CHECK(box[0] >= l.plot[0]);
      CHECK(box[1] >= l.plot[1]);
      CHECK(box[0] + box[2] <= l.plot[0] + l.plot[2]);
      CHECK(box[1] + box[3] <= l.plot[1] + l.plot[3]);
      // every curve, densely sampled, and every marker stays off the box by more than half its stroke
      for (const auto& s : f.axes[i].series) {
        const double reach = s.kind == rootsim::Series::Kind::Line ? 0.5 * s.width * pt : (1.3 * 4.5 + 0.8) * pt;
        for (size_t k = 0; k + 1 < s.x.size(); ++k)
          for (int m = 0; m <= 20; ++m) {
            const double u = m / 20.0;
            const auto q = rootsim::pagePoint(l, s.x[k] + u * (s.x[k + 1] - s.x[k]), s.y[k] + u * (s.y[k + 1] - s.y[k]));
            const double ex = std::max({box[0] - q[0], 0.0, q[0] - box[0] - box[2]});
            const double ey = std::max({box[1] - q[1], 0.0, q[1] - box[1] - box[3]});
            if (std::hypot(ex, ey) <= reach) {
              INFO(s.label << " passes through the legend at " << q[0] << ", " << q[1] << " pt");
              CHECK(false);
              k = s.x.size();
              break;
            }
          }
      }
    }
    // the square wave, the swinging third curve and the vertical line leave no free place in Fig. 2C's
    // plot area: its legend goes under it; at 180 mm Fig. 2D has room between its peaks
    CHECK(!lay[0].legendInside);
    if (mm == 180.0) {
      CHECK(lay[1].legendInside);
    }
    // the drawing puts the legend where the layout says: its labels' words (pdftotext -bbox) inside the box
    const fs::path base = rootsim::test::scratchDir("plot", "dense_legend") / "figure";
    rootsim::saveFigure(f, base.string(), so);
    const std::string xml = capture("pdftotext -bbox '" + base.string() + ".pdf' - 2>&1");
    int found = 0;
    for (const auto& wordAxes : std::vector<std::pair<std::string, size_t>>{{"planar", 0}, {"gravity", 0}, {"bending", 1}, {"twisting", 1}, {"writhe", 2}}) {
      const std::string& word = wordAxes.first;
      const size_t axes = wordAxes.second;
      const size_t p = xml.find(">" + word + "<");
      REQUIRE(p != std::string::npos);
      const size_t w = xml.rfind("<word ", p);
      auto attr = [&](const std::string& k) { return std::stod(xml.substr(xml.find(k + "=\"", w) + k.size() + 2)); };
      const auto& box = lay[axes].legend;
      INFO(word << " at " << attr("xMin") << ".." << attr("xMax") << ", " << attr("yMin") << ".." << attr("yMax"));
      CHECK(attr("xMin") >= box[0]);
      CHECK(attr("xMax") <= box[0] + box[2] + 0.5);
      CHECK(attr("yMin") >= box[1]);
      CHECK(attr("yMax") <= box[1] + box[3]);
      ++found;
    }
    CHECK(found == 5);
  }
}
