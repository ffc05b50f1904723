// the overlays that explain a picture (src/render/render_scene.cpp, compose.cpp): the stripe legend,
// the downhill arrow, the scale references of every view, grid lines that stay visible at 4K
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render_test_util.hpp"
#include "rootsim/compose.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/render_scene.hpp"
#include "../tolerance_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;

namespace {

const OverlayText* findText(const RenderScene& rs, const std::string& text) {
  for (const OverlayText& t : rs.texts)
    if (t.text == text) return &t;
  return nullptr;
}

int darkness(const std::uint8_t* p) { return 255 - (299 * p[0] + 587 * p[1] + 114 * p[2]) / 1000; }

}  // namespace

TEST_CASE("legend: a pink swatch by +d1 and an orange one by -d1, bottom left, clear of the root") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 20, 2.0, 0.1);
  View v = rtest::viewOf(1280, 720);
  const Framing f = frameFor({s}, si, v);
  const RenderScene rs = buildRenderScene(s, si, v, f);
  const OverlayText* plus = findText(rs, kLegendPlus);
  const OverlayText* minus = findText(rs, kLegendMinus);
  REQUIRE(plus);
  REQUIRE(minus);
  CHECK(std::string(kLegendMinus) == "\xE2\x88\x92" "d1");
  // both in the bottom band on the left, +d1 first
  CHECK(plus->x < 0.3f * v.width);
  CHECK(minus->x > plus->x);
  CHECK(plus->y > 0.88f * v.height);
  GlRenderer r(v.width, v.height);
  const Image img = r.render(rs);
  // pixels just left of each label, at the label's middle height: the swatch's colour
  auto swatch = [&](const OverlayText* t) {
    const int y = static_cast<int>(t->y + 0.5f * t->sizePx);
    const int x = static_cast<int>(t->x - 0.3f * t->sizePx - 0.5f * std::round(1.3f * t->sizePx));
    return rtest::paint(img.at(x, y));
  };
  CHECK(swatch(plus) == rtest::Paint::Plus);
  CHECK(swatch(minus) == rtest::Paint::Minus);
  const std::uint8_t* p = img.at(static_cast<int>(plus->x - 0.9f * plus->sizePx), static_cast<int>(plus->y + 0.5f * plus->sizePx));
  CHECK(std::abs(p[0] - std::lround(255 * rs.material.plus[0])) <= 2);
  CHECK(std::abs(p[1] - std::lround(255 * rs.material.plus[1])) <= 2);
  CHECK(std::abs(p[2] - std::lround(255 * rs.material.plus[2])) <= 2);
  // the root lies above the bottom band: the framing keeps the overlays off it
  const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
  for (long i = 0; i < s.x.cols(); ++i) {
    const Eigen::Vector3d q = pf.toPlateMm(s.x.col(i));
    CHECK(topViewPixel(f, v, q.x(), q.y()).y() + 0.1 * rs.pxPerMm < plus->y);
  }
  View off = v;
  off.showLegend = false;
  CHECK_FALSE(findText(buildRenderScene(s, si, off, f), kLegendPlus));
  off = v;
  off.overlays = false;
  CHECK(buildRenderScene(s, si, off, f).texts.empty());
}

TEST_CASE("downhill arrow: in the top view it points down the picture") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 20, 2.0, 0.1);
  View v = rtest::viewOf(1280, 720);
  v.showScaleBar = false;  // only the arrow's ink in the bottom right corner
  const Framing f = frameFor({s}, si, v);
  const RenderScene rs = buildRenderScene(s, si, v, f);
  const OverlayText* label = findText(rs, kDownhillLabel);
  REQUIRE(label);
  REQUIRE(!rs.lines.empty());
  // the arrow's box from its strokes; then its ink, row by row
  float x0 = 1e9f, x1 = -1e9f, y0 = 1e9f, y1 = -1e9f;
  for (const OverlayLine& l : rs.lines)
    for (const auto& q : l.points) x0 = std::min(x0, q[0]), x1 = std::max(x1, q[0]), y0 = std::min(y0, q[1]), y1 = std::max(y1, q[1]);
  CHECK(x0 > label->x);  // right of its label
  CHECK(y1 - y0 > 0.8f * label->sizePx);
  GlRenderer r(v.width, v.height);
  const Image img = r.render(rs);
  std::vector<int> width;  // dark pixels per row over the arrow's box
  double sumY = 0, n = 0;
  for (int y = static_cast<int>(y0) - 4; y <= static_cast<int>(y1) + 4; ++y) {
    int w = 0;
    for (int x = static_cast<int>(x0) - 6; x <= static_cast<int>(x1) + 6; ++x)
      if (darkness(img.at(x, y)) > 120) ++w, sumY += y, ++n;
    width.push_back(w);
  }
  REQUIRE(n > 30);
  const std::size_t half = width.size() / 2;
  const int topMax = *std::max_element(width.begin(), width.begin() + static_cast<long>(half));
  const int bottomMax = *std::max_element(width.begin() + static_cast<long>(half), width.end());
  INFO("widest row of the upper half " << topMax << " px, of the lower half " << bottomMax << " px");
  CHECK(bottomMax >= 2 * topMax);  // the head is at the bottom: the arrow points down
  CHECK(sumY / n > 0.5 * (y0 + y1));  // and the ink's weight is there
}

TEST_CASE("downhill arrow in the 3-D view follows the plate's slope, and the grid's pitch is stated") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 20, 2.0, 0.1);
  View v = rtest::viewOf(1280, 720);
  v.kind = View::Kind::Perspective;
  const Framing f = frameFor({s}, si, v);
  const RenderScene rs = buildRenderScene(s, si, v, f);
  REQUIRE(findText(rs, kDownhillLabel));
  // the pitch the plate draws: 1 mm, or 0.1 mm where the fit view zooms in on a short root
  INFO("grid pitch " << rs.plate.gridMm << " mm");
  CHECK(findText(rs, rs.plate.gridMm >= 1 ? "grid 1 mm" : "grid 0.1 mm, dark every 1 mm"));
  // the arrow's shaft goes the way the plate's downhill goes in the picture
  Eigen::Vector2d a, b;
  REQUIRE(projectToPixel(rs, Eigen::Vector3d(f.centreU, f.centreV, 0), a));
  REQUIRE(projectToPixel(rs, Eigen::Vector3d(f.centreU, f.centreV - 1, 0), b));
  const OverlayLine& shaft = rs.lines.front();
  REQUIRE(shaft.points.size() == 2);
  const Eigen::Vector2d d(shaft.points[1][0] - shaft.points[0][0], shaft.points[1][1] - shaft.points[0][1]);
  CHECK(d.normalized().dot((b - a).normalized()) > 0.999);
  CHECK(d.y() > 0);  // downhill is down the picture in the oblique preset too
}

TEST_CASE("grid lines grow with the picture: at least 2 px wide at 3840x2160") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 10, 1.0, 0.1);
  for (const auto& size : {std::pair{1280, 720}, std::pair{3840, 2160}}) {
    const int w = size.first, h = size.second;
    CAPTURE(w);
    View v = rtest::viewOf(w, h);
    v.overlays = false;
    v.centreMm = std::array<double, 2>{0.3, -2.0};
    v.widthMm = 20.0;  // 192 px/mm at 4K: the 1 mm grid
    const Framing f = frameFor({s}, si, v);
    const RenderScene rs = buildRenderScene(s, si, v, f);
    CHECK(rs.plate.lineWidthPx >= (w >= 3840 ? 2.0f : 1.0f));
    GlRenderer r(w, h);
    const Image img = r.render(rs);
    // a row below the rod crossing the line u = 2 mm: the line's ink summed over the row, as
    // a fraction of the full line-to-plate contrast, is its width in pixels
    const int row = static_cast<int>(topViewPixel(f, v, 0, -4.5).y());
    const int cx = static_cast<int>(topViewPixel(f, v, 2.0, -4.5).x());
    const std::uint8_t* plate = img.at(cx + static_cast<int>(0.4 * rs.pxPerMm), row);
    const double contrast = plate[1] - 255.0 * rs.plate.line[1];
    REQUIRE(rs.plate.gridMm == 1.0f);
    double ink = 0;
    int dark = 0;
    for (int x = cx - 8; x <= cx + 8; ++x) {
      const double d = (plate[1] - img.at(x, row)[1]) / contrast;
      ink += std::max(0.0, d);
      dark += d > 0.3;
    }
    INFO("line ink " << ink << " px, " << dark << " px darker than half");
    if (w >= 3840) {
      CHECK(ink >= 1.8);
      CHECK(dark >= 2);
    } else {
      CHECK(ink >= 0.8);
    }
  }
}

TEST_CASE("inset: its own scale bar and its magnification") {
  std::vector<Snapshot> snaps;
  for (int k = 1; k <= 4; ++k) {
    Snapshot s = rtest::straightRod(40, 40, 2.0 * k, 0.1);
    s.timeH = k;
    snaps.push_back(s);
  }
  const SceneInfo info = rtest::info(40);
  MovieJob job;
  job.view.width = 1280;
  job.view.height = 720;
  job.inset = true;
  job.fieldMm = 1.5;
  const FramePlan plan = planFrames(snaps, info, job);
  FrameComposer comp(info, job, plan);
  Image img;
  comp.compose(snaps.back(), 3, img);
  const FrameLayout& l = comp.layout();
  REQUIRE(l.inset);
  // magnification: the inset's px/mm over the view's
  const double expected = (l.insetW / plan.inset.back().widthMm) / (l.viewW / plan.view.front().widthMm);
  ROOTSIM_CHECK_CLOSE(comp.lastInsetMagnification(), expected, kRoundoff);
  CHECK(expected > 2);
  // ink in the inset's bottom right: its scale bar and, left of it, its "x6", on a light backing
  auto inkIn = [&](int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += darkness(img.at(x, y)) > 150;
    return n;
  };
  const int side = l.insetW;
  CHECK(inkIn(l.insetX + side * 3 / 4, l.insetY + side * 4 / 5, l.insetX + side - 4, l.insetY + side - 4) > 60);
  CHECK(inkIn(l.insetX + side / 3, l.insetY + side * 4 / 5, l.insetX + side * 3 / 4, l.insetY + side - 4) > 20);
  // the legend stays visible: the inset's corner is not on the bottom band's left end
  CHECK(l.insetY + l.insetH < job.view.height - 1.5 * overlayFontPx(job.view));
}
