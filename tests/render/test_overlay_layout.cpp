// the layout step: no overlay changes a pixel of the root, in every view (fit, follow, 3-D, a coil, a
// plate of several roots, the composed frames with an inset and a plot panel); overlays are moved to
// free space where there is some
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "render_test_util.hpp"
#include "rootsim/compose.hpp"
#include "rootsim/gl_renderer.hpp"
#include "rootsim/overlay_layout.hpp"
#include "rootsim/render_scene.hpp"
#include "../tolerance_support.hpp"

using rootsim::test::kRoundoff;

using namespace rootsim;

namespace {

// a root along a centreline given in plate (u, v, w) [mm] at n + 1 nodes, radius rMm, d1 lateral-ish
Snapshot rootAlong(double alphaDeg, int n, double rMm, const std::function<Eigen::Vector3d(double)>& uvw) {
  const double a = alphaDeg * rtest::kDeg;
  const Eigen::Vector3d normal(0, -std::cos(a), std::sin(a)), downhill(0, -std::sin(a), -std::cos(a)), lateral(1, 0, 0);
  Snapshot s;
  s.timeH = 12.0;
  s.x.resize(3, n + 1);
  s.d1.resize(3, n);
  s.d3.resize(3, n);
  s.radius = Eigen::VectorXd::Constant(n, rMm * 1e-3);
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector3d p = uvw(static_cast<double>(i) / n);
    s.x.col(i) = 1e-3 * (p.x() * lateral - p.y() * downhill + p.z() * normal);
  }
  for (int e = 0; e < n; ++e) {
    const Eigen::Vector3d t = (s.x.col(e + 1) - s.x.col(e)).normalized();
    s.d3.col(e) = t;
    Eigen::Vector3d d1 = normal.cross(t);
    if (d1.norm() < 1e-9) d1 = lateral;
    s.d1.col(e) = d1.normalized();
  }
  return s;
}

// a waving root 12 mm long, going down the plate
Snapshot waving() {
  return rootAlong(60, 120, 0.1, [](double f) { return Eigen::Vector3d(0.8 * std::sin(6.0 * f * 3.14159), -12.0 * f, 0.1); });
}
// a coil: three loops of radius 0.6 mm drifting to the right, the upper strand lifted
Snapshot coil() {
  return rootAlong(80, 240, 0.1, [](double f) {
    const double th = 3 * 2 * 3.14159 * f;
    return Eigen::Vector3d(2.0 * f + 0.6 * std::sin(th), -0.6 + 0.6 * std::cos(th) - 1.0 * f, 0.1 + 0.15 * (1 + std::sin(th)));
  });
}

// pixels of the root: alpha of the same view drawn on a transparent background without overlays
std::vector<bool> rootMask(const Snapshot& s, const SceneInfo& si, View v, const Framing& f) {
  v.transparent = true;
  v.overlays = false;
  v.plateRectMm.reset();
  GlRenderer gl(v.width, v.height);
  const Image img = gl.render(buildRenderScene(s, si, v, f));
  std::vector<bool> m(static_cast<std::size_t>(v.width) * v.height);
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) m[static_cast<std::size_t>(y) * v.width + x] = img.rgba[4 * (static_cast<std::size_t>(y) * v.width + x) + 3] > 0;
  return m;
}

struct Count {
  long rootPx = 0;     // pixels of the root
  long changed = 0;    // of those, changed by the overlays
  long overlayPx = 0;  // pixels the overlays changed off the root (they are drawn)
};

// root pixels changed between img (with overlays) and ref (without), the view at (ox, oy) in img
Count compare(const Image& img, const Image& ref, const std::vector<bool>& mask, int w, int h, int ox = 0, int oy = 0) {
  Count c;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::uint8_t* a = img.at(x + ox, y + oy);
      const std::uint8_t* b = ref.at(x, y);
      const bool diff = a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
      if (mask[static_cast<std::size_t>(y) * w + x]) {
        ++c.rootPx;
        c.changed += diff;
      } else {
        c.overlayPx += diff;
      }
    }
  return c;
}

Count overlayCount(const Snapshot& s, const SceneInfo& si, View v, const Framing& f) {
  GlRenderer gl(v.width, v.height);
  const Image with = gl.render(buildRenderScene(s, si, v, f));
  View off = v;
  off.overlays = false;
  const Image without = gl.render(buildRenderScene(s, si, off, f));
  return compare(with, without, rootMask(s, si, v, f), v.width, v.height);
}

// each text's box (as the painter anchors it) and the footprint it lies on
int textsOnRoot(const RenderScene& rs, const std::string& font) {
  int n = 0;
  for (const OverlayText& t : rs.texts) {
    OverlayBlock b;
    b.texts.push_back(t);
    const auto box = blockBox(b, font);
    if (rs.keepOut->hits(box[0] + 1, box[1] + 1, box[2] - 1, box[3] - 1) > 0) ++n;
  }
  return n;
}

}  // namespace

TEST_CASE("overlay layout: no overlay changes a root pixel in the fit view, the follow view, 3-D, a coil and a plate") {
  const SceneInfo si = rtest::info(60);
  struct Case {
    const char* name;
    Snapshot snap;
    View view;
    std::optional<Framing> framing;
  };
  std::vector<Case> cases;
  {
    View v = rtest::viewOf(480, 270);
    v.colourBy = ColourField::Twist;
    v.colourRange = {-1.0, 1.0};
    cases.push_back({"fit, twist colours", waving(), v, std::nullopt});
  }
  {
    // follow: a 2 mm window on the root's middle, the tube crossing the whole picture and its corners
    View v = rtest::viewOf(480, 270);
    Framing f;
    f.centreU = 0.0, f.centreV = -6.0, f.widthMm = 2.0, f.heightMm = 2.0 * 270 / 480, f.topW = 0.2;
    cases.push_back({"follow", rootAlong(60, 100, 0.1, [](double t) { return Eigen::Vector3d(-1.5 + 3.0 * t, -5.0 - 2.0 * t, 0.1); }), v, f});
  }
  {
    View v = rtest::viewOf(480, 270);
    v.kind = View::Kind::Perspective;
    v.colourBy = ColourField::Twist;
    v.colourRange = {-1.0, 1.0};
    cases.push_back({"3-D coil, twist colours", coil(), v, std::nullopt});
  }
  {
    View v = rtest::viewOf(320, 320);
    v.whiskers = true;
    cases.push_back({"coil, top, whiskers", coil(), v, std::nullopt});
  }
  {
    // a plate of three roots drawn whole, outlined: the outline and the overlays stay off the roots
    std::vector<Snapshot> roots;
    for (int k = 0; k < 3; ++k)
      roots.push_back(rootAlong(60, 40, 0.1, [k](double t) { return Eigen::Vector3d(-6.0 + 6.0 * k + 0.5 * std::sin(9 * t), -9.0 * t, 0.1); }));
    View v = rtest::viewOf(400, 300);
    v.plateRectMm = std::array<double, 4>{-8.0, -9.0, 8.0, 0.5};  // the tips reach the outline
    cases.push_back({"plate of three roots", mergeRoots(roots), v, std::nullopt});
  }
  for (Case& c : cases) {
    CAPTURE(c.name);
    const Framing f = c.framing ? *c.framing : frameFor({c.snap}, si, c.view);
    const Count n = overlayCount(c.snap, si, c.view, f);
    CHECK(n.rootPx > 500);
    CHECK(n.changed == 0);
    CHECK(n.overlayPx > 200);  // the overlays are there
  }
}

TEST_CASE("overlay layout: overlays move off the root where there is free space, at their own size") {
  const SceneInfo si = rtest::info(60);
  // the root crosses the top left corner, where the time would go, and the top right (the parameters)
  // (the picture's top edge is at v = -3.875 mm; the tube, 0.2 mm wide, runs along it)
  const Snapshot s = rootAlong(60, 100, 0.1, [](double t) { return Eigen::Vector3d(-2.6 + 5.2 * t, -3.93, 0.1); });
  View v = rtest::viewOf(640, 360);
  Framing f;
  f.centreU = 0.0, f.centreV = -5.0, f.widthMm = 4.0, f.heightMm = 4.0 * 360 / 640, f.topW = 0.2;
  const RenderScene rs = buildRenderScene(s, si, v, f);
  REQUIRE(rs.keepOut);
  const float font = overlayFontPx(v);
  bool timeMoved = false;
  for (const OverlayText& t : rs.texts) {
    if (t.text.rfind("t = ", 0) == 0) {
      timeMoved = t.x != 0.7f * font || t.y != 0.7f * font;
      ROOTSIM_CHECK_CLOSE(t.sizePx, font, kRoundoff);  // moved, not shrunk
    }
  }
  CHECK(timeMoved);
  CHECK(textsOnRoot(rs, v.fontPath) == 0);
  // and in a fit view nothing moves: the framing keeps the margins free
  View fit = rtest::viewOf(640, 360);
  const Snapshot w = waving();
  const RenderScene plain = buildRenderScene(w, si, fit, frameFor({w}, si, fit));
  for (const OverlayText& t : plain.texts)
    if (t.text.rfind("t = ", 0) == 0) CHECK((t.x == 0.7f * font && t.y == 0.7f * font));
  CHECK(textsOnRoot(plain, fit.fontPath) == 0);
}

TEST_CASE("overlay layout: the footprint covers every pixel the tube draws, in top and 3-D views") {
  const SceneInfo si = rtest::info(80);
  for (const bool persp : {false, true}) {
    CAPTURE(persp);
    View v = rtest::viewOf(400, 300);
    if (persp) v.kind = View::Kind::Perspective;
    const Snapshot s = coil();
    const Framing f = frameFor({s}, si, v);
    const std::vector<bool> mask = rootMask(s, si, v, f);
    const auto fp = rootFootprint({s}, si, v, f);
    long missed = 0, root = 0, covered = 0;
    for (int y = 0; y < v.height; ++y)
      for (int x = 0; x < v.width; ++x) {
        root += mask[static_cast<std::size_t>(y) * v.width + x];
        covered += fp->covers(x, y);
        missed += mask[static_cast<std::size_t>(y) * v.width + x] && !fp->covers(x, y);
      }
    CHECK(root > 500);
    CHECK(missed == 0);
    // a halo, not a blanket: the footprint is less than three times the root's pixels
    CHECK(covered < 3 * root);
  }
}

TEST_CASE("overlay layout: composed frames (follow with colours and a plot panel, fit with an inset) leave the root as drawn") {
  const SceneInfo si = rtest::info(60);
  std::vector<Snapshot> snaps;
  for (int k = 1; k <= 4; ++k) {
    const double len = 3.0 * k;
    Snapshot s = rootAlong(60, 30 * k, 0.1, [len](double t) { return Eigen::Vector3d(0.8 * std::sin(2.0 * t * len), -len * t, 0.1); });
    s.timeH = 3.0 * k;
    snaps.push_back(s);
  }
  PlotSeries ser;
  ser.name = "θ_tip";
  ser.unit = "°";
  ser.timeH = {3, 6, 9, 12};
  ser.value = {0, 10, 5, 20};
  for (const int look : {0, 1}) {
    CAPTURE(look);
    MovieJob job;
    job.view.width = 640, job.view.height = 360;
    if (look == 0) {
      job.camera = CameraMode::Follow;
      job.fieldMm = 2.0;
      job.view.colourBy = ColourField::Twist;
      job.view.colourRange = {-1.0, 1.0};
      job.plots = {ser};
    } else {
      job.view.width = 360, job.view.height = 640;
      job.inset = true;
      job.fieldMm = 1.5;
    }
    const FramePlan plan = planFrames(snaps, si, job);
    FrameComposer comp(si, job, plan);
    const FrameLayout& l = comp.layout();
    View v = job.view;
    v.width = l.viewW, v.height = l.viewH;
    GlRenderer gl(v.width, v.height);
    for (int frame = 0; frame < 4; ++frame) {
      CAPTURE(frame);
      Image img;
      comp.compose(snaps[static_cast<std::size_t>(frame)], frame, img);
      const Framing& f = plan.view[std::min<std::size_t>(static_cast<std::size_t>(frame), plan.view.size() - 1)];
      View off = v;
      off.overlays = false;
      const Image ref = gl.render(buildRenderScene(snaps[static_cast<std::size_t>(frame)], si, off, f));
      const Count n = compare(img, ref, rootMask(snaps[static_cast<std::size_t>(frame)], si, v, f), v.width, v.height, l.viewX, l.viewY);
      CHECK(n.rootPx > 200);
      CHECK(n.changed == 0);
      CHECK(n.overlayPx > 200);
    }
    if (look == 1) CHECK(l.inset);  // the portrait fit view has room for the inset
  }
}
