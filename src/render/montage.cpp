// several runs side by side (`rootsim montage`): one scale (the same plate width in every tile, each
// tile framed around its run's base node so the bases line up), one clock (the union of the runs'
// snapshot times; a run that ended holds its last frame)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include <Eigen/Core>

#include "frame_sink.hpp"
#include "overlay.hpp"
#include "rootsim/montage.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {


void checkRuns(const std::vector<MontageRun>& runs) {
  if (runs.empty()) throw RenderError("montage: no runs");
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (runs[i].snaps.empty()) throw RenderError("montage: run " + std::to_string(i + 1) + " has no snapshots");
}

}  // namespace

std::vector<double> montageClock(const std::vector<MontageRun>& runs) {
  checkRuns(runs);
  std::vector<double> t;
  for (const MontageRun& r : runs)
    for (const Snapshot& s : r.snaps) t.push_back(s.timeH);
  std::sort(t.begin(), t.end());
  std::vector<double> out;
  for (double x : t)
    if (out.empty() || x - out.back() > 1e-9) out.push_back(x);
  return out;
}

int snapshotAt(const std::vector<Snapshot>& snaps, double tH) {
  int k = 0;
  for (int i = 0; i < static_cast<int>(snaps.size()); ++i)
    if (snaps[static_cast<std::size_t>(i)].timeH <= tH + 1e-9) k = i;
  return k;
}

MontageLayout montageLayout(const std::vector<MontageRun>& runs, const View& view) {
  checkRuns(runs);
  if (view.width <= 0 || view.height <= 0) throw RenderError("montage: size must be positive");
  // every run's extent relative to its base node, over all its snapshots [mm]
  const double inf = std::numeric_limits<double>::infinity();
  double u0 = inf, u1 = -inf, v0 = inf, v1 = -inf, rMax = 0.0;
  for (const MontageRun& r : runs) {
    const PlateFrame pf = PlateFrame::tilted(r.info.alphaDeg * units::deg);
    const Eigen::Vector3d base = pf.toPlateMm(r.snaps.front().x.col(0));
    for (const Snapshot& s : r.snaps) {
      for (long i = 0; i < s.x.cols(); ++i) {
        const Eigen::Vector3d p = pf.toPlateMm(s.x.col(i)) - base;
        u0 = std::min(u0, p.x()), u1 = std::max(u1, p.x());
        v0 = std::min(v0, p.y()), v1 = std::max(v1, p.y());
      }
      rMax = std::max(rMax, s.radius.maxCoeff() / units::mm);
    }
  }
  const double pad = rMax + view.marginMm;
  const double wMm = u1 - u0 + 2 * pad, hMm = v1 - v0 + 2 * pad;
  MontageLayout l;
  // labels legible at 720p (21 px there) and growing with the picture
  const float font = std::max(14.0f, std::round(static_cast<float>(std::min(view.width, view.height)) / 34.0f));
  l.labelPx = font;
  l.headerH = static_cast<int>(std::lround(1.8f * font));
  const int n = static_cast<int>(runs.size());
  // the grid with the largest common scale [px/mm]; a tile keeps room for its label
  double best = -1.0;
  for (int c = 1; c <= n; ++c) {
    const int r = (n + c - 1) / c;
    const int tw = view.width / c, th = (view.height - l.headerH) / r;
    const double scale = std::min(tw / wMm, (th - 2.1 * font) / hMm);
    if (scale > best) best = scale, l.cols = c, l.rows = r, l.tileW = tw, l.tileH = th;
  }
  if (l.tileW < 16 || l.tileH < 16) throw RenderError("montage: " + std::to_string(n) + " tiles do not fit " +
                                                      std::to_string(view.width) + "x" + std::to_string(view.height));
  // one width in mm for every tile; the content centred (leaving the label band at the bottom free)
  const double width = std::max(wMm, hMm * l.tileW / std::max(1.0, l.tileH - 2.1 * font));
  const double height = width * l.tileH / l.tileW;
  const double labelMm = 2.1 * font / l.tileH * height;
  for (const MontageRun& r : runs) {
    const PlateFrame pf = PlateFrame::tilted(r.info.alphaDeg * units::deg);
    const Eigen::Vector3d base = pf.toPlateMm(r.snaps.front().x.col(0));
    Framing f;
    f.widthMm = width;
    f.heightMm = height;
    f.centreU = base.x() + 0.5 * (u0 + u1);
    f.centreV = base.y() + 0.5 * (v0 + v1) - 0.5 * labelMm;
    double wTop = 0.0;
    for (const Snapshot& s : r.snaps)
      for (long i = 0; i < s.x.cols(); ++i) wTop = std::max(wTop, pf.toPlateMm(s.x.col(i)).z());
    f.topW = wTop + rMax;
    l.framing.push_back(f);
  }
  return l;
}

std::array<float, 2> montageLabelAnchor(const MontageRun& run, const View& tileView, const Framing& framing,
                                        float labelWidthPx, float labelPx) {
  View v = tileView;
  v.overlays = false;
  const RenderScene scene = buildRenderScene(run.snaps.back(), run.info, v, framing);
  const PlateFrame pf = PlateFrame::tilted(run.info.alphaDeg * units::deg);
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, yMax = -x0;
  for (const Snapshot& s : run.snaps)
    for (long i = 0; i < s.x.cols(); ++i) {
      Eigen::Vector2d px;
      if (!projectToPixel(scene, pf.toPlateMm(s.x.col(i)), px)) continue;
      x0 = std::min(x0, px.x()), x1 = std::max(x1, px.x()), yMax = std::max(yMax, px.y());
    }
  const float w = static_cast<float>(v.width), h = static_cast<float>(v.height);
  if (!(x1 >= x0)) return {0.5f * w, h - 0.3f * labelPx};
  const float rPx = static_cast<float>(run.snaps.back().radius.maxCoeff() / units::mm * v.width / framing.widthMm);
  const float half = 0.5f * labelWidthPx + 0.3f * labelPx;
  const float x = std::clamp(static_cast<float>(0.5 * (x0 + x1)), std::min(half, 0.5f * w), std::max(w - half, 0.5f * w));
  const float y = std::clamp(static_cast<float>(yMax) + rPx + 1.4f * labelPx, 1.2f * labelPx, h - 0.3f * labelPx);
  return {x, y};
}

View montageTileView(const MontageLayout& l, const View& view, std::size_t i, std::size_t n) {
  View v = view;
  v.width = l.tileW;
  v.height = l.tileH;
  v.showTime = false;
  v.showParams = false;
  v.showTitle = false;
  // the last tile's scale bar, downhill arrow and colour bar in the labels' size (the tile's own would be
  // its shorter side / 26: 13-16 px at 720p beside 21 px labels)
  v.fontPx = l.labelPx;
  // one scale bar, downhill arrow and colour bar: all are common (the legend is in the header)
  v.showScaleBar = v.showScaleBar && i + 1 == n;
  v.showColourBar = v.showColourBar && i + 1 == n;
  v.showDownhill = v.showDownhill && i + 1 == n;
  v.showLegend = false;
  return v;
}

void renderMontage(const std::vector<MontageRun>& runs, const MontageJob& job, const MovieProgress& progress) {
  const MontageLayout l = montageLayout(runs, job.view);
  const std::vector<double> clock = montageClock(runs);
  if (job.view.transparent && !job.mp4.empty())
    throw RenderError("montage " + job.mp4 + ": a transparent background is for PNG only (MP4 has no alpha)");
  // one colour range over every run
  View tileView = montageTileView(l, job.view, 0, runs.size());
  if (tileView.colourBy != ColourField::None) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const MontageRun& r : runs) {
      const auto range = fieldRange(r.snaps, r.info, tileView.colourBy);
      lo = std::min(lo, range[0]), hi = std::max(hi, range[1]);
    }
    tileView.colourRange = {lo, hi};
  }
  GlRenderer gl(l.tileW, l.tileH, job.renderer);
  detail::OverlayPainter painter;
  const float font = l.labelPx;
  // labels under their roots, fixed for the whole movie
  std::vector<std::array<float, 2>> anchors;
  for (std::size_t i = 0; i < runs.size(); ++i)
    anchors.push_back(montageLabelAnchor(runs[i], tileView, l.framing[i],
                                         painter.textWidth(job.view.fontPath, runs[i].label, font), font));
  // the header: time on the left, then the caption; the stripe legend at the right end
  const float m = 0.5f * font;
  const float timeW = painter.textWidth(job.view.fontPath, "t = " + fixedText(clock.back(), 1) + " h", font);
  const bool overlays = job.view.overlays;
  detail::FrameSink sink(job.mp4, job.pngDir, "", job.view.width, job.view.height, job.video);
  Image frame(job.view.width, job.view.height), tile;
  const int total = static_cast<int>(clock.size());
  for (int k = 0; k < total; ++k) {
    const double t = clock[static_cast<std::size_t>(k)];
    if (frame.width != job.view.width || frame.rgba.size() != static_cast<std::size_t>(4) * job.view.width * job.view.height)
      frame = Image(job.view.width, job.view.height);
    std::fill(frame.rgba.begin(), frame.rgba.end(), std::uint8_t{255});
    std::vector<OverlayText> texts;
    std::vector<OverlayRect> rects;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const MontageRun& r = runs[i];
      const int col = static_cast<int>(i) % l.cols, row = static_cast<int>(i) / l.cols;
      View v = montageTileView(l, job.view, i, runs.size());
      v.colourRange = tileView.colourRange;
      const Snapshot& s = r.snaps[static_cast<std::size_t>(snapshotAt(r.snaps, t))];
      gl.render(buildRenderScene(s, r.info, v, l.framing[i]), tile);
      const int x = col * l.tileW, y = l.headerH + row * l.tileH;
      blit(tile, frame, x, y);
      // thin separators and the run's label at the bottom of its tile
      rects.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(l.tileW), 1, {200, 200, 200, 255}});
      rects.push_back({static_cast<float>(x), static_cast<float>(y), 1, static_cast<float>(l.tileH), {200, 200, 200, 255}});
      texts.push_back({r.label, static_cast<float>(x) + anchors[i][0], static_cast<float>(y) + anchors[i][1], font,
                         OverlayText::Anchor::BottomCentre});
    }
    {
      const float ty = std::round(0.5f * (static_cast<float>(l.headerH) - font));
      texts.push_back({"t = " + fixedText(t, 1) + " h", m, ty, font, OverlayText::Anchor::TopLeft});
      if (!job.caption.empty()) texts.push_back({job.caption, m + timeW + 1.5f * font, ty, font, OverlayText::Anchor::TopLeft});
      if (overlays && job.view.showLegend) {
        float right = static_cast<float>(job.view.width) - m;
        const RenderScene::Material mat;
        for (int side = 1; side >= 0; --side) {
          const std::string label = side == 0 ? kLegendPlus : kLegendMinus;
          const auto& c = side == 0 ? mat.plus : mat.minus;
          texts.push_back({label, right, ty, font, OverlayText::Anchor::TopRight});
          right -= painter.textWidth(job.view.fontPath, label, font) + 0.3f * font;
          const float sw = std::round(1.3f * font), sh = std::max(3.0f, std::round(0.45f * font));
          rects.push_back({std::round(right - sw), std::round(ty + 0.5f * font - 0.5f * sh), sw, sh,
                           {static_cast<std::uint8_t>(std::lround(255 * c[0])), static_cast<std::uint8_t>(std::lround(255 * c[1])),
                            static_cast<std::uint8_t>(std::lround(255 * c[2])), 255}});
          right -= sw + 0.9f * font;
        }
      }
    }
    painter.draw(rects, {}, texts, job.view.fontPath, frame);
    sink.push(frame);
    if (progress) progress(k + 1, total);
  }
  sink.finish();
}

}  // namespace rootsim
