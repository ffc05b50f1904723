// the colour maps of --color-by (src/render/colour_map.cpp): diverging for the signed fields, centred on
// zero; sequential for the magnitudes; the colour bar's label with the field's name and unit
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render_test_util.hpp"
#include "rootsim/colour_map.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/render_scene.hpp"
#include "../tolerance_support.hpp"

using rootsim::test::kRoundoff;
using rootsim::test::kFloatRoundoff;

using namespace rootsim;

namespace {

// CIE L* of an sRGB colour 0..1
double lightness(const std::array<float, 3>& c) {
  auto lin = [](double u) { return u <= 0.04045 ? u / 12.92 : std::pow((u + 0.055) / 1.055, 2.4); };
  const double y = 0.2126 * lin(c[0]) + 0.7152 * lin(c[1]) + 0.0722 * lin(c[2]);
  return y > 0.008856 ? 116 * std::cbrt(y) - 16 : 903.3 * y;
}

}  // namespace

TEST_CASE("the diverging map: neutral at 0, blue below, red above, lightness mirrored") {
  const auto mid = coolWarm(0.5);
  ROOTSIM_CHECK_CLOSE(mid[0], 221 / 255.0, kFloatRoundoff);
  ROOTSIM_CHECK_CLOSE(mid[1], 221 / 255.0, kFloatRoundoff);
  ROOTSIM_CHECK_CLOSE(mid[2], 221 / 255.0, kFloatRoundoff);
  // Moreland's published end points
  ROOTSIM_CHECK_CLOSE(coolWarm(0.0)[2], 192 / 255.0, kFloatRoundoff);
  ROOTSIM_CHECK_CLOSE(coolWarm(1.0)[0], 180 / 255.0, kFloatRoundoff);
  for (int i = 1; i <= 16; ++i) {
    const double d = i / 32.0;
    CAPTURE(d);
    const auto lo = coolWarm(0.5 - d), hi = coolWarm(0.5 + d);
    CHECK(lo[2] > lo[0]);  // cool: blue over red
    CHECK(hi[0] > hi[2]);  // warm: red over blue
    CHECK(std::abs(lightness(lo) - lightness(hi)) < 3.5);  // the same lightness either side
    if (i > 1) CHECK(lightness(coolWarm(0.5 - d)) < lightness(coolWarm(0.5 - d + 1 / 32.0)));  // darker away from 0
  }
  // the field's colour: 0 of a symmetric range is the neutral middle for twist, kappa1, kappa2
  for (ColourField f : {ColourField::Twist, ColourField::Kappa1, ColourField::Kappa2}) {
    CHECK(colourFieldSigned(f));
    const auto c = fieldColour(f, 0.0, {-2.0, 2.0});
    CHECK(c == blueGreen(0.5));
    const auto a = fieldColour(f, -1.0, {-2.0, 2.0}), b = fieldColour(f, 1.0, {-2.0, 2.0});
    CHECK(a[2] > a[0]);
    CHECK(a[2] > a[1]);
    CHECK(b[1] > b[0]);
    CHECK(b[1] > b[2]);
  }
  // the magnitudes: viridis without its ends
  for (ColourField f : {ColourField::Curvature, ColourField::Kappa0, ColourField::Stretch, ColourField::Contact}) {
    CHECK_FALSE(colourFieldSigned(f));
    CHECK(fieldColour(f, 0.25, {0.0, 1.0}) == viridis(0.3));
  }
}

TEST_CASE("the signed fields' map: neutral at 0, blue below, green above, lightness mirrored and falling away from 0") {
  const auto mid = blueGreen(0.5);
  CHECK(std::abs(mid[0] - mid[1]) < 0.01f);
  CHECK(std::abs(mid[1] - mid[2]) < 0.01f);
  CHECK(lightness(mid) == doctest::Approx(88).epsilon(0.01));
  for (int i = 1; i <= 16; ++i) {
    const double d = i / 32.0;
    CAPTURE(d);
    const auto lo = blueGreen(0.5 - d), hi = blueGreen(0.5 + d);
    CHECK(lo[2] > lo[0]);
    CHECK(hi[1] > hi[0]);
    CHECK(std::abs(lightness(lo) - lightness(hi)) < 1.0);
    CHECK(lightness(lo) < lightness(blueGreen(0.5 - d + 1 / 32.0)));
    CHECK(lightness(lo) == doctest::Approx(88 - 100 * d).epsilon(0.02));  // in gamut: not clipped
  }
}

TEST_CASE("colour maps keep their hues at least 40 degrees from the stripes' pink and orange") {
  // CIELAB hue; the stripes sit at about 355 (pink) and 62 degrees (orange). Moreland's cool-warm map
  // and viridis' ends come within 35 degrees of them (the reason for the maps used now)
  double worstSigned = 180, worstSeq = 180, worstCoolWarm = 180, worstViridis = 180;
  for (int i = 0; i <= 200; ++i) {
    const double t = i / 200.0;
    worstSigned = std::min(worstSigned, stripeHueDistanceDeg(fieldColour(ColourField::Twist, t, {0.0, 1.0})));
    worstSeq = std::min(worstSeq, stripeHueDistanceDeg(fieldColour(ColourField::Curvature, t, {0.0, 1.0})));
    worstCoolWarm = std::min(worstCoolWarm, stripeHueDistanceDeg(coolWarm(t)));
    worstViridis = std::min(worstViridis, stripeHueDistanceDeg(viridis(t)));
  }
  INFO("signed " << worstSigned << ", sequential " << worstSeq << ", cool-warm " << worstCoolWarm << ", viridis " << worstViridis);
  CHECK(worstSigned >= 40.0);
  CHECK(worstSeq >= 40.0);
  // the check can fail: the maps used before would
  CHECK(worstCoolWarm < 40.0);
  CHECK(worstViridis < 40.0);
}

TEST_CASE("signed fields: a symmetric range, and kappa1 and kappa2 are the bending components") {
  ColourField f{};
  REQUIRE(parseColourField("kappa1", f));
  CHECK(f == ColourField::Kappa1);
  REQUIRE(parseColourField("kappa2", f));
  CHECK(colourFieldNames().find("kappa1") != std::string::npos);
  // a rod twisted one way: the range is still symmetric about 0
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 40, 2.0, 0.1, [](double sMm) { return 1.5 * sMm; });
  const auto r = fieldRange({s}, si, ColourField::Twist);
  ROOTSIM_CHECK_CLOSE(r[0], -r[1], kRoundoff);
  CHECK(r[1] == doctest::Approx(1.5).epsilon(0.02));
  const Eigen::VectorXd tw = nodeField(s, si, ColourField::Twist);
  CHECK(tw[20] == doctest::Approx(1.5).epsilon(0.01));
  // a straight rod has no bending: kappa1 = kappa2 = 0
  CHECK(nodeField(s, si, ColourField::Kappa1).cwiseAbs().maxCoeff() < 1e-6);
  CHECK(nodeField(s, si, ColourField::Kappa2).cwiseAbs().maxCoeff() < 1e-6);
  const auto rk = fieldRange({s}, si, ColourField::Kappa1);
  ROOTSIM_CHECK_CLOSE(rk[0], -rk[1], kRoundoff);
}

TEST_CASE("colour bar: the field's name and unit, 0 marked, the diverging map's colours") {
  const SceneInfo si = rtest::info(40);
  const Snapshot s = rtest::straightRod(40, 40, 2.0, 0.1, [](double sMm) { return 1.5 * sMm; });
  View v = rtest::viewOf(1280, 720);
  v.colourBy = ColourField::Twist;
  v.colourRange = {-2.0, 2.0};
  const Framing f = frameFor({s}, si, v);
  const RenderScene rs = buildRenderScene(s, si, v, f);
  CHECK(colourFieldLabel(ColourField::Twist) == "twist \xCE\xBA\xE2\x82\x83 [rad/mm]");
  bool title = false, zero = false;
  float titleX = 0;
  for (const OverlayText& t : rs.texts) {
    if (t.text == "twist \xCE\xBA\xE2\x82\x83 [rad/mm]") title = true, titleX = t.x;
    if (t.text == "0") zero = true;
  }
  CHECK(title);
  CHECK(zero);
  CHECK(titleX > 0.8f * v.width);
  // the bar's pixels: blue at the bottom, neutral in the middle, green at the top
  GlRenderer r(v.width, v.height);
  const Image img = r.render(rs);
  const float m = 0.7f * overlayFontPx(v);
  const int x = static_cast<int>(v.width - m - 4);
  const int yTop = static_cast<int>(0.28 * v.height) + 4, yBottom = static_cast<int>(0.78 * v.height) - 4;
  const std::uint8_t* top = img.at(x, yTop);
  const std::uint8_t* bottom = img.at(x, yBottom);
  CHECK(top[1] > top[0] + 50);
  CHECK(top[1] > top[2] + 20);
  CHECK(bottom[2] > bottom[0] + 50);
  // just off the 0 line (it is drawn across the bar): grey
  const std::uint8_t* mid = img.at(x, static_cast<int>(0.53 * v.height) + 4);
  CHECK(std::max({mid[0], mid[1], mid[2]}) - std::min({mid[0], mid[1], mid[2]}) < 30);
  // the framing keeps a root lying across the picture left of the bar, its ticks and title
  Snapshot across = s;
  const double a = 40 * rtest::kDeg;
  const Eigen::Vector3d lateral(1, 0, 0), normal(0, -std::cos(a), std::sin(a)), downhill(0, -std::sin(a), -std::cos(a));
  for (long i = 0; i < across.x.cols(); ++i)
    across.x.col(i) = (8e-3 * static_cast<double>(i) / static_cast<double>(across.x.cols() - 1)) * lateral + 1e-4 * normal;
  for (long e = 0; e < across.d3.cols(); ++e) across.d3.col(e) = lateral, across.d1.col(e) = -downhill;
  const Framing fa = frameFor({across}, si, v);
  const double barX = v.width - m - std::round(0.6f * overlayFontPx(v));
  const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
  double right = 0, left = 1e9;
  for (long i = 0; i < across.x.cols(); ++i) {
    const Eigen::Vector3d q = pf.toPlateMm(across.x.col(i));
    right = std::max(right, topViewPixel(fa, v, q.x(), q.y()).x());
    left = std::min(left, topViewPixel(fa, v, q.x(), q.y()).x());
  }
  INFO("root from " << left << " to " << right << " px, bar at " << barX);
  CHECK(right < barX - 150);  // clear of the tick labels and of the title above the bar
  CHECK(left > 0.5 * m);
}
