// state -> abstract render scene: the root as a swept tube with its stripes, the plate, the camera
// and the overlay items. No GL here; glm only for the camera matrices.
#include "rootsim/render_scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>

#include "overlay.hpp"
#include "rootsim/image.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/obstacle_mesh.hpp"
#include "rootsim/overlay_layout.hpp"
#include "rootsim/tube_rings.hpp"

namespace rootsim {

namespace {

constexpr double kPi = units::pi;
constexpr int kSides = 24;        // tube sides; normals are smooth, stripes are per pixel
constexpr int kTipRings = 8;      // rings of the hemispherical tip cap
constexpr int kWhiskerSides = 6;

using V3 = Eigen::Vector3d;

std::array<float, 16> toArray(const glm::mat4& m) {
  std::array<float, 16> a{};
  const float* p = glm::value_ptr(m);
  std::copy(p, p + 16, a.begin());
  return a;
}

void checkSize(const View& view) {
  if (view.width <= 0 || view.height <= 0)
    throw RenderError("render view: size must be positive (got " + std::to_string(view.width) + "x" +
                      std::to_string(view.height) + ")");
}

using Ring = TubeRing;  // rootsim/tube_rings.hpp

void addVertex(RenderScene& rs, const V3& p, const V3& nrm, double cs, double sn,
               const std::array<float, 3>& col, bool striped) {
  TubeVertex v{};
  for (int k = 0; k < 3; ++k) {
    v.pos[k] = static_cast<float>(p[k]);
    v.normal[k] = static_cast<float>(nrm[k]);
    v.colour[k] = col[static_cast<size_t>(k)];
  }
  v.side[0] = static_cast<float>(cs);
  v.side[1] = static_cast<float>(sn);
  v.striped = striped ? 1.0f : 0.0f;
  rs.vertices.push_back(v);
}

// quads between consecutive rings of `sides` vertices starting at index first
void stitchRings(RenderScene& rs, std::uint32_t first, int rings, int sides) {
  for (int j = 0; j + 1 < rings; ++j)
    for (int k = 0; k < sides; ++k) {
      const std::uint32_t a = first + static_cast<std::uint32_t>(j * sides + k);
      const std::uint32_t b = first + static_cast<std::uint32_t>(j * sides + (k + 1) % sides);
      const std::uint32_t c = a + static_cast<std::uint32_t>(sides), d = b + static_cast<std::uint32_t>(sides);
      rs.indices.insert(rs.indices.end(), {a, b, d, a, d, c});
    }
}

// ringColour: the body colour of each ring (empty: the material's ivory); with colours, the vertices
// carry striped = 2 (stripes over the vertex colour, outlined so they read on any map colour)
void addTube(RenderScene& rs, const std::vector<Ring>& rings, const std::vector<std::array<float, 3>>& ringColour) {
  const bool coloured = !ringColour.empty();
  const float stripedFlag = coloured ? 2.0f : 1.0f;
  auto colourOf = [&](std::size_t i) { return coloured ? ringColour[i] : rs.material.body; };
  auto striped = [&]() { rs.vertices.back().striped = stripedFlag; };
  // side wall
  const auto first = static_cast<std::uint32_t>(rs.vertices.size());
  for (std::size_t i = 0; i < rings.size(); ++i) {
    const Ring& g = rings[i];
    for (int k = 0; k < kSides; ++k) {
      const double phi = 2 * kPi * k / kSides, cs = std::cos(phi), sn = std::sin(phi);
      const V3 dir = cs * g.a + sn * g.b;
      addVertex(rs, g.c + g.r * dir, dir, cs, sn, colourOf(i), true);
      striped();
    }
  }
  stitchRings(rs, first, static_cast<int>(rings.size()), kSides);

  // tip: a hemisphere whose stripes run on to the apex
  const Ring& tip = rings.back();
  const auto tipFirst = static_cast<std::uint32_t>(rs.vertices.size());
  for (int j = 0; j <= kTipRings; ++j) {
    const double th = 0.5 * kPi * j / kTipRings;
    for (int k = 0; k < kSides; ++k) {
      const double phi = 2 * kPi * k / kSides, cs = std::cos(phi), sn = std::sin(phi);
      const V3 dir = cs * tip.a + sn * tip.b;
      const V3 nrm = std::cos(th) * dir + std::sin(th) * tip.t;
      addVertex(rs, tip.c + tip.r * nrm, nrm, cs, sn, colourOf(rings.size() - 1), true);
      striped();
    }
  }
  stitchRings(rs, tipFirst, kTipRings + 1, kSides);

  // base: a flat disc facing back along the axis
  const Ring& base = rings.front();
  const auto centre = static_cast<std::uint32_t>(rs.vertices.size());
  addVertex(rs, base.c, -base.t, 1, 0, colourOf(0), false);
  for (int k = 0; k < kSides; ++k) {
    const double phi = 2 * kPi * k / kSides;
    addVertex(rs, base.c + base.r * (std::cos(phi) * base.a + std::sin(phi) * base.b), -base.t, 1, 0,
              colourOf(0), false);
  }
  for (int k = 0; k < kSides; ++k)
    rs.indices.insert(rs.indices.end(), {centre, centre + 1 + static_cast<std::uint32_t>((k + 1) % kSides),
                                         centre + 1 + static_cast<std::uint32_t>(k)});
}

// thin cylinders along +d1 (pink) and -d1 (orange), about every two diameters along the root
void addWhiskers(RenderScene& rs, const std::vector<Ring>& rings) {
  double arc = 1e300;  // arc length since the last whisker [mm]
  for (size_t i = 0; i < rings.size(); ++i) {
    if (i > 0) arc += (rings[i].c - rings[i - 1].c).norm();
    const Ring& g = rings[i];
    if (arc < 2.5 * g.r && i + 1 != rings.size()) continue;
    arc = 0.0;
    for (int sgn : {+1, -1}) {
      const V3 axis = sgn * g.a;
      const V3 p0 = g.c + 0.8 * g.r * axis, p1 = g.c + 2.4 * g.r * axis;
      const double rw = 0.09 * g.r;
      const auto& col = sgn > 0 ? rs.material.plus : rs.material.minus;
      const V3 e1 = g.t, e2 = axis.cross(g.t);
      const auto first = static_cast<std::uint32_t>(rs.vertices.size());
      for (const V3& p : {p0, p1})
        for (int k = 0; k < kWhiskerSides; ++k) {
          const double phi = 2 * kPi * k / kWhiskerSides;
          const V3 dir = std::cos(phi) * e1 + std::sin(phi) * e2;
          addVertex(rs, p + rw * dir, dir, 1, 0, col, false);
        }
      stitchRings(rs, first, 2, kWhiskerSides);
      const auto capC = static_cast<std::uint32_t>(rs.vertices.size());
      addVertex(rs, p1, axis, 1, 0, col, false);
      for (int k = 0; k < kWhiskerSides; ++k)
        rs.indices.insert(rs.indices.end(),
                          {capC, first + kWhiskerSides + static_cast<std::uint32_t>(k),
                           first + kWhiskerSides + static_cast<std::uint32_t>((k + 1) % kWhiskerSides)});
    }
  }
}



std::array<std::uint8_t, 4> rgba8(const std::array<float, 3>& c) {
  auto b = [](float v) { return static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(v, 0.0f, 1.0f))); };
  return {b(c[0]), b(c[1]), b(c[2]), 255};
}

// the colour bar's geometry for a view: bar width, and the width [px] it takes from the right edge
// with its tick labels and its title (the framing keeps that strip free of the root)
struct ColourBarBox {
  float barW, small, reserve;
};
ColourBarBox colourBarBox(const View& view, float font) {
  ColourBarBox b{};
  const float m = 0.7f * font;
  b.barW = std::max(8.0f, std::round(0.6f * font));
  b.small = std::round(0.8f * font);
  const auto [lo, hi] = view.colourRange;
  float ticks = 0;
  for (double v : {lo, 0.5 * (lo + hi), hi}) ticks = std::max(ticks, detail::measureText(view.fontPath, tickText(v), b.small));
  const float title = detail::measureText(view.fontPath, colourFieldLabel(view.colourBy), b.small);
  b.reserve = m + std::max(b.barW + 7 + ticks, title) + 0.5f * font;
  return b;
}

// vertical colour bar at the right edge, middle half of the height: the map from the range's low
// end (bottom) to its high end (top), three labelled values and the field's name with its unit above;
// a signed field's diverging map has its 0 marked across the bar
void addColourBar(RenderScene& rs, const View& view, float font) {
  const float m = 0.7f * font;
  const ColourBarBox box = colourBarBox(view, font);
  const float barW = box.barW;
  const float y0 = std::round(0.28f * static_cast<float>(view.height));
  const float y1 = std::round(0.78f * static_cast<float>(view.height));
  const float x = std::round(static_cast<float>(view.width) - m - barW);
  const int rows = static_cast<int>(y1 - y0);
  const auto [lo, hi] = view.colourRange;
  for (int r = 0; r < rows; ++r) {
    const double v = lo + (hi - lo) * (1.0 - (r + 0.5) / rows);
    rs.rects.push_back({x, y0 + static_cast<float>(r), barW, 1.0f, rgba8(fieldColour(view.colourBy, v, view.colourRange))});
  }
  // frame around the bar
  rs.rects.push_back({x - 1, y0 - 1, barW + 2, 1, detail::kInk});
  rs.rects.push_back({x - 1, y1, barW + 2, 1, detail::kInk});
  rs.rects.push_back({x - 1, y0 - 1, 1, y1 - y0 + 2, detail::kInk});
  rs.rects.push_back({x + barW, y0 - 1, 1, y1 - y0 + 2, detail::kInk});
  const float small = box.small;
  for (int k = 0; k <= 2; ++k) {
    const double v = lo + (hi - lo) * k / 2.0;
    const float y = y1 - (y1 - y0) * static_cast<float>(k) / 2.0f;
    rs.rects.push_back({x - 5, std::round(y), 5, 1, detail::kInk});
    rs.texts.push_back({tickText(v), x - 7, y - 0.5f * small, small, OverlayText::Anchor::TopRight});
  }
  if (colourFieldSigned(view.colourBy) && lo < 0 && hi > 0) {
    // 0 across the bar, and its label (the middle tick when the range is symmetric)
    const float y = std::round(y1 - (y1 - y0) * static_cast<float>(-lo / (hi - lo)));
    rs.rects.push_back({x - 5, y, barW + 6, std::max(1.0f, std::round(font / 14.0f)), detail::kInk});
    if (std::abs(lo + hi) > 1e-9 * (hi - lo))
      rs.texts.push_back({"0", x - 7, y - 0.5f * small, small, OverlayText::Anchor::TopRight});
  }
  rs.texts.push_back({colourFieldLabel(view.colourBy), static_cast<float>(view.width) - m, y0 - 0.5f * font, small,
                      OverlayText::Anchor::BottomRight});
}

// an arrow from a to b [px]: shaft and a filled-looking head (two thick strokes)
void addArrow(RenderScene& rs, const Eigen::Vector2d& a, const Eigen::Vector2d& b, float width) {
  const Eigen::Vector2d d = (b - a).normalized(), n(-d.y(), d.x());
  const double head = 4.0 * width;
  const Eigen::Vector2d h1 = b - head * d + 0.6 * head * n, h2 = b - head * d - 0.6 * head * n;
  auto pt = [](const Eigen::Vector2d& p) { return std::array<float, 2>{static_cast<float>(p.x()), static_cast<float>(p.y())}; };
  rs.lines.push_back({{pt(a), pt(b - 0.5 * width * d)}, width, detail::kInk});
  rs.lines.push_back({{pt(h1), pt(b), pt(h2)}, width, detail::kInk});
  // the head's inside: strokes from its tip across to its base
  for (double f : {0.25, 0.5, 0.75}) rs.lines.push_back({{pt(b), pt(h1 + f * (h2 - h1))}, width, detail::kInk});
}

// the colour of a traced root's line: the figures' trace colour (compare_panel.cpp)
constexpr std::array<std::uint8_t, 4> kTraceInk{13, 51, 140, 255};

// a traced root over the picture, as a line through its projected points; a time-lapse trace as it was
// at time tH
void addTrace(RenderScene& rs, const View& view, double tH) {
  if (view.traceUvMm.size() < 2) return;
  std::vector<std::array<double, 2>> uv = view.traceUvMm;
  if (view.traceTimeH.size() == uv.size()) {
    // the points reached by tH, and where the tip was between the two around it
    std::size_t n = 0;
    while (n < uv.size() && view.traceTimeH[n] <= tH) ++n;
    if (n == 0) return;
    if (n < uv.size() && view.traceTimeH[n] > view.traceTimeH[n - 1]) {
      const double f = (tH - view.traceTimeH[n - 1]) / (view.traceTimeH[n] - view.traceTimeH[n - 1]);
      uv[n] = {uv[n - 1][0] + f * (uv[n][0] - uv[n - 1][0]), uv[n - 1][1] + f * (uv[n][1] - uv[n - 1][1])};
      ++n;
    }
    uv.resize(n);
  }
  OverlayLine l;
  l.widthPx = std::max(2.0f, std::round(overlayFontPx(view) / 9.0f));
  l.colour = kTraceInk;
  l.overRoot = true;  // a trace is compared with the root: drawn over it
  for (const auto& p : uv) {
    Eigen::Vector2d px;
    if (projectToPixel(rs, V3(p[0], p[1], 0), px)) l.points.push_back({static_cast<float>(px.x()), static_cast<float>(px.y())});
  }
  if (l.points.size() >= 2) rs.lines.push_back(std::move(l));
}

// the overlays at their preferred places, one block each (time, parameters, title and legend, scale,
// downhill arrow, colour bar), in the order the layout serves them
void addOverlays(RenderScene& rs, const Snapshot& s, const SceneInfo& info, const View& view, const Framing& framing,
                 std::vector<OverlayBlock>& blocks) {
  if (!view.overlays) return;
  // each block: the items added to rs since the last cut, moved out of rs
  std::size_t r0 = rs.rects.size(), l0 = rs.lines.size(), t0 = rs.texts.size();
  const auto cut = [&]() {
    OverlayBlock b;
    b.rects.assign(rs.rects.begin() + static_cast<long>(r0), rs.rects.end());
    b.lines.assign(rs.lines.begin() + static_cast<long>(l0), rs.lines.end());
    b.texts.assign(rs.texts.begin() + static_cast<long>(t0), rs.texts.end());
    rs.rects.resize(r0), rs.lines.resize(l0), rs.texts.resize(t0);
    if (!b.rects.empty() || !b.lines.empty() || !b.texts.empty()) blocks.push_back(std::move(b));
  };
  // text scales with the shorter side, so portrait frames get the same text as landscape ones
  const float font = overlayFontPx(view);
  const bool portrait = view.height > view.width;
  const float m = 0.7f * font;
  const auto W = static_cast<float>(view.width), H = static_cast<float>(view.height);
  auto width = [&](const std::string& t, float size) { return detail::measureText(view.fontPath, t, size); };
  if (view.showTime)
    rs.texts.push_back({"t = " + fixedText(s.timeH, 1) + " h", m, m, font, OverlayText::Anchor::TopLeft});
  cut();
  // a plate's seedlings: their labels on the plate above their seeds, each a block of its own
  for (const View::SeedLabel& sl : view.seedLabels) {
    Eigen::Vector2d px;
    if (!projectToPixel(rs, V3(sl.u, sl.v, 0), px)) continue;
    const float x = static_cast<float>(px.x()), y = static_cast<float>(px.y()) - 0.3f * font;
    const float subPx = std::round(0.6f * font);
    if (!sl.sub.empty()) rs.texts.push_back({sl.sub, x, y, subPx, OverlayText::Anchor::BottomCentre});
    rs.texts.push_back({sl.label, x, sl.sub.empty() ? y : y - 1.25f * subPx, std::round(0.75f * font), OverlayText::Anchor::BottomCentre});
    cut();
  }
  if (view.showParams) {
    // a plate's seedlings each have their own beta and R tau: those are in the legend, not the header
    const bool own = !view.seedLabels.empty();
    std::string p = "\xCE\xB1 = " + fixedText(info.alphaDeg, 0) + "\xC2\xB0" +
                    (own ? std::string() : "    \xCE\xB2 = " + significantText(info.beta, 3)) + "    \xCE\xB3 = " + significantText(info.gamma, 3);
    if (!own && info.rTau != 0.0) p += "    R\xCF\x84 = " + significantText(info.rTau, 3);
    // the legend: one line per seedling under the header, at the right edge
    const float small = std::round(0.8f * font);
    float y = m + (portrait && view.showTime ? 3.0f : 1.5f) * font;
    for (const View::SeedLabel& sl : view.seedLabels) {
      rs.texts.push_back({sl.values, W - m, y, small, OverlayText::Anchor::TopRight});
      y += 1.3f * small;
    }
    // landscape: top right, beside the time; portrait: a second line under the time
    if (portrait)
      rs.texts.push_back({p, m, m + (view.showTime ? 1.5f * font : 0.0f), font, OverlayText::Anchor::TopLeft});
    else
      rs.texts.push_back({p, W - m, m, font, OverlayText::Anchor::TopRight});
  }
  cut();
  // the bottom band: from the left the title and the stripe legend, from the right the scale bar (or
  // the grid's pitch) and the downhill arrow; every item's vertical centre on one line
  const float small = std::round(0.8f * font);
  const float midY = std::round(H - m - 0.55f * font);
  float left = m, right = W - m;
  bool scaleBlock = false;
  if (view.showTitle && !info.title.empty()) {
    rs.texts.push_back({info.title, m, H - m, font, OverlayText::Anchor::BottomLeft});
    left += width(info.title, font) + 1.2f * font;
  }
  if (view.showLegend) {
    const float sw = std::round(1.3f * font), sh = std::max(3.0f, std::round(0.45f * font));
    for (int k = 0; k < 2; ++k) {
      const auto& c = k == 0 ? rs.material.plus : rs.material.minus;
      const std::string label = k == 0 ? kLegendPlus : kLegendMinus;
      rs.rects.push_back({std::round(left), std::round(midY - 0.5f * sh), sw, sh, rgba8(c)});
      rs.texts.push_back({label, left + sw + 0.3f * font, midY - 0.5f * font, font, OverlayText::Anchor::TopLeft});
      left += sw + 0.3f * font + width(label, font) + 0.9f * font;
    }
    if (view.traceUvMm.size() >= 2) {
      const float tw = std::round(1.3f * font), tl = std::max(2.0f, std::round(font / 9.0f));
      rs.rects.push_back({std::round(left), std::round(midY - 0.5f * tl), tw, tl, kTraceInk});
      rs.texts.push_back({"trace", left + tw + 0.3f * font, midY - 0.5f * font, font, OverlayText::Anchor::TopLeft});
      left += tw + 0.3f * font + width("trace", font) + 0.9f * font;
    }
  }
  cut();
  if (view.showScaleBar && rs.pxPerMm > 0) {
    const double lenMm = niceLength(0.22 * view.width / rs.pxPerMm);
    const float len = static_cast<float>(lenMm * rs.pxPerMm);
    const float h = std::max(3.0f, std::round(0.22f * font));
    const float x = std::round(W - m - len);
    const float y = std::round(H - m - h);
    rs.rects.push_back({x, y, std::round(len), h});
    const std::string label = (lenMm >= 1 ? fixedText(lenMm, 0) : fixedText(lenMm, 1)) + " mm";
    rs.texts.push_back({label, x + 0.5f * len, y - 0.35f * font, font, OverlayText::Anchor::BottomCentre});
    right = x - 1.0f * font;
    scaleBlock = true;
  } else if (view.showScaleBar && rs.plate.visible) {
    // perspective: no single scale, so the grid's pitch
    const std::string pitch = "grid " + (rs.plate.gridMm >= 1 ? fixedText(rs.plate.gridMm, 0) : fixedText(rs.plate.gridMm, 1)) +
                              " mm" + (rs.plate.gridMm < 1 ? ", dark every 1 mm" : "");
    rs.texts.push_back({pitch, right, midY - 0.5f * font, font, OverlayText::Anchor::TopRight});
    right -= width(pitch, font) + 1.0f * font;
  }
  cut();
  if (scaleBlock) blocks.back().shrink = false;  // the bar's length is its label's
  if (view.showDownhill && info.plate) {
    // downhill (-v) as the picture shows it at the framing's centre
    Eigen::Vector2d a, b, dir(0, 1);
    const double step = 0.05 * framing.widthMm;
    if (projectToPixel(rs, V3(framing.centreU, framing.centreV, 0), a) &&
        projectToPixel(rs, V3(framing.centreU, framing.centreV - step, 0), b) && (b - a).norm() > 1e-6)
      dir = (b - a).normalized();
    const float lw = std::max(2.0f, std::round(font / 9.0f));
    const double half = 0.75 * font;
    const Eigen::Vector2d centre(right - 0.5 * font, midY);
    addArrow(rs, centre - half * dir, centre + half * dir, lw);
    rs.texts.push_back({kDownhillLabel, right - 1.3f * font, midY - 0.5f * small, small, OverlayText::Anchor::TopRight});
  }
  cut();
  if (view.colourBy != ColourField::None && view.showColourBar) addColourBar(rs, view, font);
  cut();
}

// the layout step: every block moved off the root's footprint fp and the rectangles the view keeps
// clear, then added to the scene
void placeOverlays(RenderScene& rs, const View& view, std::vector<OverlayBlock>& blocks,
                   std::vector<std::array<float, 4>> keepClear, const RootFootprint& fp) {
  if (blocks.empty()) return;
  std::vector<std::array<float, 4>> boxes;
  boxes.reserve(blocks.size());
  std::vector<float> minScale;
  for (const OverlayBlock& b : blocks) {
    boxes.push_back(blockBox(b, view.fontPath));
    minScale.push_back(b.shrink ? 0.64f : 1.0f);
  }
  const float m = 0.35f * overlayFontPx(view);
  keepClear.insert(keepClear.end(), view.keepClearPx.begin(), view.keepClearPx.end());
  const std::vector<PlacedBlock> placed = layoutBoxes(boxes, fp, keepClear, view.width, view.height, m, minScale);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    OverlayBlock& b = blocks[i];
    applyPlacement(b, boxes[i], placed[i]);
    rs.rects.insert(rs.rects.end(), b.rects.begin(), b.rects.end());
    rs.lines.insert(rs.lines.end(), b.lines.begin(), b.lines.end());
    for (OverlayText& t : b.texts) rs.texts.push_back(std::move(t));
  }
}

// the key light's depth view of the root: an orthographic box along the light, fitted around the
// tube vertices near the visible part of the plate (their shadows can fall into the picture)
// mapSide: in, the largest map side [px]; out, a side giving about one texel per picture pixel;
// texelMm: out, the size of one texel on the light's view [mm]
std::array<float, 16> lightViewProj(const RenderScene& rs, const glm::vec3& towardsLight, const Framing& f,
                                    double pxPerMm, int& mapSide, float& texelMm) {
  const glm::vec3 L = glm::normalize(towardsLight);
  const glm::vec3 up = std::abs(L.y) > 0.95f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::mat4 look = glm::lookAt(glm::vec3(0.0f), -L, up);  // light looks along -L
  // plate window with room for the shadows of raised parts
  const double reach = 2.0 * f.topW + 1.0;
  const double u0 = f.centreU - 0.5 * f.widthMm - reach, u1 = f.centreU + 0.5 * f.widthMm + reach;
  const double v0 = f.centreV - 0.5 * f.heightMm - reach, v1 = f.centreV + 0.5 * f.heightMm + reach;
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const TubeVertex& v : rs.vertices) {
    if (v.pos[0] < u0 || v.pos[0] > u1 || v.pos[1] < v0 || v.pos[1] > v1) continue;
    const glm::vec3 q = glm::vec3(look * glm::vec4(v.pos[0], v.pos[1], v.pos[2], 1.0f));
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  if (lo.x > hi.x) {  // nothing of the root near the picture: an empty box far from everything
    lo = glm::vec3(-1.0f);
    hi = glm::vec3(-0.5f);
  }
  const float pad = 0.02f * std::max(hi.x - lo.x, hi.y - lo.y) + 1e-3f;
  // texels: about one per picture pixel across the box (a power of two, 256 .. mapSide)
  const double needed = (std::max(hi.x - lo.x, hi.y - lo.y) + 2 * pad) * pxPerMm;
  int side = 256;
  while (side < needed && side < mapSide) side *= 2;
  mapSide = std::min(side, mapSide);
  texelMm = (std::max(hi.x - lo.x, hi.y - lo.y) + 2 * pad) / static_cast<float>(mapSide);
  // eye-space z is negative in front: near/far from the depth range, the far plane well behind
  // the plate so every plate point under the root compares against the stored depths
  const float nearZ = -hi.z - pad, farZ = -lo.z + 100.0f * (hi.z - lo.z + 1.0f);
  return toArray(glm::ortho(lo.x - pad, hi.x + pad, lo.y - pad, hi.y + pad, nearZ, farZ) * look);
}

}  // namespace

float overlayFontPx(const View& view) {
  if (view.fontPx) {
    if (!(*view.fontPx > 0)) throw RenderError("render view: fontPx must be > 0 (got " + std::to_string(*view.fontPx) + ")");
    return *view.fontPx;
  }
  return std::max(12.0f, static_cast<float>(std::min(view.width, view.height)) / 26.0f);
}

Framing frameFor(const std::vector<Snapshot>& snaps, const SceneInfo& info, const View& view) {
  checkSize(view);
  if (snaps.empty()) throw RenderError("render: no snapshots to frame");
  const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
  const double inf = std::numeric_limits<double>::infinity();
  double u0 = inf, u1 = -inf, v0 = inf, v1 = -inf, wTop = 0.0, rMax = 0.0;
  for (const Snapshot& s : snaps) {
    checkTubeSnapshot(s, "render");
    for (long i = 0; i < s.x.cols(); ++i) {
      const V3 p = pf.toPlateMm(s.x.col(i));
      u0 = std::min(u0, p.x()), u1 = std::max(u1, p.x());
      v0 = std::min(v0, p.y()), v1 = std::max(v1, p.y());
      wTop = std::max(wTop, p.z());
    }
    rMax = std::max(rMax, s.radius.maxCoeff() / units::mm);
  }
  const double pad = rMax + view.marginMm;
  const double aspect = static_cast<double>(view.width) / view.height;
  // with overlays, keep the root inside the middle 80 % of the height (text above, scale bar below)
  const double usable = view.overlays ? 0.8 : 1.0;
  // with a colour bar, keep the root left of its strip at the right edge
  const bool bar = view.overlays && view.showColourBar && view.colourBy != ColourField::None;
  const double barFrac = bar ? std::min(0.4, static_cast<double>(colourBarBox(view, overlayFontPx(view)).reserve) / view.width) : 0.0;
  Framing f;
  f.centreU = view.centreMm ? (*view.centreMm)[0] : 0.5 * (u0 + u1);
  f.centreV = view.centreMm ? (*view.centreMm)[1] : 0.5 * (v0 + v1);
  if (view.widthMm) {
    if (!(*view.widthMm > 0)) throw RenderError("render view: widthMm must be > 0 (got " + std::to_string(*view.widthMm) + ")");
    f.widthMm = *view.widthMm;
  } else {
    // half extents about the (possibly fixed) centre
    const double hu = std::max(f.centreU - u0, u1 - f.centreU) + pad;
    const double hv = std::max(f.centreV - v0, v1 - f.centreV) + pad;
    f.widthMm = std::max({2 * hu / (1.0 - barFrac), 2 * hv / usable * aspect, 1.0});
    // the root's centre in the middle of the part left of the bar
    if (!view.centreMm) f.centreU += 0.5 * barFrac * f.widthMm;
  }
  f.heightMm = f.widthMm / aspect;
  f.topW = wTop + rMax;
  if (view.kind == View::Kind::Perspective && !view.widthMm && !view.centreMm) {
    // the oblique camera shows the box smaller than the top view: fit the nodes' projection into the
    // part of the picture the top view keeps for the root (the middle of the height with overlays, left
    // of the colour bar's strip), less a margin of max(6 px, 4 % of it)
    std::vector<Eigen::Vector3d> pts;
    for (const Snapshot& s : snaps)
      for (long i = 0; i < s.x.cols(); ++i) pts.push_back(pf.toPlateMm(s.x.col(i)));
    const double W = view.width, H = view.height;
    const double m = std::max(6.0, 0.04 * std::min(W, usable * H));  // as a montage's tiles
    std::vector<Framing> one{f};
    fitFramingsToBox(one, {pts}, view, {m, 0.5 * (1 - usable) * H + m, (1 - barFrac) * W - m, H - 0.5 * (1 - usable) * H - m}, rMax);
    f = one.front();
  }
  return f;
}

void fitFramingsToBox(std::vector<Framing>& framings, const std::vector<std::vector<Eigen::Vector3d>>& points,
                      const View& view, const std::array<double, 4>& goal, double padMm) {
  const double goalW = goal[2] - goal[0], goalH = goal[3] - goal[1];
  if (framings.empty() || !(goalW > 4) || !(goalH > 4)) return;
  const double inf = std::numeric_limits<double>::infinity();
  for (int round = 0; round < 8; ++round) {
    double x0 = inf, x1 = -inf, y0 = inf, y1 = -inf;
    Eigen::Matrix2d jac = Eigen::Matrix2d::Zero();  // px per mm along u and v at the first window's centre
    for (std::size_t k = 0; k < framings.size() && k < points.size(); ++k) {
      RenderScene cam;
      cam.width = view.width;
      cam.height = view.height;
      const CameraMatrices mx = cameraFor(view, framings[k]);
      cam.viewMatrix = mx.view;
      cam.projMatrix = mx.proj;
      for (const Eigen::Vector3d& p : points[k]) {
        Eigen::Vector2d px;
        if (!projectToPixel(cam, p, px)) continue;
        x0 = std::min(x0, px.x()), x1 = std::max(x1, px.x()), y0 = std::min(y0, px.y()), y1 = std::max(y1, px.y());
      }
      if (k == 0) {
        const Eigen::Vector3d c(framings[0].centreU, framings[0].centreV, 0.0);
        Eigen::Vector2d p0, pu, pv;
        if (projectToPixel(cam, c, p0) && projectToPixel(cam, c + Eigen::Vector3d(1, 0, 0), pu) &&
            projectToPixel(cam, c + Eigen::Vector3d(0, 1, 0), pv)) {
          jac.col(0) = pu - p0;
          jac.col(1) = pv - p0;
        }
      }
    }
    if (!(x1 >= x0) || std::abs(jac.determinant()) < 1e-12) return;
    const double rPx = padMm * view.width / framings[0].widthMm;
    const double bw = x1 - x0 + 2 * rPx, bh = y1 - y0 + 2 * rPx;
    const double k = std::min(goalW / std::max(bw, 1.0), goalH / std::max(bh, 1.0));
    // the box's centre to the goal's (a window moved by d mm moves the picture by -J d)
    const Eigen::Vector2d shift(0.5 * (x0 + x1) - 0.5 * (goal[0] + goal[2]), 0.5 * (y0 + y1) - 0.5 * (goal[1] + goal[3]));
    if (std::abs(k - 1) < 1e-3 && shift.norm() < 0.25) return;
    const Eigen::Vector2d d = jac.inverse() * shift;
    for (Framing& f : framings) {
      f.centreU += d.x(), f.centreV += d.y();
      f.widthMm /= k, f.heightMm /= k;
    }
  }
}

bool projectToPixel(const RenderScene& rs, const Eigen::Vector3d& p, Eigen::Vector2d& px) {
  glm::mat4 V, P;
  std::copy(rs.viewMatrix.begin(), rs.viewMatrix.end(), glm::value_ptr(V));
  std::copy(rs.projMatrix.begin(), rs.projMatrix.end(), glm::value_ptr(P));
  const glm::vec4 c = P * V * glm::vec4(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()), 1.0f);
  if (!(c.w > 0.0f)) return false;
  px = {(0.5 * (c.x / c.w) + 0.5) * rs.width, (0.5 - 0.5 * (c.y / c.w)) * rs.height};
  return true;
}

Eigen::Vector2d topViewPixel(const Framing& f, const View& view, double u, double v) {
  return {(u - (f.centreU - 0.5 * f.widthMm)) / f.widthMm * view.width,
          ((f.centreV + 0.5 * f.heightMm) - v) / f.heightMm * view.height};
}

CameraMatrices cameraFor(const View& view, const Framing& framing) {
  CameraMatrices c;
  const auto cu = static_cast<float>(framing.centreU), cv = static_cast<float>(framing.centreV);
  const auto hw = static_cast<float>(0.5 * framing.widthMm), hh = static_cast<float>(0.5 * framing.heightMm);
  const float aspect = static_cast<float>(view.width) / static_cast<float>(view.height);
  if (view.kind == View::Kind::Top) {
    // orthographic along -n: u to the right, v (uphill) up, so downhill points down the image
    const float eyeW = 1000.0f;
    c.view = toArray(glm::lookAt(glm::vec3(cu, cv, eyeW), glm::vec3(cu, cv, 0), glm::vec3(0, 1, 0)));
    c.proj = toArray(glm::ortho(-hw, hw, -hh, hh, 1.0f, 2.0f * eyeW));
  } else {
    // oblique preset: from above the plate, in front of its lower right part, uphill up the image
    const float fovY = glm::radians(30.0f);
    const glm::vec3 target(cu, cv, 0.5f * static_cast<float>(framing.topW));
    const glm::vec3 dir = glm::normalize(glm::vec3(0.45f, -0.85f, 1.0f));
    const float fit = std::max(hh, hw / aspect);
    const float dist = 1.05f * fit / std::tan(0.5f * fovY);
    c.view = toArray(glm::lookAt(target + dist * dir, target, glm::vec3(0, 1, 0)));
    c.proj = toArray(glm::perspective(fovY, aspect, 0.02f * dist, 20.0f * dist));
  }
  return c;
}

RenderScene buildRenderScene(const Snapshot& snap, const SceneInfo& info, const View& view,
                             const Framing& framing) {
  checkSize(view);
  checkTubeSnapshot(snap, "render");
  if (!(framing.widthMm > 0) || !(framing.heightMm > 0))
    throw RenderError("render: framing must have a positive width and height (got " +
                      std::to_string(framing.widthMm) + " x " + std::to_string(framing.heightMm) + " mm)");
  RenderScene rs;
  rs.width = view.width;
  rs.height = view.height;
  rs.fontPath = view.fontPath;
  rs.material.stripeCos = static_cast<float>(std::cos(view.stripeHalfWidthDeg * units::deg));

  std::vector<std::array<float, 4>> outlineClear;  // a whole plate's outline, kept clear of the overlays
  // the root
  const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
  rs.vertices.reserve(static_cast<size_t>((snap.x.cols() + rootCount(snap) * (kTipRings + 2)) * kSides));
  rs.indices.reserve(rs.vertices.capacity() * 6);
  // each root its own tube (a plate's roots: Snapshot::rootStarts)
  for (int k = 0; k < rootCount(snap); ++k) {
    const Snapshot part = rootCount(snap) == 1 ? Snapshot{} : rootOf(snap, k);
    const Snapshot& root = rootCount(snap) == 1 ? snap : part;
    std::vector<Ring> rings = tubeRings(root, pf);
    // at least 1.5 px wide in the top view, so a thin root (a lateral on a whole plate) stays one line
    if (view.kind == View::Kind::Top)
      for (Ring& g : rings) g.r = std::max(g.r, 0.75 * framing.widthMm / view.width);
    std::vector<std::array<float, 3>> ringColour;
    if (view.colourBy != ColourField::None) {
      const Eigen::VectorXd field = nodeField(root, info, view.colourBy);
      const auto [lo, hi] = view.colourRange;
      if (!(hi > lo)) throw RenderError("render view: colourRange must be increasing");
      for (double v : field) ringColour.push_back(fieldColour(view.colourBy, v, view.colourRange));
    }
    addTube(rs, rings, ringColour);
    if (view.whiskers) addWhiskers(rs, rings);
  }
  addObstacleMeshes(info, rs);

  // camera
  const CameraMatrices cam = cameraFor(view, framing);
  rs.viewMatrix = cam.view;
  rs.projMatrix = cam.proj;
  const auto cu = static_cast<float>(framing.centreU), cv = static_cast<float>(framing.centreV);
  const auto hw = static_cast<float>(0.5 * framing.widthMm), hh = static_cast<float>(0.5 * framing.heightMm);
  glm::vec3 light, towardsLightPlate;
  if (view.kind == View::Kind::Top) {
    rs.pxPerMm = view.width / framing.widthMm;
    rs.plate.u0 = cu - 1.05f * hw, rs.plate.u1 = cu + 1.05f * hw;
    rs.plate.v0 = cv - 1.05f * hh, rs.plate.v1 = cv + 1.05f * hh;
    light = glm::normalize(glm::vec3(-0.35f, 0.5f, 1.0f));
    towardsLightPlate = light;  // the view is a translation: eye axes are the plate axes
  } else {
    const float ext = 4.0f * std::max(hw, hh);
    rs.plate.u0 = cu - ext, rs.plate.u1 = cu + ext;
    rs.plate.v0 = cv - ext, rs.plate.v1 = cv + ext;
    light = glm::normalize(glm::vec3(-0.3f, 0.6f, 1.0f));
    // the same light in plate axes (the view's rotation is orthonormal)
    glm::mat4 viewM;
    std::copy(rs.viewMatrix.begin(), rs.viewMatrix.end(), glm::value_ptr(viewM));
    towardsLightPlate = glm::transpose(glm::mat3(viewM)) * light;
  }
  rs.lightDir = {light.x, light.y, light.z};

  // a 1 mm grid, or 0.1 mm (every 10th line darker) when millimetres are hundreds of pixels apart
  if (view.width / framing.widthMm > 250.0) rs.plate.gridMm = 0.1f;

  // shadows need a plate to fall on
  rs.shadows = view.shadows && info.plate && !view.transparent;
  if (rs.shadows) {
    if (view.shadowMapPx < 256 || view.shadowMapPx > 8192)
      throw RenderError("render view: shadowMapPx must be in 256..8192 (got " + std::to_string(view.shadowMapPx) + ")");
    rs.shadowMapPx = view.shadowMapPx;
    rs.lightViewProj = lightViewProj(rs, towardsLightPlate, framing, view.width / framing.widthMm, rs.shadowMapPx,
                                     rs.shadowTexelMm);
    rs.lightPlate = {towardsLightPlate.x, towardsLightPlate.y, towardsLightPlate.z};
    // the map's footprint on the plate: each corner's ray through the light box meets w = 0
    glm::mat4 lvp;
    std::copy(rs.lightViewProj.begin(), rs.lightViewProj.end(), glm::value_ptr(lvp));
    const glm::mat4 inv = glm::inverse(lvp);
    const float corners[4][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    for (int c = 0; c < 4; ++c) {
      glm::vec4 a = inv * glm::vec4(corners[c][0], corners[c][1], -1.0f, 1.0f);
      glm::vec4 b = inv * glm::vec4(corners[c][0], corners[c][1], 1.0f, 1.0f);
      a /= a.w;
      b /= b.w;
      const float t = std::abs(a.z - b.z) > 1e-12f ? a.z / (a.z - b.z) : 0.0f;
      rs.shadowQuad[static_cast<std::size_t>(2 * c)] = a.x + t * (b.x - a.x);
      rs.shadowQuad[static_cast<std::size_t>(2 * c + 1)] = a.y + t * (b.y - a.y);
    }
  }

  // background: the plate, a plain light field without one, or nothing (transparent)
  rs.plate.visible = info.plate && !view.transparent;
  if (view.transparent)
    rs.background = {0, 0, 0, 0};
  else if (info.plate)
    rs.background = {1, 1, 1, 1};
  else
    rs.background = {rs.plate.colour[0], rs.plate.colour[1], rs.plate.colour[2], 1};

  // grid lines that stay visible on big pictures
  rs.plate.lineWidthPx = std::max(1.0f, static_cast<float>(std::min(view.width, view.height)) / 1080.0f);
  if (view.plateRectMm && rs.plate.visible) {
    // the whole plate: its own extent on a grey surround, outlined
    const auto [u0, v0, u1, v1] = *view.plateRectMm;
    rs.plate.u0 = static_cast<float>(u0), rs.plate.v0 = static_cast<float>(v0);
    rs.plate.u1 = static_cast<float>(u1), rs.plate.v1 = static_cast<float>(v1);
    rs.background = {0.78f, 0.78f, 0.78f, 1};
    OverlayLine l;
    l.widthPx = std::max(1.5f, rs.plate.lineWidthPx * 1.5f);
    l.colour = {60, 60, 60, 255};
    for (const auto& [u, v] : {std::pair{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}, {u0, v0}}) {
      Eigen::Vector2d px;
      if (projectToPixel(rs, V3(u, v, 0), px)) l.points.push_back({static_cast<float>(px.x()), static_cast<float>(px.y())});
    }
    if (l.points.size() == 5) {
      // the overlays keep off the outline: a strip a font's third wide along each side
      const float k = std::max(4.0f, 0.35f * overlayFontPx(view));
      for (std::size_t i = 0; i + 1 < l.points.size(); ++i) {
        const auto& a = l.points[i];
        const auto& b = l.points[i + 1];
        outlineClear.push_back({std::min(a[0], b[0]) - k, std::min(a[1], b[1]) - k, std::max(a[0], b[0]) + k, std::max(a[1], b[1]) + k});
      }
      rs.lines.push_back(std::move(l));
    }
  }
  if (view.scanLook) {
    // light roots on a dark plate, no stripes, no grid: a scanner's picture of the plate
    rs.material.body = {0.92f, 0.91f, 0.86f};
    rs.material.plus = rs.material.minus = rs.material.body;
    rs.plate.colour = {0.05f, 0.05f, 0.06f};
    rs.plate.line = rs.plate.major = rs.plate.colour;
    rs.background = {0.0f, 0.0f, 0.0f, 1};
    rs.shadows = false;
  }
  addTrace(rs, view, snap.timeH);
  std::vector<OverlayBlock> blocks;
  addOverlays(rs, snap, info, view, framing, blocks);
  if (rs.rects.empty() && rs.texts.empty() && blocks.empty() &&
      std::all_of(rs.lines.begin(), rs.lines.end(), [](const OverlayLine& l) { return l.overRoot; }))
    return rs;
  // the painter keeps this snapshot's footprint; the layout the movie's (View::footprint: every frame
  // the overlays hold still over), or this snapshot's own
  auto own = std::make_shared<RootFootprint>(view.width, view.height);
  own->add(snap, info, cam, view.whiskers);
  rs.keepOut = std::move(own);
  const bool movie = view.footprint && view.footprint->width() == view.width && view.footprint->height() == view.height;
  placeOverlays(rs, view, blocks, outlineClear, movie ? *view.footprint : *rs.keepOut);
  return rs;
}

}  // namespace rootsim
