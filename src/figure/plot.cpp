// Plots with cairo: one drawing routine, three surfaces (PDF, SVG, and a PNG image rasterised from it).
#include "rootsim/plot.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/number_text.hpp"
#include "rootsim/png_encode.hpp"
#include "rootsim/units.hpp"
#include "rootsim/write_rule.hpp"

namespace fs = std::filesystem;

namespace rootsim {

Rgb paletteColor(int i) {
  static const Rgb c[] = {{0.000, 0.447, 0.698}, {0.835, 0.369, 0.000}, {0.000, 0.620, 0.451},
                          {0.800, 0.475, 0.655}, {0.902, 0.624, 0.000}, {0.337, 0.706, 0.914},
                          {0.941, 0.894, 0.259}, {0.0, 0.0, 0.0}};
  return c[((i % 8) + 8) % 8];
}

namespace {

// "nice" tick positions covering [lo, hi]
std::vector<double> ticks(double lo, double hi, int target = 6) {
  std::vector<double> t;
  if (!(hi > lo)) return t;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * mag >= raw) { step = m * mag; break; }
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
    t.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  return t;
}

// ticks of a log axis over [lo, hi] (lo > 0): 1, 2, 5 per decade
std::vector<double> logTicks(double lo, double hi) {
  std::vector<double> t;
  if (!(hi > lo) || !(lo > 0)) return t;
  for (int e = static_cast<int>(std::floor(std::log10(lo))) - 1; e <= static_cast<int>(std::ceil(std::log10(hi))); ++e)
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, e);
      if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) t.push_back(v);
    }
  return t;
}


struct Box { double x, y, w, h; };

// layout of one axes inside its cell [layout units]
constexpr double kLeft = 64, kRight = 14, kTop = 12, kTopTitle = 32, kBottom = 46, kFigureTitle = 34;
constexpr double kFigureTitleSize = 17, kFigureTitleLine = 22;  // the figure title's font and line pitch
// the physical layout (SaveOptions::widthMm; docs/rendering.md, Figure panels): a
// layout unit is kPtPerUnit points, so the 12-unit tick labels are 7 pt, axis labels 7.6 pt, titles
// 8.75 pt; sub- and superscripts no smaller than kScriptMinPt
constexpr double kPtPerUnit = 7.0 / 12.0;
constexpr double kScriptMinPt = 6;
constexpr double kInnerLeft = 10;   // left margin of a tile that shares its row's y axis [layout units]
constexpr double kMinPlotMm = 12;   // narrowest plot area before a row of tiles wraps into more rows [mm]
constexpr double kMinPlotAspect = 0.45;  // height / width of a plot's area at least (not for pictures)
// a legend entry: its swatch (a line, marker or patch) and the label after it, and the gap to the next
// entry in a row; the room kept between the legend's box and anything drawn in the plot area; how far a
// marker reaches from its point (4.5 units, 1.3 of it for a diamond, with half its 1.6-unit outline)
constexpr double kLegendSwatch = 38, kLegendGap = 14, kLegendClear = 2, kMarkerReach = 1.3 * 4.5 + 0.8;

// a cairo context and the smallest size of sub- and superscripts on it [layout units]
struct Pen {
  cairo_t* cr;
  double scriptMin = 0;
};

// a label as runs of text at three levels (0 base, -1 subscript, +1 superscript): _{..} and ^{..}
struct Run { std::string s; int level; };
std::vector<Run> parseLabel(const std::string& s) {
  std::vector<Run> out;
  auto push = [&](std::string t, int level) {
    if (t.empty()) return;
    if (!out.empty() && out.back().level == level) out.back().s += t;
    else out.push_back({std::move(t), level});
  };
  std::string cur;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 1 < s.size() && (s[i + 1] == '_' || s[i + 1] == '^' || s[i + 1] == '\\')) {
      cur += s[++i];  // an escaped _, ^ or backslash: itself
      continue;
    }
    if ((s[i] == '_' || s[i] == '^') && i + 1 < s.size()) {
      const int level = s[i] == '_' ? -1 : 1;
      std::string inner;
      size_t j = i + 1;
      if (s[j] == '{') {
        const size_t close = s.find('}', j);
        if (close == std::string::npos) { cur += s[i]; continue; }
        inner = s.substr(j + 1, close - j - 1);
        j = close;
      } else {
        // one character (a whole UTF-8 sequence)
        size_t k = j + 1;
        while (k < s.size() && (static_cast<unsigned char>(s[k]) & 0xC0) == 0x80) ++k;
        inner = s.substr(j, k - j);
        j = k - 1;
      }
      push(cur, 0);
      cur.clear();
      push(inner, level);
      i = j;
      continue;
    }
    cur += s[i];
  }
  push(cur, 0);
  return out;
}

void setFont(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

constexpr double kScriptScale = 0.7;
// a label's runs placed on a cairo context (label markup: plot.hpp)
LabelLayout placeLabel(cairo_t* cr, const std::string& s, double size, bool bold, double scriptMin) {
  LabelLayout out;
  double pen = 0;
  double prevAdvance = 0;  // advance of the run before
  for (const Run& r : parseLabel(s)) {
    const double sz = r.level ? std::max(kScriptScale * size, scriptMin) : size;
    setFont(cr, sz, bold);
    cairo_text_extents_t e;
    cairo_text_extents(cr, r.s.c_str(), &e);
    const double shift = r.level < 0 ? 0.22 * size : r.level > 0 ? -0.38 * size : 0.0;
    // a subscript right after a superscript (or the other way round) stacks on it, as in κ_f^0: both
    // start at the same x, and the pen moves on by the wider of the two
    const bool stacks = r.level != 0 && !out.runs.empty() && out.runs.back().level == -r.level &&
                        (out.runs.size() < 2 || out.runs[out.runs.size() - 2].level != r.level ||
                         out.runs[out.runs.size() - 2].x != out.runs.back().x);
    if (stacks) {
      const double x = out.runs.back().x;
      out.runs.push_back({r.s, x, shift, sz, r.level});
      pen = x + std::max(prevAdvance, e.x_advance);
    } else {
      out.runs.push_back({r.s, pen, shift, sz, r.level});
      pen += e.x_advance;
    }
    prevAdvance = e.x_advance;
  }
  out.width = pen;
  return out;
}

// advance width of a label with its markup
double labelWidth(const Pen& p, const std::string& s, double size, bool bold = false) {
  return placeLabel(p.cr, s, size, bold, p.scriptMin).width;
}

// a label anchored at (x, y): ax, ay in 0..1 of its width and of its cap height (0: left / top)
void text(const Pen& p, double x, double y, const std::string& s, double size, double ax, double ay,
          bool bold = false, double angle = 0) {
  if (s.empty()) return;
  cairo_t* cr = p.cr;
  const LabelLayout lay = placeLabel(cr, s, size, bold, p.scriptMin);
  const double capH = 0.73 * size;  // DejaVu Sans cap height
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, angle);
  const double x0 = -ax * lay.width, base = (1 - ay) * capH;
  for (const LabelRun& r : lay.runs) {
    setFont(cr, r.size, bold);
    cairo_move_to(cr, x0 + r.x, base + r.y);
    cairo_show_text(cr, r.text.c_str());
  }
  cairo_restore(cr);
}

void marker(cairo_t* cr, char m, double x, double y, double r) {
  switch (m) {
    case 's': cairo_rectangle(cr, x - r, y - r, 2 * r, 2 * r); cairo_fill(cr); break;
    case '^':
      cairo_move_to(cr, x, y - 1.2 * r); cairo_line_to(cr, x + r, y + 0.8 * r); cairo_line_to(cr, x - r, y + 0.8 * r);
      cairo_close_path(cr); cairo_fill(cr); break;
    case '>':
      cairo_move_to(cr, x + 1.2 * r, y); cairo_line_to(cr, x - 0.8 * r, y + r); cairo_line_to(cr, x - 0.8 * r, y - r);
      cairo_close_path(cr); cairo_fill(cr); break;
    case 'D':
      cairo_move_to(cr, x, y - 1.3 * r); cairo_line_to(cr, x + r, y); cairo_line_to(cr, x, y + 1.3 * r);
      cairo_line_to(cr, x - r, y); cairo_close_path(cr); cairo_fill(cr); break;
    case 'x':
      cairo_move_to(cr, x - r, y - r); cairo_line_to(cr, x + r, y + r);
      cairo_move_to(cr, x - r, y + r); cairo_line_to(cr, x + r, y - r); cairo_stroke(cr); break;
    default: cairo_arc(cr, x, y, r, 0, 2 * units::pi); cairo_fill(cr);
  }
}

// a path along the tube between nodes i0..i1 at lateral offsets u0(i), u1(i) (units of r): forward along
// u0, back along u1
template <class FX, class FY, class U0, class U1>
void strip(cairo_t* cr, const Tube& t, size_t i0, size_t i1, FX X, FY Y, U0 u0, U1 u1) {
  for (size_t i = i0; i <= i1; ++i) {
    const double u = u0(i) * t.r[i];
    (i == i0 ? cairo_move_to : cairo_line_to)(cr, X(t.x[i] + u * t.sx[i]), Y(t.y[i] + u * t.sy[i]));
  }
  for (size_t i = i1 + 1; i-- > i0;) {
    const double u = u1(i) * t.r[i];
    cairo_line_to(cr, X(t.x[i] + u * t.sx[i]), Y(t.y[i] + u * t.sy[i]));
  }
  cairo_close_path(cr);
}

Rgb mixRgb(const Rgb& c, const Rgb& d, double f) {
  return {c[0] + f * (d[0] - c[0]), c[1] + f * (d[1] - c[1]), c[2] + f * (d[2] - c[2])};
}

// a tube seen from above, lowest first (a coil's upper strand covers the lower): the tube is cut into
// pieces of a few elements, each piece gets a layer (its mean height in radii, rounded: a strand lying on
// the plate is one layer, a strand crossing over it one higher), and consecutive pieces of one layer are
// drawn as one run: the body in nested shading bands (darker at the flanks), each band one path over the
// whole run, then the visible stripes and the flanks' outline; the tip's cap closes the last run. Drawing
// a band piece by piece would leave antialiasing seams across the tube where pieces meet (each edge
// pixel covered twice by half: the plate shows through); a run that follows another starts one node
// back, under the other's end, so the plate does not show through there either.
template <class FX, class FY>
void drawTube(cairo_t* cr, const Tube& t, FX X, FY Y, double unit) {
  const size_t n = t.x.size();
  if (n < 2 || t.y.size() != n || t.r.size() != n || t.sx.size() != n || t.sy.size() != n) return;
  const bool haveZ = t.z.size() == n, haveStripes = t.plus.size() == n && t.minus.size() == n;
  constexpr size_t kPiece = 4;  // elements per piece
  struct Piece {
    size_t i0, i1;
    long layer;
  };
  std::vector<Piece> pieces;
  for (size_t i = 0; i + 1 < n; i += kPiece) {
    const size_t i1 = std::min(n - 1, i + kPiece);
    long layer = 0;
    if (haveZ) {
      double h = 0, r = 0;
      for (size_t k = i; k <= i1; ++k) {
        h += t.z[k];
        r += t.r[k];
      }
      layer = r > 0 ? std::lround(h / r) : 0;
    }
    pieces.push_back({i, i1, layer});
  }
  std::stable_sort(pieces.begin(), pieces.end(), [](const Piece& p, const Piece& q) { return p.layer < q.layer; });
  std::vector<std::pair<size_t, size_t>> runs;
  for (size_t k = 0; k < pieces.size(); ++k) {
    if (k > 0 && pieces[k].layer == pieces[k - 1].layer && pieces[k].i0 == pieces[k - 1].i1) runs.back().second = pieces[k].i1;
    else runs.push_back({pieces[k].i0, pieces[k].i1});
  }
  const Rgb outline = mixRgb(t.body, {0, 0, 0}, 0.62);
  // shading bands: half widths (units of r) and their colour, outermost (darkest) first
  const double bands[] = {1.0, 0.82, 0.58, 0.3};
  const double shade[] = {0.34, 0.18, 0.07, 0.0};
  const double lw = std::max(0.6, 0.08 * unit * t.r[0]);
  for (auto [i0, i1] : runs) {
    if (i0 > 0) --i0;  // under the end of the run before
    const bool tip = i1 == n - 1;
    for (int b = 0; b < 4; ++b) {
      const Rgb c = mixRgb(t.body, {0.35, 0.3, 0.22}, shade[b]);
      cairo_set_source_rgb(cr, c[0], c[1], c[2]);
      const double h = bands[b];
      strip(cr, t, i0, i1, X, Y, [&](size_t) { return -h; }, [&](size_t) { return h; });
      cairo_fill(cr);
      if (tip) {  // the cap: a disc of the band's width at the tip (its edge inside the band or on its edge)
        cairo_arc(cr, X(t.x[n - 1]), Y(t.y[n - 1]), h * t.r[n - 1] * unit, 0, 2 * units::pi);
        cairo_fill(cr);
      }
    }
    if (haveStripes) {
      for (int k = 0; k < 2; ++k) {
        const auto& sp = k ? t.minus : t.plus;
        const Rgb& c = k ? t.minusColor : t.plusColor;
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        // runs of nodes where the stripe is seen
        size_t i = i0;
        while (i <= i1) {
          while (i <= i1 && !std::isfinite(sp[i][0])) ++i;
          size_t j = i;
          while (j + 1 <= i1 && std::isfinite(sp[j + 1][0])) ++j;
          if (i <= i1 && j > i) {
            strip(cr, t, i, j, X, Y, [&](size_t m) { return sp[m][0]; }, [&](size_t m) { return sp[m][1]; });
            cairo_fill(cr);
          }
          i = j + 1;
        }
      }
    }
    cairo_set_source_rgb(cr, outline[0], outline[1], outline[2]);
    cairo_set_line_width(cr, lw);
    for (double side : {-1.0, 1.0}) {
      for (size_t i = i0; i <= i1; ++i) {
        const double u = side * t.r[i];
        (i == i0 ? cairo_move_to : cairo_line_to)(cr, X(t.x[i] + u * t.sx[i]), Y(t.y[i] + u * t.sy[i]));
      }
      cairo_stroke(cr);
    }
    if (tip) {
      // the cap's outline: the half circle ahead of the tip
      const double dx = X(t.x[n - 1]) - X(t.x[n - 2]), dy = Y(t.y[n - 1]) - Y(t.y[n - 2]);
      const double ang = std::atan2(dy, dx);
      cairo_new_sub_path(cr);
      cairo_arc(cr, X(t.x[n - 1]), Y(t.y[n - 1]), t.r[n - 1] * unit, ang - 0.5 * units::pi, ang + 0.5 * units::pi);
      cairo_stroke(cr);
    }
  }
}

// an axes' place in the figure: its cell, the cell's left margin (kLeft, or kInnerLeft for a tile that
// shares its row's y axis) and whether it labels its y ticks
struct Cell {
  Box box;
  double left = kLeft;
  bool yTickLabels = true;
  // the x label: its own (centred under its plot), none, or the row's one label centred over
  // [rowX0, rowX1] (a row sharing its y axis whose equal x labels would crowd each other)
  bool xLabel = true;
  bool rowLabel = false;
  double rowX0 = 0, rowX1 = 0;
  // the legend's box (w = 0: none), inside the plot area or under the axes; the room kept under the
  // axes for it (0 when inside)
  Box legend{0, 0, 0, 0};
  bool legendInside = true;
  double legendBelow = 0;
};

// about one tick label per `pitch` layout units of the axis, between lo and hi labels
int tickTarget(double length, double pitch, int lo, int hi) {
  return std::clamp(static_cast<int>(length / pitch), lo, hi);
}

// an axes' plot area [layout units] and data range, and the map from data to layout units
struct Geo {
  double L = 0, R = 0, T = 0, B = 0;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  bool logX = false, yDown = false;
  double X(double x) const {
    return logX ? L + std::log(x / x0) / std::log(x1 / x0) * (R - L) : L + (x - x0) / (x1 - x0) * (R - L);
  }
  double Y(double y) const { return yDown ? T + (y - y0) / (y1 - y0) * (B - T) : B - (y - y0) / (y1 - y0) * (B - T); }
  double unit() const { return (R - L) / (x1 - x0); }  // layout units per data unit along x
};

Geo geometryOf(const Axes& a, const Cell& cell) {
  const Box box = cell.box;
  // data range
  double x0 = a.xmin, x1 = a.xmax, y0 = a.ymin, y1 = a.ymax;
  if (a.autoX || a.autoY) {
    double lx = std::numeric_limits<double>::infinity(), hx = -lx, ly = lx, hy = -lx;
    auto see = [&](double x, double y) {
      if (!std::isfinite(x) || !std::isfinite(y)) return;
      lx = std::min(lx, x); hx = std::max(hx, x); ly = std::min(ly, y); hy = std::max(hy, y);
    };
    for (const auto& s : a.series) for (size_t i = 0; i < s.x.size(); ++i) see(s.x[i], s.y[i]);
    for (const auto& s : a.shapes) for (size_t i = 0; i < s.x.size(); ++i) see(s.x[i], s.y[i]);
    for (const auto& s : a.tubes) for (size_t i = 0; i < s.x.size(); ++i) see(s.x[i], s.y[i]);
    if (!std::isfinite(lx)) { lx = 0; hx = 1; ly = 0; hy = 1; }
    if (hx - lx < 1e-12) { lx -= 0.5; hx += 0.5; }
    if (hy - ly < 1e-12) { ly -= 0.5; hy += 0.5; }
    const double px = 0.04 * (hx - lx), py = 0.06 * (hy - ly);
    if (a.autoX && a.logX && lx > 0) { x0 = lx / 1.25; x1 = hx * 1.25; }
    else if (a.autoX) { x0 = lx - px; x1 = hx + px; }
    if (a.autoY) { y0 = ly - py; y1 = hy + py; }
  }
  Geo g;
  g.L = box.x + cell.left;
  g.R = box.x + box.w - kRight;
  g.T = box.y + (a.title.empty() ? kTop : kTopTitle);
  g.B = box.y + box.h - kBottom - cell.legendBelow;
  const double pw = g.R - g.L, ph = g.B - g.T;
  if (a.equalAspect) {
    // widen the smaller range so one data unit has the same length on both axes
    const double sx = pw / (x1 - x0), sy = ph / (y1 - y0);
    if (sx > sy) { const double c = 0.5 * (x0 + x1), h = 0.5 * pw / sy; x0 = c - h; x1 = c + h; }
    else { const double c = 0.5 * (y0 + y1), h = 0.5 * ph / sx; y0 = c - h; y1 = c + h; }
  }
  g.x0 = x0, g.x1 = x1, g.y0 = y0, g.y1 = y1;
  g.logX = a.logX && x0 > 0 && x1 > x0;
  g.yDown = a.yDown;
  return g;
}

// a note's box: 12 units high, its width, kept inside the plot area clear of the frame's lines
Box noteBox(const Pen& p, const Geo& g, const std::array<double, 2>& at, const std::string& s) {
  const double hw = 0.5 * labelWidth(p, s, 12) + 2, hh = 0.5 * 12 * 1.164 + 2;
  const double pw = g.R - g.L, ph = g.B - g.T;
  const double cx = hw < 0.5 * pw ? std::clamp(g.X(at[0]), g.L + hw, g.R - hw) : g.X(at[0]);
  const double cy = hh < 0.5 * ph ? std::clamp(g.Y(at[1]), g.T + hh, g.B - hh) : g.Y(at[1]);
  return {cx - hw, cy - hh, 2 * hw, 2 * hh};
}

// the legend's entries (series, then fills, with a label) and their widths
struct LegendEntries {
  int n = 0;
  double widest = 0;             // the widest label [layout units]
  std::vector<double> widths;    // each entry's swatch + label + gap, for a legend in rows
};
LegendEntries legendEntries(const Pen& p, const Axes& a) {
  LegendEntries e;
  if (a.legendPos == "none") return e;
  auto add = [&](const std::string& label) {
    if (label.empty()) return;
    const double w = labelWidth(p, label, 12);
    ++e.n;
    e.widest = std::max(e.widest, w);
    e.widths.push_back(kLegendSwatch + w + kLegendGap);
  };
  for (const auto& s : a.series) add(s.label);
  for (const auto& fl : a.fills) add(fl.label);
  return e;
}

// distance from the segment a-b to the rectangle r (0 where they meet)
double segmentToBox(double ax, double ay, double bx, double by, const Box& r) {
  auto inBox = [&](double x, double y) { return x >= r.x && x <= r.x + r.w && y >= r.y && y <= r.y + r.h; };
  if (inBox(ax, ay) || inBox(bx, by)) return 0;
  // the segment crosses the rectangle: clip it to the box's slab in x, then in y (Liang-Barsky)
  double t0 = 0, t1 = 1;
  const double dx = bx - ax, dy = by - ay;
  auto clip = [&](double pp, double q) {
    if (pp == 0) return q >= 0;
    const double t = q / pp;
    if (pp < 0) { if (t > t1) return false; t0 = std::max(t0, t); }
    else { if (t < t0) return false; t1 = std::min(t1, t); }
    return true;
  };
  if (clip(-dx, ax - r.x) && clip(dx, r.x + r.w - ax) && clip(-dy, ay - r.y) && clip(dy, r.y + r.h - ay) && t0 <= t1)
    return 0;
  auto pointToBox = [&](double x, double y) {
    const double ex = std::max({r.x - x, 0.0, x - r.x - r.w}), ey = std::max({r.y - y, 0.0, y - r.y - r.h});
    return std::hypot(ex, ey);
  };
  auto pointToSegment = [&](double x, double y) {
    const double l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / l2, 0.0, 1.0) : 0.0;
    return std::hypot(ax + t * dx - x, ay + t * dy - y);
  };
  return std::min({pointToBox(ax, ay), pointToBox(bx, by), pointToSegment(r.x, r.y), pointToSegment(r.x + r.w, r.y),
                   pointToSegment(r.x, r.y + r.h), pointToSegment(r.x + r.w, r.y + r.h)});
}

// whether a legend box inside the plot area stays kLegendClear units off everything the axes draw in
// it: each series' line (half its width) and markers, each tube (its radius), each shape (half its
// width) and each note's box
bool legendClear(const Pen& p, const Axes& a, const Geo& g, const Box& box) {
  const double unit = g.unit();
  auto off = [&](double ax, double ay, double bx, double by, double half) {
    return segmentToBox(ax, ay, bx, by, box) > half + kLegendClear;
  };
  auto finite = [](double x, double y) { return std::isfinite(x) && std::isfinite(y); };
  for (const auto& s : a.series) {
    const bool lines = s.kind != Series::Kind::Markers, marks = s.kind != Series::Kind::Line;
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!finite(s.x[i], s.y[i])) continue;
      const double ax = g.X(s.x[i]), ay = g.Y(s.y[i]);
      if (marks && !off(ax, ay, ax, ay, kMarkerReach)) return false;
      if (lines && i + 1 < s.x.size() && finite(s.x[i + 1], s.y[i + 1]) &&
          !off(ax, ay, g.X(s.x[i + 1]), g.Y(s.y[i + 1]), 0.5 * s.width))
        return false;
      if (lines && s.x.size() == 1 && !off(ax, ay, ax, ay, 0.5 * s.width)) return false;
    }
  }
  for (const auto& t : a.tubes)
    for (size_t i = 0; i + 1 < t.x.size(); ++i)
      if (!off(g.X(t.x[i]), g.Y(t.y[i]), g.X(t.x[i + 1]), g.Y(t.y[i + 1]), std::max(t.r[i], t.r[i + 1]) * unit)) return false;
  for (const auto& s : a.shapes)
    for (size_t i = 0; i + 1 < s.x.size(); ++i)
      if (!off(g.X(s.x[i]), g.Y(s.y[i]), g.X(s.x[i + 1]), g.Y(s.y[i + 1]), 0.5 * std::max(1.0, s.width * unit))) return false;
  for (const auto& [at, s] : a.notes) {
    const Box nb = noteBox(p, g, at, s);
    const double ox = std::min(nb.x + nb.w, box.x + box.w) - std::max(nb.x, box.x);
    const double oy = std::min(nb.y + nb.h, box.y + box.h) - std::max(nb.y, box.y);
    if (ox > -kLegendClear && oy > -kLegendClear) return false;
  }
  return true;
}

// a place for the legend inside the plot area g: the corner asked for (Axes::legendPos) when nothing drawn
// in the plot area comes within kLegendClear of it; else the other corners, the edges' middles, then
// every place on a grid of about 4 units, nearest the asked corner first; none when every place meets a
// curve (the legend then goes under the axes: legendBelowHeight)
std::optional<Box> legendInside(const Pen& p, const Axes& a, const Geo& g, const LegendEntries& e) {
  const double bw = e.widest + kLegendSwatch + 6, bh = 18.0 * e.n + 8;
  const double lo_x = g.L + 8, hi_x = g.R - bw - 8, lo_y = g.T + 8, hi_y = g.B - bh - 8;
  if (hi_x < lo_x || hi_y < lo_y) return std::nullopt;
  auto corner = [&](const std::string& c) {
    const double x = c[1] == 'w' ? lo_x : c[1] == 'e' ? hi_x : 0.5 * (lo_x + hi_x);
    const double y = c[0] == 'n' ? lo_y : c[0] == 's' ? hi_y : 0.5 * (lo_y + hi_y);
    return Box{x, y, bw, bh};
  };
  const std::string asked = a.legendPos.size() == 2 ? a.legendPos : "ne";
  std::vector<Box> order{corner(asked)};
  for (const char* c : {"ne", "nw", "se", "sw", "ce", "cw", "nc", "sc"})
    if (c != asked) order.push_back(corner(c));
  const Box home = order.front();
  std::vector<Box> grid;
  const int nx = static_cast<int>((hi_x - lo_x) / 4), ny = static_cast<int>((hi_y - lo_y) / 4);
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) grid.push_back({lo_x + (hi_x - lo_x) * (nx ? static_cast<double>(i) / nx : 0), lo_y + (hi_y - lo_y) * (ny ? static_cast<double>(j) / ny : 0), bw, bh});
  std::stable_sort(grid.begin(), grid.end(), [&](const Box& u, const Box& v) {
    return std::hypot(u.x - home.x, u.y - home.y) < std::hypot(v.x - home.x, v.y - home.y);
  });
  order.insert(order.end(), grid.begin(), grid.end());
  for (const Box& b : order)
    if (legendClear(p, a, g, b)) return b;
  return std::nullopt;
}

// a legend under the axes (below the x label): its entries in rows no wider than the plot area, each
// row as many entries as fit; the rows' count
int legendRows(const LegendEntries& e, double width) {
  int rows = e.n > 0 ? 1 : 0;
  double x = 0;
  for (double w : e.widths) {
    if (x > 0 && x + w > width) { ++rows; x = 0; }
    x += w;
  }
  return rows;
}
double legendBelowHeight(const LegendEntries& e, double width) { return e.n > 0 ? 18.0 * legendRows(e, width) + 8 + 4 : 0; }

// the room a legend needs under the axes in this cell: 0 when a place inside its plot area is free
double legendRoom(const Pen& p, const Axes& a, Cell cell) {
  const LegendEntries e = legendEntries(p, a);
  if (e.n == 0) return 0;
  cell.legendBelow = 0;
  const Geo g = geometryOf(a, cell);
  return legendInside(p, a, g, e) ? 0 : legendBelowHeight(e, g.R - g.L);
}

// the legend's box in a cell whose room under the axes is set: inside the plot area where a place is
// free, else under the axes (below the x label), its rows centred under the plot area
void placeLegend(const Pen& p, const Axes& a, Cell& cell) {
  cell.legend = Box{0, 0, 0, 0};
  cell.legendInside = true;
  const LegendEntries e = legendEntries(p, a);
  if (e.n == 0) return;
  const Geo g = geometryOf(a, cell);
  if (const auto in = legendInside(p, a, g, e)) {
    cell.legend = *in;
    return;
  }
  const double width = g.R - g.L;
  double widest = 0, x = 0;
  for (double w : e.widths) {
    if (x > 0 && x + w > width) x = 0;
    x += w;
    widest = std::max(widest, x);
  }
  cell.legendInside = false;
  cell.legend = Box{0.5 * (g.L + g.R - widest), g.B + kBottom, widest, 18.0 * legendRows(e, width) + 8};
}

// the axes' frame: the white plot area, grid lines and ticks with their labels, the frame, the title,
// the panel label and the axis labels
void drawFrame(const Pen& p, const Axes& a, const Cell& cell, const Geo& g) {
  cairo_t* cr = p.cr;
  const double L = g.L, R = g.R, T = g.T, B = g.B;
  const double pw = R - L, ph = B - T;
  auto X = [&](double x) { return g.X(x); };
  auto Y = [&](double y) { return g.Y(y); };
  const Box box = cell.box;

  // frame, grid, ticks
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_rectangle(cr, L, T, pw, ph);
  cairo_fill(cr);
  const auto xt = a.frameOnly ? std::vector<double>{} : g.logX ? logTicks(g.x0, g.x1) : ticks(g.x0, g.x1, tickTarget(pw, 40, 2, 6));
  const auto yt = a.frameOnly ? std::vector<double>{} : ticks(g.y0, g.y1, tickTarget(ph, 36, 3, 5));
  cairo_set_line_width(cr, 0.8);
  if (a.xCategories.empty()) {
    for (double v : xt) {
      if (a.grid) { cairo_set_source_rgb(cr, 0.9, 0.9, 0.9); cairo_move_to(cr, X(v), T); cairo_line_to(cr, X(v), B); cairo_stroke(cr); }
      cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
      cairo_move_to(cr, X(v), B); cairo_line_to(cr, X(v), B + 5); cairo_stroke(cr);
      text(p, X(v), B + 8, significantText(v), 12, 0.5, 0.0);
    }
  } else {
    // categories: a tick and the name at each one's position
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    for (const auto& c : a.xCategories) {
      if (c.first < std::min(g.x0, g.x1) || c.first > std::max(g.x0, g.x1)) continue;
      cairo_move_to(cr, X(c.first), B); cairo_line_to(cr, X(c.first), B + 5); cairo_stroke(cr);
      text(p, X(c.first), B + 8, c.second, 12, 0.5, 0.0);
    }
  }
  for (double v : yt) {
    if (a.grid) { cairo_set_source_rgb(cr, 0.9, 0.9, 0.9); cairo_move_to(cr, L, Y(v)); cairo_line_to(cr, R, Y(v)); cairo_stroke(cr); }
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_move_to(cr, L - 5, Y(v)); cairo_line_to(cr, L, Y(v)); cairo_stroke(cr);
    if (cell.yTickLabels) text(p, L - 8, Y(v), significantText(v), 12, 1.0, 0.5);
  }
  cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
  cairo_set_line_width(cr, 1.2);
  cairo_rectangle(cr, L, T, pw, ph);
  cairo_stroke(cr);
  if (!a.title.empty()) text(p, 0.5 * (L + R), box.y + 8, a.title, 15, 0.5, 0.0, true);
  if (!a.panelLabel.empty()) text(p, box.x + 8, box.y + 6, a.panelLabel, 20, 0.0, 0.0, true);
  if (cell.xLabel) text(p, cell.rowLabel ? 0.5 * (cell.rowX0 + cell.rowX1) : 0.5 * (L + R), B + 26, a.xlabel, 13, 0.5, 0.0);
  text(p, box.x + 14, 0.5 * (T + B), a.ylabel, 13, 0.5, 0.5, false, -units::pi / 2);
}

// the axes' data, clipped to the plot area: fills, the plate's grid, obstacles, shapes, tubes, series
// (lines and markers) and notes
void drawData(const Pen& p, const Axes& a, const Geo& g) {
  cairo_t* cr = p.cr;
  const double L = g.L, R = g.R, T = g.T, B = g.B;
  const double x0 = g.x0, x1 = g.x1, y0 = g.y0, y1 = g.y1;
  const double pw = R - L, ph = B - T;
  auto X = [&](double x) { return g.X(x); };
  auto Y = [&](double y) { return g.Y(y); };
  const double unit = g.unit();  // layout units per data unit along x

  cairo_save(cr);
  cairo_rectangle(cr, L, T, pw, ph);
  cairo_clip(cr);
  for (const auto& fl : a.fills) {
    cairo_set_source_rgba(cr, fl.color[0], fl.color[1], fl.color[2], fl.alpha);
    for (size_t i = 0; i < fl.x.size(); ++i) (i ? cairo_line_to : cairo_move_to)(cr, X(fl.x[i]), Y(fl.y[i]));
    cairo_close_path(cr);
    cairo_fill(cr);
  }
  if (a.plateGridPitch > 0) {
    // the plate's grid (as the raster renderer's plate, docs/rendering.md): light lines every pitch
    const double pitch = a.plateGridPitch;
    const double lo = std::min(y0, y1), hi = std::max(y0, y1);
    if ((x1 - x0) / pitch < 2000 && (hi - lo) / pitch < 2000) {
      cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
      cairo_set_line_width(cr, 0.7);
      for (double v = std::ceil(x0 / pitch) * pitch; v <= x1; v += pitch) { cairo_move_to(cr, X(v), T); cairo_line_to(cr, X(v), B); }
      for (double v = std::ceil(lo / pitch) * pitch; v <= hi; v += pitch) { cairo_move_to(cr, L, Y(v)); cairo_line_to(cr, R, Y(v)); }
      cairo_stroke(cr);
    }
  }
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const auto& o : a.obstacles) {
    // the capsule (or disc) filled, then its outline a darker shade
    const double rr = o.r * unit;
    const double dx = X(o.toX) - X(o.fromX), dy = Y(o.toY) - Y(o.fromY);
    const double ang = std::atan2(dy, dx);
    cairo_new_sub_path(cr);
    cairo_arc(cr, X(o.toX), Y(o.toY), rr, ang - 0.5 * units::pi, ang + 0.5 * units::pi);
    cairo_arc(cr, X(o.fromX), Y(o.fromY), rr, ang + 0.5 * units::pi, ang + 1.5 * units::pi);
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, o.color[0], o.color[1], o.color[2]);
    cairo_fill_preserve(cr);
    const Rgb edge = mixRgb(o.color, {0, 0, 0}, 0.45);
    cairo_set_source_rgb(cr, edge[0], edge[1], edge[2]);
    cairo_set_line_width(cr, 0.8);
    cairo_stroke(cr);
  }
  for (const auto& s : a.shapes) {
    cairo_set_source_rgb(cr, s.color[0], s.color[1], s.color[2]);
    cairo_set_line_width(cr, std::max(1.0, s.width * unit));
    for (size_t i = 0; i < s.x.size(); ++i) (i ? cairo_line_to : cairo_move_to)(cr, X(s.x[i]), Y(s.y[i]));
    cairo_stroke(cr);
  }
  for (const auto& tb : a.tubes) drawTube(cr, tb, X, Y, unit);
  for (const auto& s : a.series) {
    cairo_set_source_rgb(cr, s.color[0], s.color[1], s.color[2]);
    cairo_set_line_width(cr, s.width);
    if (s.dashed) { const double d[] = {6, 4}; cairo_set_dash(cr, d, 2, 0); }
    if (s.kind != Series::Kind::Markers) {
      bool pen = false;
      for (size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) { pen = false; continue; }
        (pen ? cairo_line_to : cairo_move_to)(cr, X(s.x[i]), Y(s.y[i]));
        pen = true;
      }
      cairo_stroke(cr);
    }
    cairo_set_dash(cr, nullptr, 0, 0);
    if (s.kind != Series::Kind::Line) {
      cairo_set_line_width(cr, 1.6);
      for (size_t i = 0; i < s.x.size(); ++i)
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) marker(cr, s.marker, X(s.x[i]), Y(s.y[i]), 4.5);
    }
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  for (const auto& [at, s] : a.notes) {
    // a note stays inside the frame: its box (12 units high, its width) clear of the frame's lines
    const Box nb = noteBox(p, g, at, s);
    text(p, nb.x + 0.5 * nb.w, nb.y + 0.5 * nb.h, s, 12, 0.5, 0.5);
  }
  cairo_restore(cr);
}

// the legend: at the place the layout chose (Cell::legend), inside the plot area or in rows under the axes
void drawLegend(const Pen& p, const Axes& a, const Cell& cell) {
  cairo_t* cr = p.cr;
  if (cell.legend.w > 0) {
    const double lx = cell.legend.x, ly = cell.legend.y, bw = cell.legend.w, bh = cell.legend.h;
    cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
    cairo_rectangle(cr, lx, ly, bw, bh);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
    cairo_set_line_width(cr, 0.8);
    cairo_stroke(cr);
    // each entry's swatch and label: one per line inside, or left to right in rows under the axes
    double ex = lx, ey = ly + 13;
    auto next = [&](const std::string& label) {
      if (!cell.legendInside) {
        const double w = kLegendSwatch + labelWidth(p, label, 12) + kLegendGap;
        if (ex > lx && ex + w > lx + bw) { ex = lx; ey += 18; }
      }
      const std::array<double, 2> at{ex, ey};
      if (cell.legendInside) ey += 18;
      else ex += kLegendSwatch + labelWidth(p, label, 12) + kLegendGap;
      return at;
    };
    for (const auto& s : a.series) {
      if (s.label.empty()) continue;
      const auto [ex0, yy] = next(s.label);
      cairo_set_source_rgb(cr, s.color[0], s.color[1], s.color[2]);
      if (s.kind != Series::Kind::Markers) {
        cairo_set_line_width(cr, s.width);
        if (s.dashed) { const double d[] = {6, 4}; cairo_set_dash(cr, d, 2, 0); }
        cairo_move_to(cr, ex0 + 6, yy); cairo_line_to(cr, ex0 + 32, yy); cairo_stroke(cr);
        cairo_set_dash(cr, nullptr, 0, 0);
      }
      if (s.kind != Series::Kind::Line) marker(cr, s.marker, ex0 + 19, yy, 4.5);
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      text(p, ex0 + kLegendSwatch, yy, s.label, 12, 0.0, 0.5);
    }
    for (const auto& fl : a.fills) {
      if (fl.label.empty()) continue;
      const auto [ex0, yy] = next(fl.label);
      cairo_set_source_rgba(cr, fl.color[0], fl.color[1], fl.color[2], std::max(fl.alpha, 0.6));
      cairo_rectangle(cr, ex0 + 8, yy - 6, 22, 12);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      text(p, ex0 + kLegendSwatch, yy, fl.label, 12, 0.0, 0.5);
    }
  }
}

void drawAxes(const Pen& p, const Axes& a, const Cell& cell) {
  const Geo g = geometryOf(a, cell);
  drawFrame(p, a, cell, g);
  drawData(p, a, g);
  drawLegend(p, a, cell);
}

// a figure laid out: its size [layout units], the figure title's lines and each axes' cell
struct Layout {
  double width = 0, height = 0;
  double scriptMin = 0;  // [layout units]
  std::vector<std::string> titleLines;
  std::vector<Cell> cells;
};

// the title in lines no wider than `width`, broken between its phrases (titleChunks), never inside a
// formula; a phrase wider than a line on its own is broken where titleChunks' second tier allows
std::vector<std::string> wrapTitle(const Pen& p, const std::string& title, double width) {
  std::vector<std::string> lines;
  std::string line;
  auto fits = [&](const std::string& s) { return labelWidth(p, s, kFigureTitleSize, true) <= width; };
  for (const std::string& chunk : titleChunks(title)) {
    std::vector<std::string> parts{chunk};
    if (!fits(chunk)) parts = titleChunks(chunk, true);
    for (const std::string& part : parts) {
      const std::string longer = line.empty() ? part : line + " " + part;
      if (!line.empty() && !fits(longer)) {
        lines.push_back(line);
        line = part;
      } else {
        line = longer;
      }
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

// the axes share their y axis: more than one tile in a row, each with the same fixed y range, and only
// the first with a y label (rows of roots on the plate at one scale)
bool sharesY(const Figure& f) {
  if (f.cols < 2 || f.axes.size() < 2) return false;
  const Axes& a0 = f.axes[0];
  for (size_t i = 0; i < f.axes.size(); ++i) {
    const Axes& a = f.axes[i];
    if (a.autoY || a.yDown != a0.yDown || a.ymin != a0.ymin || a.ymax != a0.ymax) return false;
    if (i > 0 && !a.ylabel.empty()) return false;
  }
  return true;
}

// widthMm 0: f's own grid on f.width x f.height. widthMm > 0: the physical layout (plot.hpp): f.width's
// grid redrawn at widthMm / 25.4 * 72 / kPtPerUnit layout units, each row as high as its plot areas at
// their aspect (plotAspect) need
Layout layoutOf(cairo_t* cr, const Figure& f, double widthMm) {
  const bool physical = widthMm > 0;
  Layout out;
  out.width = physical ? widthMm / 25.4 * 72.0 / kPtPerUnit : f.width;
  out.scriptMin = physical ? kScriptMinPt / kPtPerUnit : 0;
  const Pen p{cr, out.scriptMin};
  if (!f.title.empty()) out.titleLines = wrapTitle(p, f.title, out.width - 20);
  const double top =
      out.titleLines.empty() ? 0 : kFigureTitle + kFigureTitleLine * static_cast<double>(out.titleLines.size() - 1);
  const int n = static_cast<int>(f.axes.size());
  if (!physical) {
    out.height = f.height;
    const double cw = static_cast<double>(f.width) / f.cols, ch = (f.height - top) / static_cast<double>(f.rows);
    for (int i = 0; i < n; ++i) {
      out.cells.push_back({Box{i % f.cols * cw, top + i / f.cols * ch, cw, ch}});
      // a legend that finds no free place in the plot area takes room from it, under the axes
      Cell& cell = out.cells.back();
      cell.legendBelow = legendRoom(p, f.axes[static_cast<size_t>(i)], cell);
      placeLegend(p, f.axes[static_cast<size_t>(i)], cell);
    }
    return out;
  }
  const bool shared = sharesY(f);
  const double inner = shared ? kInnerLeft : kLeft;
  auto plotWidth = [&](int cols) { return (out.width - kLeft - (cols - 1) * inner - cols * kRight) / cols; };
  int cols = std::max(1, f.cols);
  while (cols > 1 && plotWidth(cols) * kPtPerUnit < kMinPlotMm / 25.4 * 72.0) --cols;
  const double pw = plotWidth(cols);
  double y = top;
  for (int r0 = 0; r0 < n; r0 += cols) {
    double h = 0;
    for (int i = r0; i < std::min(n, r0 + cols); ++i) {
      const Axes& a = f.axes[static_cast<size_t>(i)];
      // a plot (not a picture at one scale) at least kMinPlotAspect high: a wide default plot (Fig. 2C-E,
      // 0.27) would leave a column's plot too flat for its ticks and legend
      const double aspect = a.equalAspect ? plotAspect(f, a) : std::max(kMinPlotAspect, plotAspect(f, a));
      h = std::max(h, pw * aspect + (a.title.empty() ? kTop : kTopTitle) + kBottom);
    }
    // equal x labels in a row sharing its y axis: one under the row when side by side they would come
    // within 1 em (12 units) of each other
    const int rowEnd = std::min(n, r0 + cols);
    bool sameX = shared && rowEnd - r0 > 1 && !f.axes[static_cast<size_t>(r0)].xlabel.empty();
    for (int i = r0 + 1; i < rowEnd && sameX; ++i) sameX = f.axes[static_cast<size_t>(i)].xlabel == f.axes[static_cast<size_t>(r0)].xlabel;
    const bool rowLabel = sameX && labelWidth(p, f.axes[static_cast<size_t>(r0)].xlabel, 13) + 12 > inner + pw + kRight;
    for (int i = r0; i < rowEnd; ++i) {
      const int c = i - r0;
      const double x = c == 0 ? 0 : kLeft + pw + kRight + (c - 1) * (inner + pw + kRight);
      const double left = c == 0 ? kLeft : inner;
      out.cells.push_back({Box{x, y, left + pw + kRight, h}, left, c == 0 || !shared});
      if (rowLabel) {
        Cell& cell = out.cells.back();
        cell.xLabel = c == 0;
        cell.rowLabel = true;
        cell.rowX0 = kLeft;
        cell.rowX1 = kLeft + pw + (rowEnd - r0 - 1) * (kRight + inner + pw);
      }
    }
    // a legend that finds no free place in its plot area goes under the axes: the row grows by its room
    double extra = 0;
    for (int i = r0; i < rowEnd; ++i)
      extra = std::max(extra, legendRoom(p, f.axes[static_cast<size_t>(i)], out.cells[static_cast<size_t>(i)]));
    for (int i = r0; i < rowEnd; ++i) {
      Cell& cell = out.cells[static_cast<size_t>(i)];
      cell.box.h += extra;
      cell.legendBelow = extra;
      placeLegend(p, f.axes[static_cast<size_t>(i)], cell);
    }
    y += h + extra;
  }
  out.height = n > 0 ? y : top + f.height * out.width / f.width;
  return out;
}

void drawFigure(const Pen& p, const Figure& f, const Layout& lay) {
  cairo_t* cr = p.cr;
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  for (size_t k = 0; k < lay.titleLines.size(); ++k)
    text(p, 0.5 * lay.width, 10 + kFigureTitleLine * static_cast<double>(k), lay.titleLines[k], kFigureTitleSize, 0.5, 0.0, true);
  for (size_t i = 0; i < f.axes.size(); ++i) drawAxes(p, f.axes[i], lay.cells[i]);
}

void check(cairo_status_t st, const std::string& what) {
  if (st != CAIRO_STATUS_SUCCESS) throw RunError(what + ": cairo: " + cairo_status_to_string(st));
}

}  // namespace

double plotAspect(const Figure& f, const Axes& a) {
  const double top = f.title.empty() ? 0 : kFigureTitle;
  const double cw = static_cast<double>(f.width) / f.cols, ch = (f.height - top) / static_cast<double>(f.rows);
  const double pw = cw - kLeft - kRight, ph = ch - (a.title.empty() ? kTop : kTopTitle) - kBottom;
  return ph / pw;
}

namespace {
// the PNG of a cairo RGB24 surface: its pixels (native-endian 32-bit words 0x00RRGGBB) as RGB rows, as
// cairo's own PNG writer passes them to libpng (its settings, its white bKGD), with a pHYs chunk of dpi
std::string figurePng(cairo_surface_t* s, double dpi, std::string* why) {
  cairo_surface_flush(s);
  const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* src = cairo_image_surface_get_data(s);
  std::vector<unsigned char> rgb(static_cast<size_t>(3) * w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint32_t px = 0;
      std::memcpy(&px, src + static_cast<size_t>(y) * stride + 4 * static_cast<size_t>(x), 4);
      unsigned char* out = rgb.data() + 3 * (static_cast<size_t>(y) * w + x);
      out[0] = static_cast<unsigned char>(px >> 16);
      out[1] = static_cast<unsigned char>(px >> 8);
      out[2] = static_cast<unsigned char>(px);
    }
  PngOptions o;
  o.dpi = dpi;
  o.whiteBackground = true;
  return encodeSignedPng({rgb.data(), w, h, 3, 3 * static_cast<size_t>(w)}, o, why);
}
}  // namespace

std::vector<AxesLayout> figureLayout(const Figure& fig, const SaveOptions& so) {
  Figure f = fig;
  if (!so.titles) f.title.clear();
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
  cairo_t* cr = cairo_create(s);
  const Layout lay = layoutOf(cr, f, so.widthMm);
  cairo_destroy(cr);
  cairo_surface_destroy(s);
  const double pt = so.widthMm > 0 ? kPtPerUnit : 72.0 / 96.0;
  std::vector<AxesLayout> out;
  for (size_t i = 0; i < f.axes.size(); ++i) {
    const Cell& cell = lay.cells[i];
    const Geo g = geometryOf(f.axes[i], cell);
    AxesLayout l;
    l.plot = {g.L * pt, g.T * pt, (g.R - g.L) * pt, (g.B - g.T) * pt};
    l.legend = {cell.legend.x * pt, cell.legend.y * pt, cell.legend.w * pt, cell.legend.h * pt};
    l.legendInside = cell.legendInside;
    l.x0 = g.x0, l.x1 = g.x1, l.y0 = g.y0, l.y1 = g.y1;
    l.logX = g.logX;
    l.yDown = g.yDown;
    out.push_back(l);
  }
  return out;
}

std::array<double, 2> pagePoint(const AxesLayout& l, double x, double y) {
  const double fx = l.logX ? std::log(x / l.x0) / std::log(l.x1 / l.x0) : (x - l.x0) / (l.x1 - l.x0);
  const double fy = (y - l.y0) / (l.y1 - l.y0);
  return {l.plot[0] + fx * l.plot[2], l.yDown ? l.plot[1] + fy * l.plot[3] : l.plot[1] + (1 - fy) * l.plot[3]};
}

void saveFigure(const Figure& fig, const std::string& base, const SaveOptions& so) {
  Figure f = fig;
  if (!so.titles) f.title.clear();
  if (!(so.dpi > 0) || so.widthMm < 0) throw RunError("figure: --dpi must be positive and --width-mm not negative");
  // the layout, measured on a scratch surface (text extents do not depend on the surface)
  Layout lay;
  {
    cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t* cr = cairo_create(s);
    lay = layoutOf(cr, f, so.widthMm);
    cairo_destroy(cr);
    cairo_surface_destroy(s);
  }
  const double pt = so.widthMm > 0 ? kPtPerUnit : 72.0 / 96.0;  // points per layout unit (PDF, SVG)
  const double inches = lay.width * pt / 72.0;
  const fs::path png = base + ".png", svg = base + ".svg", pdf = base + ".pdf";
  const fs::path pngTmp = base + ".png.tmp", svgTmp = base + ".svg.tmp", pdfTmp = base + ".pdf.tmp";
  auto vector = [&](cairo_surface_t* s, const fs::path& tmp) {
    check(cairo_surface_status(s), "creating " + tmp.string());
    cairo_t* cr = cairo_create(s);
    cairo_scale(cr, pt, pt);
    drawFigure(Pen{cr, lay.scriptMin}, f, lay);
    cairo_destroy(cr);
    cairo_surface_finish(s);
    const cairo_status_t st = cairo_surface_status(s);
    cairo_surface_destroy(s);
    check(st, "writing " + tmp.string());
  };
  {
    // same input, same bytes: cairo stamps the PDF's CreationDate with the clock unless it is given one;
    // an empty one is written as an empty string
    cairo_surface_t* s = cairo_pdf_surface_create(pdfTmp.c_str(), lay.width * pt, lay.height * pt);
    cairo_pdf_surface_set_metadata(s, CAIRO_PDF_METADATA_CREATE_DATE, "");
    vector(s, pdfTmp);
  }
  vector(cairo_svg_surface_create(svgTmp.c_str(), lay.width * pt, lay.height * pt), svgTmp);
  {
    const int w = std::max(1, static_cast<int>(std::lround(inches * so.dpi)));
    const double scale = static_cast<double>(w) / lay.width;
    const int h = std::max(1, static_cast<int>(std::lround(lay.height * scale)));
    cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    cairo_t* cr = cairo_create(s);
    cairo_scale(cr, scale, scale);
    drawFigure(Pen{cr, lay.scriptMin}, f, lay);
    cairo_destroy(cr);
    check(cairo_surface_status(s), "drawing " + pngTmp.string());
    std::string why;
    const std::string bytes = figurePng(s, so.dpi, &why);
    cairo_surface_destroy(s);
    if (bytes.empty()) throw RunError("encoding " + pngTmp.string() + ": libpng: " + why);
    std::ofstream o(pngTmp, std::ios::binary);
    o << bytes;
    o.close();
    if (!o) throw RunError("cannot write " + pngTmp.string());
  }
  std::error_code ec;
  fs::rename(pngTmp, png, ec);
  if (!ec) fs::rename(svgTmp, svg, ec);
  if (!ec) fs::rename(pdfTmp, pdf, ec);
  if (ec) throw RunError("cannot rename figure files to " + base + ".{png,svg,pdf}: " + ec.message());
  // in a folder of rootsim's (a figure, compare or fit folder): recorded as written, so that --force
  // later replaces them only while they are as rootsim wrote them
  recordWritten({png, svg, pdf});
}

std::string literalLabel(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '_' || c == '^' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

namespace {

// a word that is part of a formula: an operator, or a symbol with a sub- or superscript or an operator
// at one end, or a lone symbol that is not a Latin letter word (β, α, γ, 0.1 next to an =)
const std::vector<std::string>& operators() {
  static const std::vector<std::string> kOps = {"=", "/", "+", "\xE2\x88\x92", "\xC3\x97", "\xC2\xB7", "<", ">",
                                                "\xE2\x89\x88", "\xE2\x89\xA4", "\xE2\x89\xA5", "~", "-", "*"};
  return kOps;
}
bool opStart(const std::string& w) {
  for (const std::string& o : operators())
    if (w.rfind(o, 0) == 0) return true;
  return false;
}
bool opEnd(const std::string& w) {
  for (const std::string& o : operators())
    if (w.size() >= o.size() && w.compare(w.size() - o.size(), o.size(), o) == 0) return true;
  return false;
}
bool operatorWord(const std::string& w) { return opStart(w) || opEnd(w); }
bool mathWord(const std::string& w) {
  if (operatorWord(w)) return true;
  if (w.find('_') != std::string::npos || w.find('^') != std::string::npos) return true;
  // one code point that is not ASCII (a Greek symbol)
  std::size_t cps = 0;
  bool ascii = true;
  for (char c : w) {
    cps += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    ascii = ascii && static_cast<unsigned char>(c) < 0x80;
  }
  return cps == 1 && !ascii;
}
bool endsPhrase(const std::string& w) {
  const char c = w.empty() ? ' ' : w.back();
  return c == ',' || c == ';' || c == ':' || c == ')';
}

}  // namespace

std::vector<std::string> titleChunks(const std::string& title, bool inside) {
  std::vector<std::string> words;
  for (std::size_t i = 0; i <= title.size();) {
    std::size_t j = title.find(' ', i);
    if (j == std::string::npos) j = title.size();
    if (j > i) words.push_back(title.substr(i, j - i));
    i = j + 1;
  }
  std::vector<std::string> out;
  std::string cur;
  int depth = 0;
  for (std::size_t k = 0; k < words.size(); ++k) {
    const std::string& w = words[k];
    if (!cur.empty()) {
      const std::string& prev = words[k - 1];
      const bool phraseEnd = endsPhrase(prev) || w.front() == '(';
      // a number or symbol next to an operator, an operator itself: inside a formula
      const bool formula = opEnd(prev) || opStart(w) || (mathWord(prev) && mathWord(w)) ||
                           (prev.back() == '.' && std::isdigit(static_cast<unsigned char>(w.front())));  // "Fig. 2A"
      const bool plain = !mathWord(prev) && !mathWord(w);
      const bool brk = !formula && (phraseEnd || (plain && (depth == 0 || inside)));
      if (brk) {
        out.push_back(cur);
        cur.clear();
      }
    }
    cur += (cur.empty() ? "" : " ") + w;
    for (char c : w) depth += c == '(' ? 1 : c == ')' ? -1 : 0;
    depth = std::max(depth, 0);
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

LabelLayout layoutLabel(const std::string& label, double size, bool bold, double scriptMin) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
  cairo_t* cr = cairo_create(s);
  LabelLayout out = placeLabel(cr, label, size, bold, scriptMin);
  cairo_destroy(cr);
  cairo_surface_destroy(s);
  return out;
}

std::array<double, 2> visibleStripe(const std::array<double, 3>& a, const std::array<double, 3>& b,
                                    const std::array<double, 3>& side, const std::array<double, 3>& view,
                                    double halfWidthRad) {
  auto dot = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
    return p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
  };
  const double an = dot(a, view), bn = dot(b, view), as = dot(a, side), bs = dot(b, side);
  constexpr int kSamples = 48;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int k = 0; k <= kSamples; ++k) {
    const double phi = -halfWidthRad + 2 * halfWidthRad * k / kSamples;
    const double c = std::cos(phi), sn = std::sin(phi);
    if (c * an + sn * bn <= 0) continue;  // faces away from the viewer
    const double u = c * as + sn * bs;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  if (!(hi >= lo)) return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {lo, hi};
}

}  // namespace rootsim
