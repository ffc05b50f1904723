// Plots with cairo: one drawing routine, two surfaces (PNG image and SVG).
#include "rootsim/plot.hpp"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "rootsim/errors.hpp"
#include "rootsim/units.hpp"

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

std::string tickLabel(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

struct Box { double x, y, w, h; };

// layout of one axes inside its cell [px]
constexpr double kLeft = 64, kRight = 14, kTop = 12, kTopTitle = 32, kBottom = 46, kFigureTitle = 34;

void text(cairo_t* cr, double x, double y, const std::string& s, double size, double ax, double ay,
          bool bold = false, double angle = 0) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, angle);
  cairo_move_to(cr, -ax * e.width - e.x_bearing, -ay * e.height - e.y_bearing);
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

void marker(cairo_t* cr, char m, double x, double y, double r) {
  switch (m) {
    case 's': cairo_rectangle(cr, x - r, y - r, 2 * r, 2 * r); cairo_fill(cr); break;
    case '^':
      cairo_move_to(cr, x, y - 1.2 * r); cairo_line_to(cr, x + r, y + 0.8 * r); cairo_line_to(cr, x - r, y + 0.8 * r);
      cairo_close_path(cr); cairo_fill(cr); break;
    case 'x':
      cairo_move_to(cr, x - r, y - r); cairo_line_to(cr, x + r, y + r);
      cairo_move_to(cr, x - r, y + r); cairo_line_to(cr, x + r, y - r); cairo_stroke(cr); break;
    default: cairo_arc(cr, x, y, r, 0, 2 * units::pi); cairo_fill(cr);
  }
}

void drawAxes(cairo_t* cr, const Axes& a, Box box) {
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
    for (const auto& r : a.rasters) { see(r.x0, r.y0); see(r.x1, r.y1); }
    if (!std::isfinite(lx)) { lx = 0; hx = 1; ly = 0; hy = 1; }
    if (hx - lx < 1e-12) { lx -= 0.5; hx += 0.5; }
    if (hy - ly < 1e-12) { ly -= 0.5; hy += 0.5; }
    const double px = 0.04 * (hx - lx), py = 0.06 * (hy - ly);
    if (a.autoX) { x0 = lx - px; x1 = hx + px; }
    if (a.autoY) { y0 = ly - py; y1 = hy + py; }
  }
  const double L = box.x + kLeft, R = box.x + box.w - kRight, T = box.y + (a.title.empty() ? kTop : kTopTitle),
               B = box.y + box.h - kBottom;
  double pw = R - L, ph = B - T;
  if (a.equalAspect) {
    // widen the smaller range so one data unit has the same length on both axes
    const double sx = pw / (x1 - x0), sy = ph / (y1 - y0);
    if (sx > sy) { const double c = 0.5 * (x0 + x1), h = 0.5 * pw / sy; x0 = c - h; x1 = c + h; }
    else { const double c = 0.5 * (y0 + y1), h = 0.5 * ph / sx; y0 = c - h; y1 = c + h; }
  }
  auto X = [&](double x) { return L + (x - x0) / (x1 - x0) * pw; };
  auto Y = [&](double y) { return B - (y - y0) / (y1 - y0) * ph; };
  const double unit = pw / (x1 - x0);  // pixels per data unit along x

  // frame, grid, ticks
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_rectangle(cr, L, T, pw, ph);
  cairo_fill(cr);
  const auto xt = a.frameOnly ? std::vector<double>{} : ticks(x0, x1);
  const auto yt = a.frameOnly ? std::vector<double>{} : ticks(y0, y1, 5);
  cairo_set_line_width(cr, 0.8);
  for (double v : xt) {
    if (a.grid) { cairo_set_source_rgb(cr, 0.9, 0.9, 0.9); cairo_move_to(cr, X(v), T); cairo_line_to(cr, X(v), B); cairo_stroke(cr); }
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_move_to(cr, X(v), B); cairo_line_to(cr, X(v), B + 5); cairo_stroke(cr);
    text(cr, X(v), B + 8, tickLabel(v), 12, 0.5, 0.0);
  }
  for (double v : yt) {
    if (a.grid) { cairo_set_source_rgb(cr, 0.9, 0.9, 0.9); cairo_move_to(cr, L, Y(v)); cairo_line_to(cr, R, Y(v)); cairo_stroke(cr); }
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_move_to(cr, L - 5, Y(v)); cairo_line_to(cr, L, Y(v)); cairo_stroke(cr);
    text(cr, L - 8, Y(v), tickLabel(v), 12, 1.0, 0.5);
  }
  cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
  cairo_set_line_width(cr, 1.2);
  cairo_rectangle(cr, L, T, pw, ph);
  cairo_stroke(cr);
  if (!a.title.empty()) text(cr, 0.5 * (L + R), box.y + 8, a.title, 15, 0.5, 0.0, true);
  if (!a.panelLabel.empty()) text(cr, box.x + 8, box.y + 6, a.panelLabel, 20, 0.0, 0.0, true);
  text(cr, 0.5 * (L + R), B + 26, a.xlabel, 13, 0.5, 0.0);
  text(cr, box.x + 14, 0.5 * (T + B), a.ylabel, 13, 0.5, 0.5, false, -units::pi / 2);

  // data, clipped to the plot area
  cairo_save(cr);
  cairo_rectangle(cr, L, T, pw, ph);
  cairo_clip(cr);
  for (const auto& fl : a.fills) {
    cairo_set_source_rgba(cr, fl.color[0], fl.color[1], fl.color[2], fl.alpha);
    for (size_t i = 0; i < fl.x.size(); ++i) (i ? cairo_line_to : cairo_move_to)(cr, X(fl.x[i]), Y(fl.y[i]));
    cairo_close_path(cr);
    cairo_fill(cr);
  }
  for (const auto& r : a.rasters) {
    if (r.width <= 0 || r.height <= 0 || r.rgba.size() != static_cast<size_t>(4 * r.width * r.height)) continue;
    // cairo wants premultiplied BGRA (native-endian ARGB32)
    cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, r.width, r.height);
    unsigned char* d = cairo_image_surface_get_data(img);
    const int stride = cairo_image_surface_get_stride(img);
    cairo_surface_flush(img);
    for (int yy = 0; yy < r.height; ++yy)
      for (int xx = 0; xx < r.width; ++xx) {
        const unsigned char* p = &r.rgba[static_cast<size_t>(4 * (yy * r.width + xx))];
        unsigned char* q = d + yy * stride + 4 * xx;
        const unsigned a8 = p[3];
        q[0] = static_cast<unsigned char>(p[2] * a8 / 255);
        q[1] = static_cast<unsigned char>(p[1] * a8 / 255);
        q[2] = static_cast<unsigned char>(p[0] * a8 / 255);
        q[3] = static_cast<unsigned char>(a8);
      }
    cairo_surface_mark_dirty(img);
    cairo_save(cr);
    cairo_translate(cr, X(r.x0), Y(r.y1));
    cairo_scale(cr, (X(r.x1) - X(r.x0)) / r.width, (Y(r.y0) - Y(r.y1)) / r.height);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
  }
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const auto& s : a.shapes) {
    cairo_set_source_rgb(cr, s.color[0], s.color[1], s.color[2]);
    cairo_set_line_width(cr, std::max(1.0, s.width * unit));
    for (size_t i = 0; i < s.x.size(); ++i) (i ? cairo_line_to : cairo_move_to)(cr, X(s.x[i]), Y(s.y[i]));
    cairo_stroke(cr);
  }
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
  for (const auto& [p, s] : a.notes) text(cr, X(p[0]), Y(p[1]), s, 12, 0.5, 0.5);
  cairo_restore(cr);

  // legend
  int n = 0;
  for (const auto& s : a.series) n += !s.label.empty();
  for (const auto& fl : a.fills) n += !fl.label.empty();
  if (n > 0 && a.legendPos != "none") {
    double w = 0;
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 12);
    for (const auto& s : a.series) {
      if (s.label.empty()) continue;
      cairo_text_extents_t e;
      cairo_text_extents(cr, s.label.c_str(), &e);
      w = std::max(w, e.x_advance);
    }
    for (const auto& fl : a.fills) {
      if (fl.label.empty()) continue;
      cairo_text_extents_t e;
      cairo_text_extents(cr, fl.label.c_str(), &e);
      w = std::max(w, e.x_advance);
    }
    const double bw = w + 44, bh = 18.0 * n + 8;
    const double lx = a.legendPos[1] == 'w' ? L + 8 : R - bw - 8;
    const double ly = a.legendPos[0] == 's' ? B - bh - 8 : T + 8;
    cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
    cairo_rectangle(cr, lx, ly, bw, bh);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
    cairo_set_line_width(cr, 0.8);
    cairo_stroke(cr);
    int k = 0;
    for (const auto& s : a.series) {
      if (s.label.empty()) continue;
      const double yy = ly + 13 + 18.0 * k++;
      cairo_set_source_rgb(cr, s.color[0], s.color[1], s.color[2]);
      if (s.kind != Series::Kind::Markers) {
        cairo_set_line_width(cr, s.width);
        if (s.dashed) { const double d[] = {6, 4}; cairo_set_dash(cr, d, 2, 0); }
        cairo_move_to(cr, lx + 6, yy); cairo_line_to(cr, lx + 32, yy); cairo_stroke(cr);
        cairo_set_dash(cr, nullptr, 0, 0);
      }
      if (s.kind != Series::Kind::Line) marker(cr, s.marker, lx + 19, yy, 4.5);
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      text(cr, lx + 38, yy, s.label, 12, 0.0, 0.5);
    }
    for (const auto& fl : a.fills) {
      if (fl.label.empty()) continue;
      const double yy = ly + 13 + 18.0 * k++;
      cairo_set_source_rgba(cr, fl.color[0], fl.color[1], fl.color[2], std::max(fl.alpha, 0.6));
      cairo_rectangle(cr, lx + 8, yy - 6, 22, 12);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      text(cr, lx + 38, yy, fl.label, 12, 0.0, 0.5);
    }
  }
}

void drawFigure(cairo_t* cr, const Figure& f) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const double top = f.title.empty() ? 0 : kFigureTitle;
  if (!f.title.empty()) {
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    text(cr, 0.5 * f.width, 10, f.title, 17, 0.5, 0.0, true);
  }
  const double cw = static_cast<double>(f.width) / f.cols, ch = (f.height - top) / static_cast<double>(f.rows);
  for (size_t i = 0; i < f.axes.size(); ++i) {
    const int r = static_cast<int>(i) / f.cols, c = static_cast<int>(i) % f.cols;
    drawAxes(cr, f.axes[i], Box{c * cw, top + r * ch, cw, ch});
  }
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

void saveFigure(const Figure& f, const std::string& base) {
  const fs::path png = base + ".png", svg = base + ".svg";
  const fs::path pngTmp = base + ".png.tmp", svgTmp = base + ".svg.tmp";
  {
    cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, f.width, f.height);
    cairo_t* cr = cairo_create(s);
    drawFigure(cr, f);
    cairo_destroy(cr);
    const cairo_status_t st = cairo_surface_write_to_png(s, pngTmp.c_str());
    cairo_surface_destroy(s);
    check(st, "writing " + pngTmp.string());
  }
  {
    cairo_surface_t* s = cairo_svg_surface_create(svgTmp.c_str(), f.width, f.height);
    check(cairo_surface_status(s), "creating " + svgTmp.string());
    cairo_t* cr = cairo_create(s);
    drawFigure(cr, f);
    cairo_destroy(cr);
    cairo_surface_finish(s);
    const cairo_status_t st = cairo_surface_status(s);
    cairo_surface_destroy(s);
    check(st, "writing " + svgTmp.string());
  }
  std::error_code ec;
  fs::rename(pngTmp, png, ec);
  if (!ec) fs::rename(svgTmp, svg, ec);
  if (ec) throw RunError("cannot rename figure files to " + base + ".{png,svg}: " + ec.message());
}

}  // namespace rootsim
