// figure panels: `rootsim figure all --quick` (run by the figures_quick ctest fixture) made every panel,
// each PNG has drawn content, and the quick runs show the paper's patterns
#include <doctest/doctest.h>

#include <cairo.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "rootsim/figure.hpp"
#include "rootsim/plot.hpp"

namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
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
}  // namespace

TEST_CASE("every panel exists as PNG and SVG with drawn content") {
  for (const auto& n : rootsim::figureNames()) {
    INFO(n);
    REQUIRE(fs::exists(kOut / (n + ".png")));
    REQUIRE(fs::exists(kOut / (n + ".svg")));
    CHECK(slurp(kOut / (n + ".svg")).find("<svg") != std::string::npos);
    int w = 0, h = 0;
    const double ink = inkFraction(kOut / (n + ".png"), &w, &h);
    CHECK(ink > 0.005);  // not blank
    CHECK(ink < 0.95);   // fig3d is mostly coloured background
    CHECK(w >= 600);     // the panel sizes set in src/figure/figure.cpp
    CHECK(w <= 2200);
    CHECK(h >= 500);
    CHECK(h <= 1100);
  }
  CHECK(slurp(kOut / "report.md").find("## fig4g") != std::string::npos);
}

TEST_CASE("quick report: straight at 0 deg, waving in the middle, coiling at high alpha, and skew grows with omega T0") {
  const std::string r = slurp(kOut / "report.md");
  CHECK(r.find("| 0 | straight |") != std::string::npos);
  CHECK(r.find("| 40 | waving |") != std::string::npos);
  CHECK(r.find("| 80 | coiling |") != std::string::npos);
  const auto p = r.find("| Fig. 4A: intrinsic twist makes the root skew; skew grows with ω T0 |");
  REQUIRE(p != std::string::npos);
  const std::string row = r.substr(p, r.find('\n', p) - p);
  INFO(row);
  CHECK(row.size() > 8);
  CHECK(row.substr(row.size() - 7) == "| yes |");
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
  const fs::path base = fs::temp_directory_path() / "rootsim_plot_test";
  rootsim::saveFigure(f, base.string());
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
