// a composed frame: the view (fit or follow camera), a follow inset with its region marked on the
// view, and a panel of time series drawn up to the current time; panels and marks are painted on the
// CPU with the overlay painter (stb_truetype), like the view's own overlays
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "overlay.hpp"
#include "rootsim/compose.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {

constexpr std::array<std::uint8_t, 4> kMark{0, 110, 230, 255};   // inset border and its region on the view
constexpr std::array<std::uint8_t, 4> kGrid{225, 225, 228, 255};
// one colour per series (Tableau 10: blue, red, green, purple, orange)
constexpr std::array<std::array<std::uint8_t, 4>, 5> kSeriesColour{{{31, 119, 180, 255},
                                                                    {214, 39, 40, 255},
                                                                    {44, 160, 44, 255},
                                                                    {148, 103, 189, 255},
                                                                    {255, 127, 14, 255}}};

// the inset's least magnification over the view, and the tube width [px] at which the view itself
// shows the stripes well enough to need no inset
constexpr double kInsetMagnification = 2.0;
constexpr double kInsetTubePx = 24.0;

int even(double v) { return 2 * static_cast<int>(std::lround(0.5 * v)); }


// a round axis step: 1, 2 or 5 x 10^n giving about `count` intervals over span
double niceStep(double span, int count) {
  const double raw = span / std::max(count, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}


// SI prefix for values up to maxAbs: (factor to multiply by, prefix)
std::pair<double, std::string> siScale(double maxAbs) {
  struct P { int e; const char* s; };
  static constexpr P kP[] = {{-15, "f"}, {-12, "p"}, {-9, "n"}, {-6, "\xC2\xB5"}, {-3, "m"}, {0, ""}, {3, "k"}};
  if (!(maxAbs > 0)) return {1.0, ""};
  const P* best = &kP[5];
  for (const P& p : kP)
    if (maxAbs >= std::pow(10.0, p.e)) best = &p;
  return {std::pow(10.0, -best->e), best->s};
}

// value of a series at tH, linear between samples, clamped to its ends
double valueAt(const PlotSeries& s, double tH) {
  const auto& t = s.timeH;
  if (t.empty()) return 0.0;
  if (tH <= t.front()) return s.value.front();
  if (tH >= t.back()) return s.value.back();
  const auto it = std::upper_bound(t.begin(), t.end(), tH);
  const std::size_t i = static_cast<std::size_t>(it - t.begin());
  const double w = (tH - t[i - 1]) / (t[i] - t[i - 1]);
  return s.value[i - 1] + w * (s.value[i] - s.value[i - 1]);
}

}  // namespace

FrameLayout frameLayout(int width, int height, bool plots, bool inset) {
  FrameLayout l;
  l.width = width;
  l.height = height;
  l.viewW = width;
  l.viewH = height;
  if (plots) {
    l.panel = true;
    if (width >= height) {
      l.viewW = even(0.64 * width);
      l.panelX = l.viewW, l.panelY = 0, l.panelW = width - l.viewW, l.panelH = height;
    } else {
      l.viewH = even(0.64 * height);
      l.panelX = 0, l.panelY = l.viewH, l.panelW = width, l.panelH = height - l.viewH;
    }
  }
  if (inset) {
    l.inset = true;
    const int side = even(0.42 * std::min(l.viewW, l.viewH));
    const int margin = std::max(4, even(0.02 * std::min(l.viewW, l.viewH)));
    l.insetW = l.insetH = side;
    l.insetX = l.viewX + margin;
    l.insetY = l.viewY + l.viewH - margin - side;
  }
  return l;
}

FramePlan planFrames(const std::vector<Snapshot>& snaps, const SceneInfo& info, const MovieJob& job) {
  const FrameLayout l = frameLayout(job.view.width, job.view.height, !job.plots.empty(), job.inset);
  View v = job.view;
  v.width = l.viewW;
  v.height = l.viewH;
  FramePlan p;
  FollowOptions fo;
  fo.fieldMm = job.fieldMm;
  if (job.camera == CameraMode::Follow)
    p.view = followFramings(snaps, info, l.viewW, l.viewH, fo);
  else
    p.view = {frameFor(snaps, info, v)};
  // the footprint the view's overlays keep off: the fit camera's over the whole movie, the follow
  // camera's over each quarter second of it (the overlays hold still that long)
  View fv = v;
  if (job.camera == CameraMode::Follow) {
    p.footprintFrames = std::max(1, job.video.fps / 4);
    for (std::size_t g = 0; g < snaps.size(); g += static_cast<std::size_t>(p.footprintFrames)) {
      auto fp = std::make_shared<RootFootprint>(l.viewW, l.viewH);
      for (std::size_t f = g; f < std::min(snaps.size(), g + static_cast<std::size_t>(p.footprintFrames)); ++f)
        fp->add(snaps[f], info, cameraFor(fv, p.view[std::min(f, p.view.size() - 1)]), v.whiskers);
      p.footprint.push_back(std::move(fp));
    }
  } else {
    p.footprint.push_back(rootFootprint(snaps, info, fv, p.view.front()));
    p.footprintFrames = std::max<int>(1, static_cast<int>(snaps.size()));
  }
  if (l.inset) {
    // candidate corners, clear of the overlays' bands (time and parameters on top, legend bottom left,
    // scale bar bottom right, colour bar on the right); the first the root's footprint over the movie
    // leaves free wins (lower left first); else the nearest free place, shrunk if need be
    const int side = l.insetW, m = l.insetX - l.viewX;
    const double font = overlayFontPx(v);
    const bool portrait = v.height > v.width;
    const int top = v.overlays ? static_cast<int>((portrait ? 3.4 : 1.9) * font) + m : m;
    const int lowY = v.height - m - side;
    const int barY = v.overlays && v.showScaleBar ? static_cast<int>(2.6 * font) : 0;
    const int legendY = v.overlays && (v.showLegend || v.showTitle) ? static_cast<int>(2.2 * font) : 0;
    std::vector<std::array<int, 2>> corners = {{m, lowY - legendY}, {m, top}};
    if (v.colourBy == ColourField::None || !v.overlays) {
      corners.push_back({v.width - m - side, lowY - barY});
      corners.push_back({v.width - m - side, top});
    }
    // every group's footprint: the inset holds still over the whole movie
    RootFootprint un(l.viewW, l.viewH);
    for (const auto& g : p.footprint) un.merge(*g);
    bool placed = false;
    for (const auto& c : corners) {
      if (c[1] < 0 || c[1] + side > v.height) continue;
      if (un.hits(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[0] + side), static_cast<float>(c[1] + side)) > 0) continue;
      p.insetX = l.viewX + c[0];
      p.insetY = l.viewY + c[1];
      placed = true;
      break;
    }
    if (!placed) {
      const std::array<float, 4> pref{static_cast<float>(m), static_cast<float>(lowY - legendY), static_cast<float>(m + side),
                                      static_cast<float>(lowY - legendY + side)};
      const PlacedBlock b = layoutBoxes({pref}, un, {}, v.width, v.height, static_cast<float>(m), {0.6f}).front();
      if (b.free) {
        p.insetSide = even(b.scale * static_cast<float>(side));
        p.insetX = l.viewX + static_cast<int>(std::lround(pref[0] + b.dx));
        p.insetY = l.viewY + static_cast<int>(std::lround(pref[1] + b.dy));
      } else {
        p.insetDropped = true;
      }
    }
    if (!p.insetDropped) {
      // the inset magnifies: its window at most half as wide as the view shows its side (x2 or more, more
      // on a long root); none when the view already draws the tube kInsetTubePx wide or more
      const int s = p.insetSide > 0 ? p.insetSide : side;
      const double viewPxPerMm = l.viewW / p.view.front().widthMm;
      double rMaxMm = 0.0;
      for (const Snapshot& sn : snaps) rMaxMm = std::max(rMaxMm, sn.radius.maxCoeff() / units::mm);
      if (job.camera != CameraMode::Follow && 2.0 * rMaxMm * viewPxPerMm >= kInsetTubePx) {
        p.insetDropped = true;
      } else {
        FollowOptions fi = fo;
        fi.fieldMm = std::min(fo.fieldMm, s / (kInsetMagnification * viewPxPerMm));
        p.inset = followFramings(snaps, info, s, s, fi);
      }
    }
  }
  return p;
}

struct FrameComposer::Impl {
  SceneInfo info;
  MovieJob job;
  FramePlan plan;
  FrameLayout layout;
  View mainView, insetView;
  GlRenderer mainGl;
  std::unique_ptr<GlRenderer> insetGl;
  Image viewImg, insetImg;
  detail::OverlayPainter painter;
  std::vector<Eigen::Vector2d> mark;

  // plot cells: the plotting rectangle and the data ranges of each series
  struct Cell {
    float x0, y0, x1, y1;   // plot area [px]: left, top, right, bottom
    double t0, t1, lo, hi;  // data ranges (values already scaled)
    double scale;           // SI factor
    std::string title;
  };
  std::vector<Cell> cells;
  float font = 14;

  Impl(const SceneInfo& i, const MovieJob& j, FramePlan p)
      : info(i),
        job(j),
        plan(std::move(p)),
        layout(placedLayout(j, plan)),
        mainView(viewOf(j, layout.viewW, layout.viewH)),
        insetView(viewOf(j, layout.insetW, layout.insetH)),
        mainGl(layout.viewW, layout.viewH, j.renderer) {
    if (plan.view.empty()) throw RenderError("movie: a frame plan without a view framing");
    if (layout.inset) {
      if (plan.inset.empty()) throw RenderError("movie: an inset without its framings");
      // the view's overlays keep off the inset
      mainView.keepClearPx.push_back({static_cast<float>(layout.insetX - layout.viewX - 2), static_cast<float>(layout.insetY - layout.viewY - 2),
                                      static_cast<float>(layout.insetX - layout.viewX + layout.insetW + 2),
                                      static_cast<float>(layout.insetY - layout.viewY + layout.insetH + 2)});
      insetView.overlays = false;
      insetGl = std::make_unique<GlRenderer>(layout.insetW, layout.insetH, j.renderer);
    }
    font = std::max(11.0f, std::round(static_cast<float>(std::min(layout.width, layout.height)) / 40.0f));
    if (layout.panel) planCells();
  }

  static FrameLayout placedLayout(const MovieJob& j, const FramePlan& p) {
    FrameLayout l = frameLayout(j.view.width, j.view.height, !j.plots.empty(), j.inset && !p.insetDropped);
    if (l.inset && p.insetX >= 0 && p.insetY >= 0) l.insetX = p.insetX, l.insetY = p.insetY;
    if (l.inset && p.insetSide > 0) l.insetW = l.insetH = p.insetSide;
    return l;
  }

  static View viewOf(const MovieJob& j, int w, int h) {
    View v = j.view;
    v.width = std::max(w, 1);
    v.height = std::max(h, 1);
    return v;
  }

  void planCells() {
    const int k = static_cast<int>(job.plots.size());
    const float ch = static_cast<float>(layout.panelH) / static_cast<float>(k);
    for (int i = 0; i < k; ++i) {
      const PlotSeries& s = job.plots[static_cast<std::size_t>(i)];
      if (s.timeH.size() < 1 || s.timeH.size() != s.value.size())
        throw RenderError("plot " + s.name + ": needs matching time and value samples");
      Cell c{};
      const float y0 = static_cast<float>(layout.panelY) + ch * static_cast<float>(i);
      c.x0 = static_cast<float>(layout.panelX) + 5.4f * font;
      c.x1 = static_cast<float>(layout.panelX + layout.panelW) - 1.4f * font;
      c.y0 = y0 + 1.9f * font;
      c.y1 = y0 + ch - 2.0f * font;
      double maxAbs = 0.0, lo = 1e300, hi = -1e300;
      for (double v : s.value) maxAbs = std::max(maxAbs, std::abs(v)), lo = std::min(lo, v), hi = std::max(hi, v);
      std::string unit = s.unit;
      c.scale = 1.0;
      if (s.siPrefix) {
        const auto [f, prefix] = siScale(maxAbs);
        c.scale = f;
        unit = prefix + unit;
      }
      lo *= c.scale, hi *= c.scale;
      const double pad = hi > lo ? 0.06 * (hi - lo) : std::max(1e-12, 0.1 * std::abs(hi)) + 1e-12;
      c.lo = lo - pad;
      c.hi = hi + pad;
      c.t0 = s.timeH.front();
      c.t1 = s.timeH.back() > c.t0 ? s.timeH.back() : c.t0 + 1.0;
      c.title = s.name + (unit.empty() ? "" : " [" + unit + "]");
      cells.push_back(c);
    }
  }

  Eigen::Vector2d toPixel(const Cell& c, double t, double scaledValue) const {
    return {c.x0 + (t - c.t0) / (c.t1 - c.t0) * (c.x1 - c.x0), c.y1 - (scaledValue - c.lo) / (c.hi - c.lo) * (c.y1 - c.y0)};
  }

  void drawPanel(double nowH, std::vector<OverlayRect>& rects, std::vector<OverlayLine>& lines,
                 std::vector<OverlayText>& texts) {
    rects.push_back({static_cast<float>(layout.panelX), static_cast<float>(layout.panelY), static_cast<float>(layout.panelW),
                     static_cast<float>(layout.panelH), {255, 255, 255, 255}});
    const float small = std::round(0.85f * font);
    const float lw = std::max(2.0f, std::round(font / 7.0f));
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const Cell& c = cells[i];
      const PlotSeries& s = job.plots[i];
      const auto& col = kSeriesColour[i % kSeriesColour.size()];
      // y ticks with light grid lines, x ticks in hours
      // about as many round y ticks as fit the cell's height
      const int yCount = std::clamp(static_cast<int>((c.y1 - c.y0) / (2.2f * small)), 1, 4);
      const double ys = niceStep(c.hi - c.lo, yCount);
      for (double v = std::ceil(c.lo / ys) * ys; v <= c.hi + 1e-9 * ys; v += ys) {
        const double vv = std::abs(v) < 1e-9 * ys ? 0.0 : v;
        const float y = std::round(static_cast<float>(toPixel(c, c.t0, vv).y()));
        rects.push_back({c.x0, y, c.x1 - c.x0, 1, kGrid});
        rects.push_back({c.x0 - 5, y, 5, 1, detail::kInk});
        texts.push_back({tickText(vv), c.x0 - 8, y - 0.55f * small, small, OverlayText::Anchor::TopRight});
      }
      // time ticks in hours; the unit on the last one
      const double step = niceStep(c.t1 - c.t0, 4);
      const double tLast = std::floor(c.t1 / step + 1e-9) * step;
      for (double t = std::ceil(c.t0 / step - 1e-9) * step; t <= c.t1 + 1e-9 * step; t += step) {
        const float x = std::round(static_cast<float>(toPixel(c, t, c.lo).x()));
        rects.push_back({x, c.y1, 1, 5, detail::kInk});
        const bool last = std::abs(t - tLast) < 1e-6 * step;
        texts.push_back({tickText(t) + (last ? " h" : ""), x, c.y1 + 6 + small * 1.05f, small, OverlayText::Anchor::BottomCentre});
      }
      // axes
      rects.push_back({c.x0, c.y0, 1, c.y1 - c.y0 + 1, detail::kInk});
      rects.push_back({c.x0, c.y1, c.x1 - c.x0, 1, detail::kInk});
      // the curve up to now, ending exactly at the value now; a dot marks now
      OverlayLine curve;
      curve.widthPx = lw;
      curve.colour = col;
      const double now = std::clamp(nowH, c.t0, c.t1);
      for (std::size_t k = 0; k < s.timeH.size() && s.timeH[k] < now; ++k) {
        const Eigen::Vector2d p = toPixel(c, s.timeH[k], c.scale * s.value[k]);
        curve.points.push_back({static_cast<float>(p.x()), static_cast<float>(p.y())});
      }
      const double vNow = valueAt(s, now);
      const Eigen::Vector2d pn = toPixel(c, now, c.scale * vNow);
      curve.points.push_back({static_cast<float>(pn.x()), static_cast<float>(pn.y())});
      lines.push_back(curve);
      lines.push_back({{{static_cast<float>(pn.x()), static_cast<float>(pn.y())}}, 3.2f * lw, col});
      texts.push_back({c.title, c.x0, c.y0 - 1.6f * font, font, OverlayText::Anchor::TopLeft});
      texts.push_back({tickText(c.scale * vNow), c.x1, c.y0 - 1.6f * font, font, OverlayText::Anchor::TopRight, col});
    }
  }

  // the inset's own scale bar and its magnification over the view ("x6"), in its bottom right corner
  // on a light backing so they read over the grid and the root
  void insetOverlays(const Framing& fv, const Framing& fi, const RootFootprint& fpi, std::vector<OverlayRect>& rects,
                     std::vector<OverlayText>& texts) {
    const float f = std::round(0.8f * overlayFontPx(mainView));
    const float m = 0.5f * f;
    const float x0 = static_cast<float>(layout.insetX), y0 = static_cast<float>(layout.insetY);
    const float w = static_cast<float>(layout.insetW), h = static_cast<float>(layout.insetH);
    const double pxPerMm = w / fi.widthMm;
    const double lenMm = niceLength(0.3 * w / pxPerMm);
    const float len = std::round(static_cast<float>(lenMm * pxPerMm));
    const float barH = std::max(3.0f, std::round(0.22f * f));
    const std::string label = (lenMm >= 1 ? fixedText(lenMm, 0) : lenMm >= 0.1 ? fixedText(lenMm, 1) : fixedText(lenMm, 2)) + " mm";
    const float labelW = painter.textWidth(job.view.fontPath, label, f);
    // magnification: the inset's pixels per mm over the view's, left of the bar in the same box
    const double mag = pxPerMm / (static_cast<double>(layout.viewW) / fv.widthMm);
    const std::string magText = "\xC3\x97" + (mag >= 3 ? fixedText(mag, 0) : fixedText(mag, 1));
    const float magW = painter.textWidth(job.view.fontPath, magText, f);
    const float boxW = magW + f + std::max(len, labelW) + 2 * m, boxH = barH + 1.35f * f + 2 * m;
    float bx = x0 + w - 3 - boxW, by = y0 + h - 3 - boxH;
    // bottom right of the inset unless the root is there: the layout step within the inset
    {
      const std::array<float, 4> pref{bx - x0, by - y0, bx - x0 + boxW, by - y0 + boxH};
      const PlacedBlock b = layoutBoxes({pref}, fpi, {}, layout.insetW, layout.insetH, 3.0f, {1.0f}).front();
      bx += std::round(b.dx), by += std::round(b.dy);
    }
    rects.push_back({bx, by, boxW, boxH, {255, 255, 255, 200}});
    const float barX = std::round(bx + boxW - m - 0.5f * (std::max(len, labelW) + len)), barY = std::round(by + boxH - m - barH);
    rects.push_back({barX, barY, len, barH, detail::kInk});
    texts.push_back({label, barX + 0.5f * len, barY - 0.3f * f, f, OverlayText::Anchor::BottomCentre});
    texts.push_back({magText, bx + m, by + 0.5f * (boxH - f), f, OverlayText::Anchor::TopLeft});
    lastMagnification = mag;
  }
  double lastMagnification = 0.0;

  void compose(const Snapshot& snap, int frame, Image& out) {
    const auto pick = [&](const std::vector<Framing>& v) -> const Framing& {
      return v[static_cast<std::size_t>(std::clamp(frame, 0, static_cast<int>(v.size()) - 1))];
    };
    if (!plan.footprint.empty()) {
      const int g = std::clamp(frame / std::max(1, plan.footprintFrames), 0, static_cast<int>(plan.footprint.size()) - 1);
      mainView.footprint = plan.footprint[static_cast<std::size_t>(g)];
    }
    const RenderScene scene = buildRenderScene(snap, info, mainView, pick(plan.view));
    if (!layout.panel && !layout.inset) {
      mainGl.render(scene, out);
      return;
    }
    mainGl.render(scene, viewImg);
    if (out.width != layout.width || out.height != layout.height || out.rgba.size() != static_cast<std::size_t>(4) * layout.width * layout.height)
      out = Image(layout.width, layout.height);
    std::fill(out.rgba.begin(), out.rgba.end(), std::uint8_t{255});
    blit(viewImg, out, layout.viewX, layout.viewY);
    std::vector<OverlayRect> rects;
    std::vector<OverlayLine> lines;
    std::vector<OverlayText> texts;
    if (layout.inset) {
      const Framing& fi = pick(plan.inset);
      insetGl->render(buildRenderScene(snap, info, insetView, fi), insetImg);
      blit(insetImg, out, layout.insetX, layout.insetY);
      // the inset's border, and its region on the view, in one colour
      const float x = static_cast<float>(layout.insetX), y = static_cast<float>(layout.insetY);
      const float w = static_cast<float>(layout.insetW), h = static_cast<float>(layout.insetH);
      lines.push_back({{{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}, {x, y}}, 3.0f, kMark});
      mark.clear();
      OverlayLine region;
      region.widthPx = 2.0f;
      region.colour = kMark;
      const double hu = 0.5 * fi.widthMm, hv = 0.5 * fi.heightMm;
      for (const auto& [du, dv] : {std::pair{-hu, hv}, {hu, hv}, {hu, -hv}, {-hu, -hv}, {-hu, hv}}) {
        Eigen::Vector2d px;
        if (!projectToPixel(scene, Eigen::Vector3d(fi.centreU + du, fi.centreV + dv, 0.0), px)) continue;
        px += Eigen::Vector2d(layout.viewX, layout.viewY);
        region.points.push_back({static_cast<float>(px.x()), static_cast<float>(px.y())});
        if (mark.size() < 4) mark.push_back(px);
      }
      lines.push_back(region);
      if (job.view.overlays) {
        // the inset's scale and magnification, off the root the inset shows
        RootFootprint fpi(layout.insetW, layout.insetH);
        fpi.add(snap, info, cameraFor(insetView, fi), insetView.whiskers);
        std::vector<OverlayRect> ir;
        std::vector<OverlayText> it;
        insetOverlays(pick(plan.view), fi, fpi, ir, it);
        painter.draw(ir, {}, it, job.view.fontPath, out, &fpi, layout.insetX, layout.insetY);
      }
    }
    if (layout.panel) drawPanel(snap.timeH, rects, lines, texts);
    // the mark and the panel: nothing over the view's root
    painter.draw(rects, lines, texts, job.view.fontPath, out, scene.keepOut.get(), layout.viewX, layout.viewY);
  }
};

FrameComposer::FrameComposer(const SceneInfo& info, const MovieJob& job, FramePlan plan)
    : impl_(std::make_unique<Impl>(info, job, std::move(plan))) {}
FrameComposer::~FrameComposer() = default;
void FrameComposer::compose(const Snapshot& snap, int frame, Image& out) { impl_->compose(snap, frame, out); }
const FrameLayout& FrameComposer::layout() const { return impl_->layout; }
std::vector<Eigen::Vector2d> FrameComposer::lastInsetMark() const { return impl_->mark; }
double FrameComposer::lastInsetMagnification() const { return impl_->lastMagnification; }

Eigen::Vector2d FrameComposer::plotPixel(int series, double timeH, double value) const {
  const auto& c = impl_->cells.at(static_cast<std::size_t>(series));
  return impl_->toPixel(c, timeH, c.scale * value);
}

}  // namespace rootsim
