// montage labels (src/app/montage_runs.cpp): scene keys as symbols with units, the values every run
// shares once in a caption; placed under each root (src/render/montage.cpp)
#include <doctest/doctest.h>

#include <string>

#include "render_test_util.hpp"
#include "rootsim/montage.hpp"
#include "rootsim/montage_runs.hpp"
#include "rootsim/scene.hpp"
#include "../tolerance_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;

namespace {

Model modelWith(const std::string& toml) { return parseScene(toml, "test.toml").model; }

// a straight root of lengthMm on the 40-degree plate (radius radiusMm, 20 elements) whose nodes move
// with their fraction t of the way from base to tip by t * lateralM metres along +u and t * downhillM
// downhill (negative: uphill)
Snapshot rootAt40(double lengthMm, double radiusMm, double lateralM = 0, double downhillM = 0) {
  Snapshot s = rtest::straightRod(40, 20, lengthMm, radiusMm);
  const double al = 40 * rtest::kDeg;
  const Eigen::Vector3d lateral(1, 0, 0), downhill(0, -std::sin(al), -std::cos(al));
  for (long i = 0; i < s.x.cols(); ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(s.x.cols() - 1);
    s.x.col(i) += (lateralM * t) * lateral + (downhillM * t) * downhill;
  }
  return s;
}

// a montage run of one snapshot on the 40-degree plate, with its label
MontageRun montageRun(const Snapshot& s, const std::string& label = "") {
  MontageRun r;
  r.info = rtest::info(40);
  r.snaps = {s};
  r.label = label;
  return r;
}

}  // namespace

TEST_CASE("montage labels: symbols and units for what differs, a caption for what is shared") {
  const std::string base = "[tropism]\nbeta = 0.1\ngamma = 0.1\n[growth]\nsteps = 10\n";
  const std::vector<Model> models = {modelWith(base + "[plane]\nalpha_deg = 0\n"),
                                     modelWith(base + "[plane]\nalpha_deg = 40\n")};
  const app::MontageLabels l = app::montageLabels(models, {"a", "b"});
  REQUIRE(l.labels.size() == 2);
  CHECK(l.labels[0] == "\xCE\xB1 = 0\xC2\xB0");
  CHECK(l.labels[1] == "\xCE\xB1 = 40\xC2\xB0");
  INFO("caption: " << l.caption);
  CHECK(l.caption.find("\xCE\xB2 = \xCE\xB3 = 0.1") != std::string::npos);
  CHECK(l.caption.find("L_gz = ") != std::string::npos);
  CHECK(l.caption.find(" mm") != std::string::npos);
  CHECK(l.caption.find("\xCE\xB1") == std::string::npos);  // what differs is not in the caption

  // two keys differ: both, in the table's order; nothing differs: the runs' names
  const std::vector<Model> two = {modelWith(base + "[plane]\nalpha_deg = 30\n"),
                                  modelWith("[tropism]\nbeta = 0.2\ngamma = 0.1\n[growth]\nsteps = 10\n[plane]\nalpha_deg = 60\n")};
  const app::MontageLabels l2 = app::montageLabels(two, {"a", "b"});
  CHECK(l2.labels[1] == "\xCE\xB1 = 60\xC2\xB0, \xCE\xB2 = 0.2");
  const app::MontageLabels same = app::montageLabels({models[0], models[0]}, {"first", "second"});
  CHECK(same.labels[0] == "first");
  CHECK(same.labels[1] == "second");
}

TEST_CASE("montage: a label sits under its own root, not in the middle of the tile") {
  const MontageRun a = montageRun(rootAt40(1.0, 0.1), "\xCE\xB1 = 0\xC2\xB0");
  // b: a root that leaves its base sideways, towards +u
  const MontageRun b = montageRun(rootAt40(2.0, 0.1, 2.0e-3, -1.0e-3), "\xCE\xB1 = 40\xC2\xB0");
  const View v = rtest::viewOf(1280, 720);
  const MontageLayout l = montageLayout({a, b}, v);
  CHECK(l.labelPx >= 14);
  View tile = v;
  tile.width = l.tileW;
  tile.height = l.tileH;
  const auto pa = montageLabelAnchor(a, tile, l.framing[0], 100, l.labelPx);
  const auto pb = montageLabelAnchor(b, tile, l.framing[1], 100, l.labelPx);
  // a hangs straight down from its base: its label under the base; b's under its sideways extent
  const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
  const Eigen::Vector3d baseA = pf.toPlateMm(a.snaps[0].x.col(0));
  const Eigen::Vector2d baseAPx = topViewPixel(l.framing[0], tile, baseA.x(), baseA.y());
  // (a label 100 px wide stops at the tile's edge: half its width plus 0.3 em from it)
  const double half = 50 + 0.3 * l.labelPx;
  CHECK(std::abs(pa[0] - std::clamp(baseAPx.x(), half, l.tileW - half)) < 3);
  CHECK(pb[0] > pa[0] + 0.5 * l.tileW / l.framing[1].widthMm);  // at least 0.5 mm further right
  // under the root's lowest point, inside the tile
  const Eigen::Vector3d tipA = pf.toPlateMm(a.snaps[0].x.col(a.snaps[0].x.cols() - 1));
  CHECK(pa[1] > topViewPixel(l.framing[0], tile, tipA.x(), tipA.y()).y());
  CHECK(pa[1] <= l.tileH);
}

TEST_CASE("montage: the last tile's scale bar and downhill text match the labels' size") {
  const SceneInfo info = rtest::info(40);
  const std::vector<MontageRun> runs(3, montageRun(rootAt40(1.0, 0.1), "\xCE\xB1 = 40\xC2\xB0"));
  const View v = rtest::viewOf(1280, 720);
  const MontageLayout l = montageLayout(runs, v);
  ROOTSIM_CHECK_CLOSE(l.labelPx, 21, kRoundoff);  // 720 / 34
  for (std::size_t i = 0; i < runs.size(); ++i) {
    INFO("tile " << i);
    const View tv = montageTileView(l, v, i, runs.size());
    CHECK(tv.width == l.tileW);
    CHECK(!tv.showTime);
    CHECK(!tv.showLegend);
    const RenderScene rs = buildRenderScene(runs[i].snaps.back(), info, tv, l.framing[i]);
    const bool last = i + 1 == runs.size();
    CHECK(rs.texts.empty() == !last);  // the common scale and arrow on the last tile only
    bool scale = false, downhill = false;
    for (const OverlayText& t : rs.texts) {
      INFO(t.text << " at " << t.sizePx << " px");
      if (t.text.find(" mm") != std::string::npos) {
        scale = true;
        ROOTSIM_CHECK_CLOSE(t.sizePx, l.labelPx, kRoundoff);
      }
      if (t.text == kDownhillLabel) {
        downhill = true;
        ROOTSIM_CHECK_CLOSE(t.sizePx, std::round(0.8f * l.labelPx), kRoundoff);  // the single view's ratio
      }
      CHECK(t.sizePx >= 0.8f * l.labelPx - 0.5f);
    }
    CHECK(scale == last);
    CHECK(downhill == last);
  }
}

TEST_CASE("montage: the tiles are framed on the union footprint of all runs, in the top and the 3-D view") {
  // a short root hanging downhill and one leaving its base sideways: every node of both, in its tile,
  // lies inside the tile above the label band, and their union's box fills the tile in its tighter
  // direction (a fixed 1 mm margin left a 1 mm root a third of the tile)
  const SceneInfo info = rtest::info(40);
  const MontageRun a = montageRun(rootAt40(1.0, 0.05)), b = montageRun(rootAt40(1.2, 0.05, 1.0e-3, -0.6e-3));
  for (View::Kind kind : {View::Kind::Top, View::Kind::Perspective}) {
    INFO((kind == View::Kind::Top ? "top" : "3-D") << " view");
    View v = rtest::viewOf(640, 360);
    v.kind = kind;
    const std::vector<MontageRun> runs{a, b};
    const MontageLayout l = montageLayout(runs, v);
    const double band = 2.1 * l.labelPx;
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      View tv = montageTileView(l, v, k, runs.size());
      tv.overlays = false;
      const RenderScene rs = buildRenderScene(runs[k].snaps.back(), info, tv, l.framing[k]);
      const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
      for (long i = 0; i < runs[k].snaps.back().x.cols(); ++i) {
        Eigen::Vector2d px;
        REQUIRE(projectToPixel(rs, pf.toPlateMm(runs[k].snaps.back().x.col(i)), px));
        x0 = std::min(x0, px.x()), x1 = std::max(x1, px.x()), y0 = std::min(y0, px.y()), y1 = std::max(y1, px.y());
      }
    }
    INFO("union box " << x0 << ".." << x1 << " x " << y0 << ".." << y1 << " px in a tile of " << l.tileW << " x "
                      << l.tileH << " with a label band of " << band << " px");
    CHECK(x0 > 0);
    CHECK(x1 < l.tileW);
    CHECK(y0 > 0);
    CHECK(y1 < l.tileH - band);
    const double fill = std::max((x1 - x0) / l.tileW, (y1 - y0) / (l.tileH - band));
    CHECK(fill > 0.8);
  }
}

TEST_CASE("montage: the last tile's colour bar keeps clear of the run's label") {
  // a root going down and to the left, and a short one hanging down: the second tile's root stands at
  // its upper right, its label under it at the height of the colour bar's title at the right edge
  const SceneInfo info = rtest::info(40);
  const MontageRun a = montageRun(rootAt40(3.0, 0.05, -1.5e-3), "\xCE\xB1 = 40\xC2\xB0");
  const MontageRun b = montageRun(rootAt40(0.6, 0.05), "\xCE\xB1 = 80\xC2\xB0, \xCE\xB2 = 0.2");
  View v = rtest::viewOf(800, 450);
  v.colourBy = ColourField::Twist;
  v.colourRange = {-1.0, 1.0};
  const std::vector<MontageRun> runs{a, b};
  const MontageLayout l = montageLayout(runs, v);
  const View plain = montageTileView(l, v, 1, 2);
  const float labelW = 0.55f * l.labelPx * 16;  // wider than the label's 16 characters are drawn
  const auto anchor = montageLabelAnchor(b, plain, l.framing[1], labelW, l.labelPx);
  const auto box = montageLabelBox(anchor, labelW, l.labelPx);
  INFO("label box " << box[0] << ", " << box[1] << " .. " << box[2] << ", " << box[3] << " in a tile of " << l.tileW
                    << " x " << l.tileH);
  auto meets = [&](const RenderScene& rs) {
    int n = 0;
    auto overlap = [&](const std::array<float, 4>& q) {
      return std::min(q[2], box[2]) > std::max(q[0], box[0]) && std::min(q[3], box[3]) > std::max(q[1], box[1]);
    };
    for (const OverlayRect& r : rs.rects) {
      n += overlap({r.x, r.y, r.x + r.w, r.y + r.h});
    }
    for (const OverlayText& t : rs.texts) {
      OverlayBlock one;
      one.texts = {t};
      const auto q = blockBox(one, v.fontPath);
      n += overlap(q);
    }
    return n;
  };
  const View kept = montageTileView(l, v, 1, 2, box);
  CHECK(kept.keepClearPx.size() == plain.keepClearPx.size() + 1);
  // without the label's box the colour bar lies on the label (so the case tests something); with it, clear
  CHECK(meets(buildRenderScene(b.snaps.back(), info, plain, l.framing[1])) > 0);
  CHECK(meets(buildRenderScene(b.snaps.back(), info, kept, l.framing[1])) == 0);
}
