// pixels where the physics puts them (src/render/render_scene.cpp + gl_renderer.cpp): orientation of
// the top view, stripes at +-d1, twist, the millimetre grid, overlays, golden image, determinism
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "render_test_util.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/paraview.hpp"
#include "rootsim/png.hpp"
#include "rootsim/render_scene.hpp"
#include "../tolerance_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;
using rtest::Paint;

namespace {

// 2.4 mm across 640 px: 266.7 px/mm, the 0.1 mm radius is 26.7 px
View closeUp(bool transparent = true) {
  View v = rtest::viewOf(640, 360);
  v.overlays = false;
  v.transparent = transparent;
  v.centreMm = std::array<double, 2>{0.0, -0.5};
  v.widthMm = 2.4;
  return v;
}

Image draw(GlRenderer& r, const Snapshot& s, const SceneInfo& si, const View& v) {
  return r.render(buildRenderScene(s, si, v, frameFor({s}, si, v)));
}

// leftmost and rightmost column of row y whose alpha exceeds 128 (-1 if none)
std::pair<int, int> span(const Image& img, int y) {
  int lo = -1, hi = -1;
  for (int x = 0; x < img.width; ++x)
    if (img.at(x, y)[3] > 128) {
      if (lo < 0) lo = x;
      hi = x;
    }
  return {lo, hi};
}

}  // namespace

TEST_CASE("a straight rod along downhill is vertical in the top view, base up, tip down") {
  GlRenderer r(640, 360);
  for (double alpha : {0.0, 40.0, 80.0}) {
    CAPTURE(alpha);
    const SceneInfo si = rtest::info(alpha);
    const View v = closeUp();
    const Framing f = frameFor({rtest::straightRod(alpha, 20, 1.0, 0.1)}, si, v);
    const Image img = draw(r, rtest::straightRod(alpha, 20, 1.0, 0.1), si, v);
    REQUIRE(img.width == 640);
    REQUIRE(img.height == 360);
    // expected: u = 0 at every row, base (v = 0) at the top end, tip (v = -1 mm) at the bottom end
    const double pxPerMm = 640 / 2.4, rPx = 0.1 * pxPerMm;
    const Eigen::Vector2d base = topViewPixel(f, v, 0.0, 0.0), tip = topViewPixel(f, v, 0.0, -1.0);
    CHECK(tip.y() > base.y() + 250);
    int rows = 0, first = -1, last = -1;
    for (int y = 0; y < img.height; ++y) {
      const auto [lo, hi] = span(img, y);
      if (lo < 0) continue;
      if (first < 0) first = y;
      last = y;
      if (y < base.y() + 2 || y > tip.y() - rPx - 2) continue;  // the caps
      ++rows;
      CHECK(std::abs(0.5 * (lo + hi + 1) - base.x()) <= 1.0);
      CHECK(std::abs((hi + 1 - lo) - 2 * rPx) <= 2.0);
    }
    CHECK(rows > 200);
    CHECK(std::abs(first - base.y()) <= 1.5);
    CHECK(std::abs(last + 1 - (tip.y() + rPx)) <= 1.5);  // the hemispherical tip
  }
}

TEST_CASE("stripes: +d1 pink, -d1 orange, where d1 points") {
  GlRenderer r(640, 360);
  const SceneInfo si = rtest::info(40);
  const View v = closeUp();
  const int y = 200;  // mid length
  auto at = [&](double thetaDeg) {
    const Image img = draw(r, rtest::straightRod(40, 20, 1.0, 0.1, [&](double) { return thetaDeg * rtest::kDeg; }), si, v);
    return img;
  };

  SUBCASE("d1 rotated +90 deg about d3 (toward the viewer): the top of the tube is pink") {
    const Image img = at(90);
    const auto [lo, hi] = span(img, y);
    REQUIRE(lo >= 0);
    const int c = (lo + hi) / 2;
    for (int dx = -8; dx <= 8; dx += 4) CHECK(rtest::name(rtest::paint(img.at(c + dx, y))) == std::string("pink"));
    CHECK(rtest::paint(img.at(lo + 3, y)) == Paint::Body);
    CHECK(rtest::paint(img.at(hi - 3, y)) == Paint::Body);
  }
  SUBCASE("-90 deg: the top is orange") {
    const Image img = at(-90);
    const auto [lo, hi] = span(img, y);
    const int c = (lo + hi) / 2;
    for (int dx = -8; dx <= 8; dx += 4) CHECK(rtest::name(rtest::paint(img.at(c + dx, y))) == std::string("orange"));
  }
  SUBCASE("0 deg (d1 lateral, +x to the right): pink on the right silhouette, orange on the left") {
    const Image img = at(0);
    const auto [lo, hi] = span(img, y);
    const int c = (lo + hi) / 2;
    CHECK(rtest::name(rtest::paint(img.at(c, y))) == std::string("body"));
    CHECK(rtest::name(rtest::paint(img.at(hi - 2, y))) == std::string("pink"));
    CHECK(rtest::name(rtest::paint(img.at(lo + 2, y))) == std::string("orange"));
    // the stripe is readable: at least 3 px wide on each silhouette
    int pink = 0, orange = 0;
    for (int x = lo; x <= hi; ++x) {
      pink += rtest::paint(img.at(x, y)) == Paint::Plus;
      orange += rtest::paint(img.at(x, y)) == Paint::Minus;
    }
    CHECK(pink >= 3);
    CHECK(orange >= 3);
  }
  SUBCASE("180 deg: the sides swap") {
    const Image img = at(180);
    const auto [lo, hi] = span(img, y);
    CHECK(rtest::name(rtest::paint(img.at(hi - 2, y))) == std::string("orange"));
    CHECK(rtest::name(rtest::paint(img.at(lo + 2, y))) == std::string("pink"));
  }
}

TEST_CASE("a rod twisted once: the pink stripe crosses the top once, then the orange one") {
  GlRenderer r(640, 360);
  const SceneInfo si = rtest::info(40);
  const View v = closeUp();
  // right-handed twist: theta grows from 0 at the base to 2 pi at the tip
  const Snapshot s = rtest::straightRod(40, 60, 1.0, 0.1, [](double sMm) { return 2 * std::numbers::pi * sMm; });
  const Image img = draw(r, s, si, v);
  const Framing f = frameFor({s}, si, v);
  const int cx = static_cast<int>(topViewPixel(f, v, 0, 0).x());
  const int y0 = static_cast<int>(topViewPixel(f, v, 0, -0.02).y()), y1 = static_cast<int>(topViewPixel(f, v, 0, -0.98).y());
  // runs of the centre column's paint from base to tip
  std::string runs;
  for (int y = y0; y <= y1; ++y) {
    const char* n = rtest::name(rtest::paint(img.at(cx, y)));
    if (runs.empty() || runs.substr(runs.rfind(' ') + 1) != n) runs += std::string(runs.empty() ? "" : " ") + n;
  }
  CHECK(runs == "body pink body orange body");
  // the pink crossing is centred a quarter of the way down (theta = 90 deg), orange at three quarters
  double sumPink = 0, nPink = 0, sumOrange = 0, nOrange = 0;
  for (int y = y0; y <= y1; ++y) {
    const Paint p = rtest::paint(img.at(cx, y));
    if (p == Paint::Plus) sumPink += y, ++nPink;
    if (p == Paint::Minus) sumOrange += y, ++nOrange;
  }
  REQUIRE(nPink > 0);
  REQUIRE(nOrange > 0);
  CHECK(std::abs(sumPink / nPink - topViewPixel(f, v, 0, -0.25).y()) < 6);
  CHECK(std::abs(sumOrange / nOrange - topViewPixel(f, v, 0, -0.75).y()) < 6);
}

TEST_CASE("the grid is 1 mm in the framing's pixels") {
  GlRenderer r(800, 600);
  const SceneInfo si = rtest::info(40);
  View v = rtest::viewOf(800, 600);
  v.overlays = false;
  v.centreMm = std::array<double, 2>{0.3, -2.0};
  v.widthMm = 7.5;  // 106.7 px/mm
  const Snapshot s = rtest::straightRod(40, 10, 1.0, 0.1);
  const Framing f = frameFor({s}, si, v);
  const RenderScene rs = buildRenderScene(s, si, v, f);
  ROOTSIM_CHECK_CLOSE(rs.pxPerMm, 800 / 7.5, kRoundoff);
  const Image img = r.render(rs);
  const std::uint8_t* plate = img.at(5, 5);
  auto dark = [&](int x, int y) { return plate[1] - img.at(x, y)[1] > 8; };
  // a row below the rod: vertical lines at integer u, where topViewPixel puts them
  const int row = static_cast<int>(topViewPixel(f, v, 0, -4.5).y());
  std::vector<double> centres;
  for (int x = 0; x < img.width;) {
    if (!dark(x, row)) {
      ++x;
      continue;
    }
    int e = x;
    while (e < img.width && dark(e, row)) ++e;
    centres.push_back(0.5 * (x + e));
    x = e;
  }
  // visible u: 0.3 -+ 3.75 mm, so the lines u = -3 .. 4
  REQUIRE(centres.size() == 8);
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const double u = -3.0 + static_cast<double>(i);
    CHECK(std::abs(centres[i] - topViewPixel(f, v, u, -4.5).x()) <= 1.0);
    if (i > 0) CHECK(centres[i] - centres[i - 1] == doctest::Approx(rs.pxPerMm).epsilon(0.02));
  }
  // a column beside the rod: horizontal lines at integer v
  const int col = static_cast<int>(topViewPixel(f, v, 2.5, 0).x());
  std::vector<int> starts;
  for (int y = 1; y < img.height; ++y)
    if (dark(col, y) && !dark(col, y - 1)) starts.push_back(y);
  // visible v: -2 -+ 2.8125 mm, so the lines v = 0 .. -4, top to bottom
  REQUIRE(starts.size() == 5);
  for (std::size_t i = 0; i < starts.size(); ++i)
    CHECK(std::abs(starts[i] + 0.5 - topViewPixel(f, v, 2.5, -static_cast<double>(i)).y()) <= 1.5);
}

TEST_CASE("overlays: time, parameters and a scale bar, each can be turned off") {
  GlRenderer r(640, 360);
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 10, 1.0, 0.1);
  View v = rtest::viewOf(640, 360);
  v.showLegend = false;  // the legend and the downhill arrow: test_legend.cpp
  v.showDownhill = false;
  const Framing f = frameFor({s}, si, v);
  const RenderScene rs = buildRenderScene(s, si, v, f);
  REQUIRE(rs.texts.size() == 3);  // time, parameters, scale-bar label
  CHECK(rs.texts[0].text == "t = 1.5 h");
  CHECK(rs.texts[1].text.find("\xCE\xB1 = 40") != std::string::npos);
  CHECK(rs.texts[1].text.find("\xCE\xB2 = 0.2") != std::string::npos);
  CHECK(rs.texts[1].text.find("\xCE\xB3 = 0.1") != std::string::npos);
  CHECK(rs.texts[1].text.find("R\xCF\x84") == std::string::npos);  // R tau only when nonzero
  REQUIRE(rs.rects.size() == 1);
  // the bar is a round length in mm at the framing's scale
  const double barMm = rs.rects[0].w / rs.pxPerMm;
  CHECK(rs.texts[2].text == std::to_string(static_cast<int>(std::lround(barMm))) + " mm");
  CHECK(std::abs(barMm - std::round(barMm)) < 0.02);

  auto darkIn = [](const Image& img, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += img.at(x, y)[0] < 100;
    return n;
  };
  const Image with = r.render(rs);
  View off = v;
  off.overlays = false;
  const Image without = r.render(buildRenderScene(s, si, off, f));
  CHECK(darkIn(with, 0, 0, 160, 40) > 20);          // "t = 1.5 h" top left
  CHECK(darkIn(with, 400, 0, 640, 40) > 100);       // alpha beta gamma top right
  CHECK(darkIn(with, 400, 300, 640, 360) > 200);    // scale bar bottom right
  CHECK(darkIn(without, 0, 0, 160, 40) == 0);
  CHECK(darkIn(without, 400, 0, 640, 40) == 0);
  CHECK(darkIn(without, 400, 300, 640, 360) == 0);

  SceneInfo twisted = si;
  twisted.rTau = -0.4;
  const RenderScene rt = buildRenderScene(s, twisted, v, f);
  CHECK(rt.texts[1].text.find("R\xCF\x84 = -0.4") != std::string::npos);
  View noTime = v;
  noTime.showTime = false;
  noTime.showScaleBar = false;
  const RenderScene rn = buildRenderScene(s, si, noTime, f);
  CHECK(rn.texts.size() == 1);
  CHECK(rn.rects.empty());
}

TEST_CASE("golden image: a twisted rod with whiskers and overlays, within tolerance") {
  GlRenderer r(320, 180);
  const SceneInfo si = rtest::info(40);
  View v = rtest::viewOf(320, 180);
  v.whiskers = true;
  const Snapshot s = rtest::straightRod(40, 40, 2.0, 0.1, [](double sMm) { return std::numbers::pi * sMm; });
  const Image img = draw(r, s, si, v);
  const std::string golden = std::string(ROOTSIM_RENDER_TEST_DATA) + "/golden_twisted_320x180.png";
  if (std::getenv("ROOTSIM_UPDATE_GOLDEN")) {
    writePng(golden, img);
    MESSAGE("wrote " << golden);
  }
  const Image ref = readPng(golden);
  REQUIRE(ref.width == img.width);
  REQUIRE(ref.height == img.height);
  // per-pixel tolerance (rasteriser and rounding differences between Mesa versions), and a cap on
  // the fraction of pixels beyond it; never byte-exact
  constexpr int kTol = 12;
  long differing = 0;
  int worst = 0;
  for (std::size_t i = 0; i < img.rgba.size(); i += 4) {
    int d = 0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(img.rgba[i + c]) - int(ref.rgba[i + c])));
    worst = std::max(worst, d);
    differing += d > kTol;
  }
  const double fraction = static_cast<double>(differing) / (img.width * img.height);
  INFO("pixels beyond " << kTol << ": " << differing << " (" << fraction * 100 << " %), worst " << worst
                        << "; set ROOTSIM_UPDATE_GOLDEN=1 to rewrite after a deliberate change");
  CHECK(fraction <= 0.005);
}

TEST_CASE("same scene, same pixels") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 30, 1.5, 0.1, [](double sMm) { return 3.0 * sMm; });
  View v = rtest::viewOf(400, 300);
  v.whiskers = true;
  GlRenderer a(400, 300);
  const Image one = draw(a, s, si, v), two = draw(a, s, si, v);
  GlRenderer b(400, 300);
  const Image three = draw(b, s, si, v);
  INFO("hashes " << rtest::hash(one) << " " << rtest::hash(two) << " " << rtest::hash(three));
  CHECK(one.rgba == two.rgba);
  CHECK(one.rgba == three.rgba);
}

TEST_CASE("transparent background: alpha 0 off the root, 255 on it") {
  GlRenderer r(640, 360);
  const Image img = draw(r, rtest::straightRod(40, 20, 1.0, 0.1), rtest::info(40), closeUp(true));
  CHECK(img.at(5, 5)[3] == 0);
  CHECK(img.at(320, 200)[3] == 255);
  CHECK(int(img.at(320, 200)[0]) > 150);  // straight alpha: the body is light, not premultiplied
}

TEST_CASE("3-D preset: the root is in the picture, the plate around it") {
  GlRenderer r(640, 360);
  View v = rtest::viewOf(640, 360);
  v.kind = View::Kind::Perspective;
  v.overlays = false;
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 20, 3.0, 0.1, [](double sMm) { return sMm; });
  const RenderScene rs = buildRenderScene(s, si, v, frameFor({s}, si, v));
  CHECK(rs.pxPerMm == 0.0);
  const Image img = r.render(rs);
  // the root's pixels (clearly not plate-grey: saturated or shaded) sit around the picture centre
  long n = 0;
  double sx = 0, sy = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      const int sat = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
      if (sat > 40) ++n, sx += x, sy += y;
    }
  REQUIRE(n > 500);
  CHECK(std::abs(sx / n - 320) < 80);
  CHECK(std::abs(sy / n - 180) < 80);
}

TEST_CASE("3-D preset: the fit view fills the picture with the root's projection") {
  // the oblique camera shows the top view's box smaller: the fit window is fitted to the nodes'
  // projection, so a coil-sized root fills the part of the picture the top view keeps for it
  View v = rtest::viewOf(640, 360);
  v.kind = View::Kind::Perspective;
  const SceneInfo si = rtest::info(40);
  Snapshot s = rtest::straightRod(40, 30, 2.0, 0.1);
  for (long i = 0; i < s.x.cols(); ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(s.x.cols() - 1);
    s.x.col(i) += Eigen::Vector3d(1.5e-3 * std::sin(3 * t), 0, 0);
  }
  const RenderScene rs = buildRenderScene(s, si, v, frameFor({s}, si, v));
  const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (long i = 0; i < s.x.cols(); ++i) {
    Eigen::Vector2d px;
    REQUIRE(projectToPixel(rs, pf.toPlateMm(s.x.col(i)), px));
    x0 = std::min(x0, px.x()), x1 = std::max(x1, px.x()), y0 = std::min(y0, px.y()), y1 = std::max(y1, px.y());
  }
  INFO("nodes at " << x0 << ".." << x1 << " x " << y0 << ".." << y1 << " px");
  // inside the middle 80 % of the height the overlays leave, and filling it or the width
  CHECK(x0 > 0);
  CHECK(x1 < 640);
  CHECK(y0 > 0.1 * 360);
  CHECK(y1 < 0.9 * 360);
  CHECK(std::max((x1 - x0) / 640, (y1 - y0) / (0.8 * 360)) > 0.75);  // less the margin and the radius
}

TEST_CASE("errors name the problem") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 10, 1.0, 0.1);
  View v;
  v.width = 0;
  CHECK_THROWS_WITH_AS(frameFor({s}, si, v), doctest::Contains("size must be positive"), RenderError);
  CHECK_THROWS_WITH_AS(GlRenderer(0, 10), doctest::Contains("size must be positive"), RenderError);
  CHECK_THROWS_WITH_AS(frameFor({}, si, View{}), doctest::Contains("no snapshots"), RenderError);
  Snapshot bad = s;
  bad.d1.resize(3, 3);
  CHECK_THROWS_WITH_AS(buildRenderScene(bad, si, View{}, Framing{}), doctest::Contains("inconsistent shapes"),
                       RenderError);
  View missingFont = rtest::viewOf(64, 64);
  missingFont.fontPath = "/nonexistent/font.ttf";
  GlRenderer r(64, 64);
  CHECK_THROWS_WITH_AS(r.render(buildRenderScene(s, si, missingFont, frameFor({s}, si, missingFont))),
                       doctest::Contains("/nonexistent/font.ttf"), RenderError);
  // a RenderError is a RunError: the CLI exits 1 on it
  CHECK_THROWS_AS(GlRenderer(-1, -1), RunError);
}

TEST_CASE("shaders from disk (development option) draw what the built-in copies draw") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 20, 1.0, 0.1, [](double sMm) { return 2.0 * sMm; });
  View v = rtest::viewOf(320, 180);
  GlRenderer builtIn(320, 180);
  RendererOptions disk;
  disk.shaderDir = std::string(ROOTSIM_SOURCE_DIR) + "/shaders";
  GlRenderer fromDisk(320, 180, disk);
  CHECK(builtIn.samples() == fromDisk.samples());
  CHECK(builtIn.glVersion().find("4.5") != std::string::npos);
  CHECK(draw(builtIn, s, si, v).rgba == draw(fromDisk, s, si, v).rgba);
  RendererOptions missing;
  missing.shaderDir = "/nonexistent/shaders";
  CHECK_THROWS_WITH_AS(GlRenderer(64, 64, missing), doctest::Contains("/nonexistent/shaders/tube.vert"), RenderError);
}

TEST_CASE("the ParaView script's stripes (paraview.hpp) are the renderer's: half width and colours") {
  const StripeStyle pv;
  const View v;
  const RenderScene::Material m;
  CHECK(pv.halfWidthDeg == v.stripeHalfWidthDeg);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(static_cast<float>(pv.body[k]) == m.body[k]);
    CHECK(static_cast<float>(pv.plus[k]) == m.plus[k]);
    CHECK(static_cast<float>(pv.minus[k]) == m.minus[k]);
  }
}

TEST_CASE("overlays: a plate view names each seedling above its seed and gives each one's beta and R tau in a legend") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 10, 1.0, 0.1);
  View v = rtest::viewOf(640, 360);
  v.showLegend = false;
  v.showDownhill = false;
  v.seedLabels = {{"wt1", "wild type", 0.2, 0.3, "wt1   b1"}, {"tw1", "", 0.8, 0.3, "tw1   b2"}};
  const Framing f = frameFor({s}, si, v);
  const RenderScene rs = buildRenderScene(s, si, v, f);
  auto text = [&](const std::string& t) -> const OverlayText* {
    for (const OverlayText& o : rs.texts)
      if (o.text == t) return &o;
    return nullptr;
  };
  for (const View::SeedLabel& sl : v.seedLabels) {
    INFO(sl.label);
    const OverlayText* name = text(sl.label);
    REQUIRE(name);
    // centred on the seed's pixel, above it (up the picture: uphill)
    const double seedX = 0.5 * v.width + (sl.u - f.centreU) * rs.pxPerMm, seedY = 0.5 * v.height - (sl.v - f.centreV) * rs.pxPerMm;
    CHECK(name->anchor == OverlayText::Anchor::BottomCentre);
    CHECK(std::abs(name->x - seedX) < 1.0);
    CHECK(name->y < seedY);
    if (!sl.sub.empty()) {
      const OverlayText* sub = text(sl.sub);
      REQUIRE(sub);
      CHECK(sub->x == name->x);
      CHECK(name->y < sub->y);  // the genotype under the name
      CHECK(sub->y < seedY);
      CHECK(sub->sizePx < name->sizePx);
    }
    // its legend line at the right edge, under the header
    const OverlayText* line = text(sl.values);
    REQUIRE(line);
    CHECK(line->anchor == OverlayText::Anchor::TopRight);
    CHECK(line->x > 0.9 * v.width);
  }
  CHECK(text("wt1   b1")->y < text("tw1   b2")->y);
  // the header: alpha and gamma, no beta (each seedling has its own)
  bool header = false;
  for (const OverlayText& o : rs.texts)
    if (o.text.find("\xCE\xB1 = 40") != std::string::npos) {
      header = true;
      CHECK(o.text.find("\xCE\xB3 = 0.1") != std::string::npos);
      CHECK(o.text.find("\xCE\xB2") == std::string::npos);
      CHECK(o.y < text("wt1   b1")->y);
    }
  CHECK(header);
}
