// composed movie frames (src/render/camera.cpp, colour_map.cpp, compose.cpp, montage.cpp, shadows in
// gl_renderer.cpp): pixels where the cameras, colours, plots, tiles and shadows should put them
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "render_test_util.hpp"
#include "rootsim/camera.hpp"
#include "rootsim/colour_map.hpp"
#include "rootsim/compose.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/montage.hpp"
#include "rootsim/movie.hpp"
#include "rootsim/png.hpp"
#include "rootsim/units.hpp"
#include "../tolerance_support.hpp"

using rootsim::test::kRoundoff;
using rootsim::test::kFloatRoundoff;

namespace fs = std::filesystem;
using namespace rootsim;

namespace {

// a rod lying on a plate tilted by alphaDeg along a planar centreline given in plate (u, v) [mm] as
// a function of arc length; d1 in the plate (stripes on the sides from above), n elements
Snapshot planarRod(double alphaDeg, int n, double lengthMm, double radiusMm,
                   const std::function<Eigen::Vector2d(double)>& uv, double timeH = 0.0) {
  const PlateFrame pf = PlateFrame::tilted(alphaDeg * units::deg);
  Snapshot s;
  s.timeH = timeH;
  s.x.resize(3, n + 1);
  s.d1.resize(3, n);
  s.d3.resize(3, n);
  s.radius = Eigen::VectorXd::Constant(n, radiusMm * units::mm);
  auto lab = [&](const Eigen::Vector2d& p, double w) -> Eigen::Vector3d {
    return units::mm * (p.x() * pf.lateral + p.y() * pf.uphill() + w * pf.normal);
  };
  for (int i = 0; i <= n; ++i) s.x.col(i) = lab(uv(lengthMm * i / n), radiusMm);
  for (int e = 0; e < n; ++e) {
    const Eigen::Vector3d d3 = (s.x.col(e + 1) - s.x.col(e)).normalized();
    s.d3.col(e) = d3;
    s.d1.col(e) = pf.normal.cross(d3).normalized();  // in the plate, normal to the axis
  }
  return s;
}

// a rod growing downhill while waving sideways, 0.12 mm per frame, its element count growing (splits)
std::vector<Snapshot> wavingGrowth(int frames) {
  std::vector<Snapshot> v;
  for (int k = 0; k < frames; ++k) {
    const double L = 1.0 + 0.12 * k;
    const int n = 10 * (1 + k / 8);  // doubles now and then, like element splits
    Snapshot s = planarRod(40, n, L, 0.1, [](double sMm) { return Eigen::Vector2d(0.6 * std::sin(sMm / 1.2), -sMm); });
    s.timeH = 0.5 * k;
    s.step = k;
    v.push_back(std::move(s));
  }
  return v;
}

bool saturated(const std::uint8_t* p, int min = 40) { return std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > min; }

std::uint8_t luminance(const std::uint8_t* p) {
  return static_cast<std::uint8_t>((299 * p[0] + 587 * p[1] + 114 * p[2]) / 1000);
}

}  // namespace

TEST_CASE("follow camera: the tip region stays central in every frame, the tube is >= 80 px wide at 2 mm") {
  const std::vector<Snapshot> snaps = wavingGrowth(24);
  const SceneInfo info = rtest::info(40);
  MovieJob job;
  job.view.width = 1280;
  job.view.height = 720;
  job.view.transparent = true;  // alpha marks the root
  job.view.overlays = false;
  job.camera = CameraMode::Follow;
  job.fieldMm = 2.0;
  const FramePlan plan = planFrames(snaps, info, job);
  REQUIRE(plan.view.size() == snaps.size());
  FrameComposer comp(info, job, plan);
  const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
  Image img;
  Eigen::Vector2d prevCentre = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < snaps.size(); ++k) {
    comp.compose(snaps[k], static_cast<int>(k), img);
    const Framing& f = plan.view[k];
    ROOTSIM_CHECK_CLOSE(f.widthMm, 2.0, kRoundoff);
    // the tip region (last 0.3 mm) on the picture: its pixels are root pixels, in the middle 60 %
    const Eigen::Vector2d c = tipRegionCentre(snaps[k], pf, 0.3);
    const Eigen::Vector2d px = topViewPixel(f, job.view, c.x(), c.y());
    INFO("frame " << k << " tip region at " << px.transpose());
    CHECK(px.x() > 0.2 * 1280);
    CHECK(px.x() < 0.8 * 1280);
    CHECK(px.y() > 0.2 * 720);
    CHECK(px.y() < 0.8 * 720);
    CHECK(img.at(static_cast<int>(px.x()), static_cast<int>(px.y()))[3] == 255);
    // the tip itself is in the picture too
    const Eigen::Vector3d tip = pf.toPlateMm(snaps[k].x.col(snaps[k].x.cols() - 1));
    const Eigen::Vector2d tpx = topViewPixel(f, job.view, tip.x(), tip.y());
    CHECK(tpx.x() > 0.1 * 1280);
    CHECK(tpx.x() < 0.9 * 1280);
    CHECK(tpx.y() > 0.1 * 720);
    CHECK(tpx.y() < 0.9 * 720);
    // smooth: the window moves at most a little more than the root grows per frame (0.12 mm),
    // also across the element-count doublings at frames 8 and 16
    const Eigen::Vector2d centre(f.centreU, f.centreV);
    if (k > 0) CHECK((centre - prevCentre).norm() < 0.2);
    prevCentre = centre;
    // width: the root's run of opaque pixels across the row through the tip region, measured
    // perpendicular to the axis (run length x |cos| of the axis' angle to the horizontal)
    const int row = static_cast<int>(px.y());
    int x0 = static_cast<int>(px.x()), x1 = x0;
    while (x0 > 0 && img.at(x0 - 1, row)[3] > 127) --x0;
    while (x1 < 1279 && img.at(x1 + 1, row)[3] > 127) ++x1;
    const Eigen::Vector3d a = pf.toPlateMm(snaps[k].x.col(snaps[k].x.cols() - 3)), b = tip;
    const Eigen::Vector2d axis = (b - a).head<2>().normalized();
    const double across = (x1 - x0 + 1) * std::abs(axis.y());
    INFO("tube " << across << " px across");
    CHECK(across >= 80);
    CHECK(across <= 140);  // 0.2 mm at 640 px/mm = 128 px
  }
  // a split keeps the centreline, so the followed point does not move
  const Snapshot coarse = planarRod(40, 10, 2.0, 0.1, [](double s) { return Eigen::Vector2d(0.0, -s); });
  const Snapshot fine = planarRod(40, 20, 2.0, 0.1, [](double s) { return Eigen::Vector2d(0.0, -s); });
  CHECK((tipRegionCentre(coarse, pf, 0.6) - tipRegionCentre(fine, pf, 0.6)).norm() < 1e-9);
  CHECK_THROWS_AS(followFramings(snaps, info, 1280, 720, FollowOptions{0.0, 2.0, 0.2}), RenderError);
}

TEST_CASE("inset: the region marked on the fit view is what the inset shows") {
  const std::vector<Snapshot> snaps = wavingGrowth(20);
  const SceneInfo info = rtest::info(40);
  MovieJob job;
  job.view.width = 960;
  job.view.height = 540;
  job.view.colourBy = ColourField::Curvature;  // a saturated tube on a grey plate
  job.view.colourRange = fieldRange(snaps, info, ColourField::Curvature);
  job.inset = true;
  job.fieldMm = 1.5;
  const FramePlan plan = planFrames(snaps, info, job);
  FrameComposer comp(info, job, plan);
  const FrameLayout& l = comp.layout();
  REQUIRE(l.inset);
  Image img;
  for (int k : {10, 19}) {
    comp.compose(snaps[static_cast<std::size_t>(k)], k, img);
    const std::vector<Eigen::Vector2d> mark = comp.lastInsetMark();
    REQUIRE(mark.size() == 4);
    // the mark is an axis-aligned rectangle with the inset's aspect
    const double mx0 = std::min(mark[0].x(), mark[2].x()), mx1 = std::max(mark[0].x(), mark[2].x());
    const double my0 = std::min(mark[0].y(), mark[2].y()), my1 = std::max(mark[0].y(), mark[2].y());
    CHECK((mx1 - mx0) / (my1 - my0) == doctest::Approx(1.0).epsilon(0.01));
    // the mark is drawn: its top edge has the mark colour (0, 110, 230) off the root (it passes under
    // the root, docs/rendering.md, Overlays laid out around the root)
    int markPx = 0;
    for (int x = static_cast<int>(mx0) + 2; x < static_cast<int>(mx1) - 2; ++x) {
      bool hit = false;
      for (int y = static_cast<int>(my0) - 1; y <= static_cast<int>(my0) + 1; ++y) {
        const std::uint8_t* q = img.at(x, y);
        hit = hit || (q[0] < 40 && std::abs(q[1] - 110) < 30 && std::abs(q[2] - 230) < 30);
      }
      markPx += hit;
    }
    CHECK(markPx > (mx1 - mx0) / 2);
    // root pixels (saturated, not the mark's blue) in normalised coordinates of each box
    auto centroid = [&](double x0, double y0, double x1, double y1) {
      const double in = 0.04 * (x1 - x0);  // keep clear of the borders
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      int cnt = 0;
      for (int y = static_cast<int>(y0 + in); y < static_cast<int>(y1 - in); ++y)
        for (int x = static_cast<int>(x0 + in); x < static_cast<int>(x1 - in); ++x) {
          const std::uint8_t* p = img.at(x, y);
          const bool blue = p[2] > 170 && p[0] < 80 && p[1] > 80 && p[1] < 150;
          if (saturated(p) && !blue) sum += Eigen::Vector2d((x - x0) / (x1 - x0), (y - y0) / (y1 - y0)), ++cnt;
        }
      return std::make_pair(cnt > 0 ? Eigen::Vector2d(sum / cnt) : Eigen::Vector2d(-1, -1), cnt);
    };
    const auto rootInMark = centroid(mx0, my0, mx1, my1);
    const auto rootInInset = centroid(l.insetX, l.insetY, l.insetX + l.insetW, l.insetY + l.insetH);
    const Eigen::Vector2d &cMark = rootInMark.first, &cInset = rootInInset.first;
    const int nMark = rootInMark.second, nInset = rootInInset.second;
    INFO("frame " << k << ": mark " << cMark.transpose() << " (" << nMark << " px), inset " << cInset.transpose()
                  << " (" << nInset << " px)");
    REQUIRE(nMark > 50);
    REQUIRE(nInset > 50);
    CHECK((cMark - cInset).norm() < 0.05);
    // the inset is magnified by the ratio of the boxes: root area scales with its square
    const double zoom = l.insetW / (mx1 - mx0);
    CHECK(nInset / static_cast<double>(nMark) == doctest::Approx(zoom * zoom).epsilon(0.35));
  }
}

TEST_CASE("curvature colour: a bent part is coloured toward the top of the map, a straight part toward the bottom") {
  // straight for 2 mm downhill, then an arc of radius 1 mm (curvature 1/mm) turning sideways
  auto uv = [](double s) {
    if (s <= 2.0) return Eigen::Vector2d(0.0, -s);
    const double a = s - 2.0;  // arc angle [rad] on radius 1 mm
    return Eigen::Vector2d(1.0 - std::cos(a), -2.0 - std::sin(a));
  };
  const Snapshot rod = planarRod(40, 120, 3.5, 0.1, uv);
  const SceneInfo info = rtest::info(40);
  const Eigen::VectorXd k = nodeField(rod, info, ColourField::Curvature);
  CHECK(k[30] == doctest::Approx(0.0).epsilon(1e-6));
  CHECK(k[110] == doctest::Approx(1.0).epsilon(0.01));
  View v = rtest::viewOf(640, 640);
  v.overlays = false;
  v.colourBy = ColourField::Curvature;
  v.colourRange = {0.0, 1.0};
  const Framing f = frameFor({rod}, info, v);
  GlRenderer gl(v.width, v.height);
  const Image img = gl.render(buildRenderScene(rod, info, v, f));
  const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
  auto topOf = [&](int node) {
    const Eigen::Vector3d p = pf.toPlateMm(rod.x.col(node));
    const Eigen::Vector2d px = topViewPixel(f, v, p.x(), p.y());
    return img.at(static_cast<int>(px.x()), static_cast<int>(px.y()));
  };
  const std::uint8_t* straight = topOf(30);  // s = 0.875 mm
  const std::uint8_t* bent = topOf(110);     // s = 3.2 mm, on the arc
  auto dist = [](const std::uint8_t* p, const std::array<float, 3>& c) {
    return std::hypot(p[0] - 255.0 * c[0], p[1] - 255.0 * c[1], p[2] - 255.0 * c[2]);
  };
  INFO("straight " << int(straight[0]) << "," << int(straight[1]) << "," << int(straight[2]) << "  bent " << int(bent[0])
                   << "," << int(bent[1]) << "," << int(bent[2]));
  // viridis runs from dark purple (low) to yellow (high): lightness and green grow along it
  CHECK(dist(straight, viridis(0.0)) < dist(straight, viridis(1.0)));
  CHECK(dist(bent, viridis(1.0)) < dist(bent, viridis(0.0)));
  CHECK(luminance(bent) > luminance(straight) + 80);
  // the stripes still show on the silhouettes of the coloured tube: pink on one side, orange on the other
  const Eigen::Vector3d p = pf.toPlateMm(rod.x.col(30));
  const Eigen::Vector2d c = topViewPixel(f, v, p.x(), p.y());
  const double rPx = 0.1 * v.width / f.widthMm;
  const int y = static_cast<int>(c.y());
  int pink = 0, orange = 0;
  for (int x = static_cast<int>(c.x() - rPx); x <= static_cast<int>(c.x() + rPx); ++x) {
    const rtest::Paint q = rtest::paint(img.at(x, y));
    pink += q == rtest::Paint::Plus, orange += q == rtest::Paint::Minus;
  }
  CHECK(pink >= 2);
  CHECK(orange >= 2);
  // the colour map itself: the published end points, increasing lightness
  ROOTSIM_CHECK_CLOSE(viridis(0.0)[0], 0x44 / 255.0, kFloatRoundoff);
  ROOTSIM_CHECK_CLOSE(viridis(1.0)[1], 0xe7 / 255.0, kFloatRoundoff);
  for (int i = 0; i < 10; ++i) {
    const auto a = viridis(0.1 * i), b = viridis(0.1 * (i + 1));
    CHECK(0.299 * b[0] + 0.587 * b[1] + 0.114 * b[2] > 0.299 * a[0] + 0.587 * a[1] + 0.114 * a[2]);
  }
}

TEST_CASE("plot panel: the curve is drawn up to now and ends at the current value") {
  std::vector<Snapshot> snaps;
  for (int k = 0; k <= 10; ++k) {
    Snapshot s = rtest::straightRod(40, 20, 1.0 + 0.2 * k, 0.1);
    s.timeH = 0.5 * k;
    snaps.push_back(s);
  }
  PlotSeries sq;
  sq.name = "square";
  sq.unit = "J";
  sq.siPrefix = true;
  for (int i = 0; i <= 50; ++i) sq.timeH.push_back(0.1 * i), sq.value.push_back(1e-9 * (0.1 * i) * (0.1 * i));
  PlotSeries lin = sq;
  lin.name = "falling";
  lin.unit = "";
  lin.siPrefix = false;
  for (std::size_t i = 0; i < lin.value.size(); ++i) lin.value[i] = 3.0 - lin.timeH[i];
  MovieJob job;
  job.view.width = 1280;
  job.view.height = 720;
  job.plots = {sq, lin};
  const SceneInfo info = rtest::info(40);
  FrameComposer comp(info, job, planFrames(snaps, info, job));
  const FrameLayout& l = comp.layout();
  REQUIRE(l.panel);
  CHECK(l.panelX == l.viewW);  // landscape: beside the view
  Image img;
  const std::array<std::array<int, 3>, 2> colour{{{31, 119, 180}, {214, 39, 40}}};
  for (int k : {3, 7}) {
    const Snapshot& s = snaps[static_cast<std::size_t>(k)];
    comp.compose(s, k, img);
    for (int series = 0; series < 2; ++series) {
      const PlotSeries& ps = series == 0 ? sq : lin;
      const double now = s.timeH, value = series == 0 ? 1e-9 * now * now : 3.0 - now;
      const Eigen::Vector2d end = comp.plotPixel(series, now, value);
      const double top = comp.plotPixel(series, 0, series == 0 ? 1e-9 * 25 : 3.0).y() - 8;
      const double bottom = comp.plotPixel(series, 0, series == 0 ? 0.0 : -2.0).y() + 8;
      // pixels of the series' colour inside its plot area
      int right = -1;
      double yAtRight = 0;
      int near = 0;
      for (int y = static_cast<int>(top); y <= static_cast<int>(bottom); ++y)
        for (int x = l.panelX; x < l.width; ++x) {
          const std::uint8_t* p = img.at(x, y);
          const auto& c = colour[static_cast<std::size_t>(series)];
          if (std::abs(p[0] - c[0]) + std::abs(p[1] - c[1]) + std::abs(p[2] - c[2]) > 30) continue;
          if (x > right) right = x, yAtRight = y;
          if ((Eigen::Vector2d(x + 0.5, y + 0.5) - end).norm() < 3) ++near;
        }
      INFO("frame " << k << " series " << ps.name << ": curve ends at x " << right << ", expected " << end.x());
      // the curve ends in the dot at now (radius ~ 1.6 x line width): no pixel of it further right
      CHECK(right >= end.x() + 2);
      CHECK(right <= end.x() + 9);
      CHECK(std::abs(yAtRight - end.y()) < 9);
      CHECK(near >= 9);  // the dot is centred on (now, value now)
      // and the curve reaches back: at the first sample's time its colour is there
      const Eigen::Vector2d start = comp.plotPixel(series, 0.0, ps.value[0]);
      const std::uint8_t* p0 = img.at(static_cast<int>(start.x()) + 1, static_cast<int>(start.y()));
      CHECK(std::abs(p0[2] - colour[static_cast<std::size_t>(series)][2]) < 60);
    }
  }
}

TEST_CASE("montage: one clock, tiles line up in time, a shorter run holds its last frame") {
  const SceneInfo info = rtest::info(40);
  auto run = [&](int frames) {
    MontageRun r;
    r.info = info;
    for (int k = 0; k < frames; ++k) {
      Snapshot s = rtest::straightRod(40, 20, 1.0 + 0.3 * k, 0.1);
      s.timeH = 0.5 * k;
      r.snaps.push_back(s);
    }
    return r;
  };
  std::vector<MontageRun> runs = {run(5), run(9)};
  runs[0].label = "short";
  runs[1].label = "long";
  const std::vector<double> clock = montageClock(runs);
  REQUIRE(clock.size() == 9);
  CHECK(snapshotAt(runs[0].snaps, 3.0) == 4);  // held
  CHECK(snapshotAt(runs[1].snaps, 3.0) == 6);
  const fs::path d = rtest::scratch("montage");
  MontageJob job;
  job.view.width = 640;
  job.view.height = 360;
  job.view.colourBy = ColourField::Curvature;  // a straight rod: the low end of the map, saturated
  job.pngDir = (d / "frames").string();
  job.mp4 = (d / "m.mp4").string();
  renderMontage(runs, job);
  CHECK(rtest::decodeMp4(job.mp4).frames == 9);
  const MontageLayout l = montageLayout(runs, job.view);
  REQUIRE(l.cols == 2);
  CHECK(l.framing[0].widthMm == l.framing[1].widthMm);  // one scale
  // the root's length in each tile: rows holding saturated pixels in the tile's middle columns
  auto lengthPx = [&](const Image& img, int tile) {
    const int x0 = tile * l.tileW + l.tileW / 3, x1 = tile * l.tileW + 2 * l.tileW / 3;
    int first = -1, last = -1;
    for (int y = l.headerH; y < l.headerH + l.tileH - 30; ++y)
      for (int x = x0; x < x1; ++x)
        if (saturated(img.at(x, y))) {
          if (first < 0) first = y;
          last = y;
          break;
        }
    return last - first;
  };
  int heldLength = 0;
  for (int k = 0; k < 9; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", k);
    const Image img = readPng((d / "frames" / name).string());
    const int a = lengthPx(img, 0), b = lengthPx(img, 1);
    INFO("frame " << k << ": tiles " << a << " and " << b << " px long");
    if (k <= 4) {
      CHECK(std::abs(a - b) <= 1);  // same time, same root
      heldLength = a;
    } else {
      CHECK(std::abs(a - heldLength) <= 1);  // the short run holds its last frame
      CHECK(b > a + 10);                    // the long one keeps growing
    }
  }
  CHECK_THROWS_AS(montageClock({}), RenderError);
}

TEST_CASE("shadows darken the plate beside a raised rod, on the side away from the light, and nowhere else") {
  // a straight rod 0.5 mm above the plate (a lifted loop): its shadow falls clear of it
  Snapshot rod = rtest::straightRod(40, 30, 3.0, 0.1);
  const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
  for (long i = 0; i < rod.x.cols(); ++i) rod.x.col(i) += 0.5 * units::mm * pf.normal;
  const SceneInfo info = rtest::info(40);
  View v = rtest::viewOf(640, 360);
  v.overlays = false;
  const Framing f = frameFor({rod}, info, v);
  GlRenderer gl(v.width, v.height);
  const Image plain = gl.render(buildRenderScene(rod, info, v, f));
  v.shadows = true;
  const RenderScene withShadows = buildRenderScene(rod, info, v, f);
  CHECK(withShadows.shadows);
  const Image shaded = gl.render(withShadows);
  View t = v;
  t.transparent = true;
  const Image mask = gl.render(buildRenderScene(rod, info, t, f));
  // the key light of the top view comes from (-0.35, 0.5, 1): the shadow of a point 0.6 mm up
  // (the axis) falls 0.6 * 0.35 mm to the right and 0.6 * 0.5 mm down the picture
  const double pxPerMm = v.width / f.widthMm;
  const Eigen::Vector3d mid = pf.toPlateMm(rod.x.col(15));
  const Eigen::Vector2d axis = topViewPixel(f, v, mid.x(), mid.y());
  int darker = 0, elsewhere = 0;
  double sumX = 0;
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) {
      const bool root = mask.at(x, y)[3] > 0;
      const int dl = luminance(plain.at(x, y)) - luminance(shaded.at(x, y));
      if (root) {
        CHECK(dl == 0);  // the root itself is drawn as before
        continue;
      }
      if (dl > 25) {
        ++darker;
        sumX += x;
      }
      // left of the rod (towards the light) and far from it, nothing changes
      if (x < axis.x() - 0.15 * pxPerMm || x > axis.x() + 0.5 * pxPerMm) elsewhere += dl != 0;
    }
  INFO(darker << " shadowed pixels, centred " << (sumX / std::max(darker, 1) - axis.x()) / pxPerMm << " mm right of the axis");
  CHECK(darker > 0.1 * pxPerMm * 2.5 * pxPerMm);  // a band ~0.2 mm wide along most of the rod
  CHECK((sumX / darker - axis.x()) / pxPerMm == doctest::Approx(0.6 * 0.35).epsilon(0.3));
  CHECK(elsewhere == 0);
}

TEST_CASE("shadows: a strand lifted across another darkens the lower strand's top where the light is blocked") {
  // down the plate for 3 mm, then up and back across its own start 1 mm above the plate (a crossing
  // of a coil); polyline in plate (u, v, w) [mm], ~0.05 mm elements
  const double R = 0.1;
  const std::vector<Eigen::Vector3d> corner = {{0, 0, R}, {0, -3, R}, {1.2, -3.3, 0.6}, {1.5, -1.75, 1.0}, {-1.5, -1.75, 1.0}};
  std::vector<Eigen::Vector3d> pts{corner[0]};
  for (std::size_t c = 1; c < corner.size(); ++c) {
    const int pieces = static_cast<int>(std::ceil((corner[c] - corner[c - 1]).norm() / 0.05));
    for (int k = 1; k <= pieces; ++k) pts.push_back(corner[c - 1] + (corner[c] - corner[c - 1]) * (double(k) / pieces));
  }
  const PlateFrame pf = PlateFrame::tilted(40 * units::deg);
  const int n = static_cast<int>(pts.size()) - 1;
  Snapshot rod;
  rod.x.resize(3, n + 1);
  rod.d1.resize(3, n);
  rod.d3.resize(3, n);
  rod.radius = Eigen::VectorXd::Constant(n, R * units::mm);
  for (int i = 0; i <= n; ++i)
    rod.x.col(i) = units::mm * (pts[i].x() * pf.lateral + pts[i].y() * pf.uphill() + pts[i].z() * pf.normal);
  for (int e = 0; e < n; ++e) {
    const Eigen::Vector3d d3 = (rod.x.col(e + 1) - rod.x.col(e)).normalized();
    rod.d3.col(e) = d3;
    rod.d1.col(e) = pf.normal.cross(d3).normalized();
  }
  const SceneInfo info = rtest::info(40);
  View v = rtest::viewOf(640, 640);
  v.overlays = false;
  const Framing f = frameFor({rod}, info, v);
  GlRenderer gl(v.width, v.height);
  const Image plain = gl.render(buildRenderScene(rod, info, v, f));
  v.shadows = true;
  const Image shaded = gl.render(buildRenderScene(rod, info, v, f));
  auto at = [&](const Image& img, double u, double vv) {
    const Eigen::Vector2d px = topViewPixel(f, v, u, vv);
    return luminance(img.at(static_cast<int>(px.x()), static_cast<int>(px.y())));
  };
  // the upper strand (axis 1 mm up) throws its shadow 0.8 mm x (0.35, -0.5) off itself: onto the
  // lower strand's top at v = -1.75 - 0.4
  INFO("lower strand top in the shadow: " << int(at(plain, 0, -2.15)) << " -> " << int(at(shaded, 0, -2.15)));
  CHECK(at(plain, 0, -2.15) - at(shaded, 0, -2.15) > 25);
  // elsewhere on the lower strand, and on the upper strand itself, nothing changes (no acne)
  for (double vv : {-0.5, -1.0, -2.7})
    CHECK(at(plain, 0, vv) == at(shaded, 0, vv));
  for (double u : {-1.0, -0.5, 0.5})
    CHECK(at(plain, u, -1.75) == at(shaded, u, -1.75));
}
