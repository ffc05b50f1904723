#pragma once
// Publication plots (cairo): one vector drawing goes to PDF, SVG and PNG (rasterised from the same
// drawing, with its resolution in a pHYs chunk). Data in, files out; no physics.
//
// Labels (titles, axis labels, legend entries, notes) take a small markup: _{...} sets its contents as a
// subscript, ^{...} as a superscript (smaller, shifted); a single character may follow _ or ^ without
// braces; a sub- and a superscript in a row stack; \_, \^ and \\ stand for themselves (literalLabel).
// Text stays text in the PDF and SVG.
#include <array>
#include <string>
#include <vector>

namespace rootsim {

using Rgb = std::array<double, 3>;  // 0..1

struct Series {
  enum class Kind { Line, Markers, LineMarkers };
  Kind kind = Kind::Line;
  std::vector<double> x, y;
  Rgb color{0.1, 0.3, 0.7};
  double width = 1.8;           // line width [px at 1x]
  bool dashed = false;
  char marker = 'o';            // 'o' circle, 's' square, 'D' diamond, '^' up / '>' right triangle, 'x' cross
  std::string label;            // legend entry ("" = none)
};

struct Shape2D {                // a root drawn on the plate: a polyline with a width, in plot units
  std::vector<double> x, y;
  double width = 0.2;           // [plot units], e.g. 2R in mm
  Rgb color{0.25, 0.25, 0.25};
};

// a root seen from above as vector paths: its outline (the centreline offset by the radius on both
// sides), shading bands along it and its +-d1 stripes, node by node in plot units
struct Tube {
  std::vector<double> x, y;       // centreline
  std::vector<double> z;          // height above the plate (strands are drawn lowest first)
  std::vector<double> r;          // radius
  std::vector<double> sx, sy;     // unit vector across the tube (the side the lateral offsets point to)
  // visible lateral extent of each stripe across the tube, in units of r (-1..1, lo <= hi); NaN where the
  // stripe faces away from the viewer
  std::vector<std::array<double, 2>> plus, minus;
  Rgb body{0.95, 0.93, 0.86}, plusColor{0.90, 0.20, 0.55}, minusColor{0.98, 0.52, 0.05};
};

// the part of a stripe of the tube's surface that a viewer sees, as a lateral extent across the tube in
// units of the radius: the stripe is the surface directions cos(phi) a + sin(phi) b (a: the stripe's
// centre direction, e.g. +d1 or -d1, b: t x a) with cos(phi) >= cos(halfWidth) (as the raster renderer
// places them, shaders/tube.frag); a surface point is seen where its normal has a positive component along
// `view` (towards the viewer) and lies at offset (normal . side) across the tube. {NaN, NaN} if none is seen.
std::array<double, 2> visibleStripe(const std::array<double, 3>& a, const std::array<double, 3>& b,
                                    const std::array<double, 3>& side, const std::array<double, 3>& view,
                                    double halfWidthRad);

// an obstacle on the plate seen from above, in plot units: a peg (a disc, from == to) or a wall (the
// segment from..to thickened by r on either side, with round ends as the model's capsule)
struct Obstacle2D {
  double fromX = 0, fromY = 0, toX = 0, toY = 0;
  double r = 0;
  Rgb color{0.56, 0.62, 0.72};  // the raster renderer's slate blue-grey (src/render/obstacle_mesh.cpp)
};

struct Fill {                   // a filled polygon in data coordinates (background regions)
  std::vector<double> x, y;
  Rgb color{0.9, 0.9, 0.9};
  double alpha = 1.0;
  std::string label;            // legend entry ("" = none)
};

struct Axes {
  std::string title, xlabel, ylabel;  // labels with their unit, e.g. "lateral [mm]"
  std::string panelLabel;       // bold letter at the top left ("A", "B", ...)
  bool frameOnly = false;       // no ticks or grid: for pictures
  std::vector<Fill> fills;
  bool autoX = true, autoY = true;
  double xmin = 0, xmax = 1, ymin = 0, ymax = 1;
  bool equalAspect = false;     // for shapes on the plate
  bool yDown = false;           // y grows downwards (plate views: downhill is down)
  bool logX = false;            // logarithmic x axis (ticks at 1, 2, 5 per decade); x must be > 0
  // a categorical x axis: each category's name under a tick at its position, no numeric ticks and no
  // vertical grid (groups side by side); empty: a numeric axis
  std::vector<std::pair<double, std::string>> xCategories;
  bool grid = true;
  std::vector<Series> series;
  std::vector<Shape2D> shapes;
  std::vector<Tube> tubes;
  std::vector<Obstacle2D> obstacles;  // drawn under the tubes
  double plateGridPitch = 0;    // > 0: a light grid of this pitch [plot units] under the data (1 mm on the plate)
  std::vector<std::pair<std::array<double, 2>, std::string>> notes;  // text at data coordinates
  std::string legendPos = "ne"; // ne, nw, se, sw, none
};

// a figure: a row-major grid of axes, laid out on width x height layout units of 1/96 inch. With
// SaveOptions::widthMm the panel is laid out again at that physical width (docs/rendering.md, Figure
// panels): text at fixed point sizes, each plot area keeping its aspect (plots at least 0.45 high), tiles
// of one row sharing their y axis, rows of tiles wrapping when a tile would be narrower than 12 mm.
struct Figure {
  int width = 1200, height = 800;
  int rows = 1, cols = 1;
  std::string title;
  std::vector<Axes> axes;
};

// height / width of the plot area of axes a in figure f (the layout saveFigure uses; the physical layout
// keeps it)
double plotAspect(const Figure& f, const Axes& a);

// a label laid out: its runs of text with the pen position of each (x along the base line from the
// label's start, y down from the base line, in the units of the font size given) and its font size. A
// subscript right after a superscript, or a superscript right after a subscript, stacks on it (κ_f^0:
// the 0 above the f, both at one x)
struct LabelRun {
  std::string text;
  double x = 0, y = 0, size = 0;
  int level = 0;  // 0 base, -1 subscript, +1 superscript
};
struct LabelLayout {
  std::vector<LabelRun> runs;
  double width = 0;  // advance width
};
// the layout of a label (markup above) at font size `size`, its sub- and superscripts no smaller than
// scriptMin (same units)
LabelLayout layoutLabel(const std::string& label, double size, bool bold = false, double scriptMin = 0);
// a figure title's pieces that a line break may separate: its phrases (broken after , ; : . or a
// closing parenthesis, before an opening one, and between two plain words outside parentheses), never
// next to an operator (=, /, +, −, ×, ·, <, >, ≈) or between two symbols of a formula (β L_gz);
// inside: also between plain words within parentheses (for a phrase wider than a line)
std::vector<std::string> titleChunks(const std::string& title, bool inside = false);
// text shown as it is in a label (a scene key such as tropism.twist_r_tau): its _, ^ and \ escaped
std::string literalLabel(const std::string& text);

struct SaveOptions {
  double dpi = 300;             // PNG resolution (stored in its pHYs chunk)
  double widthMm = 0;           // physical width (e.g. 85 or 180 mm for a journal column); 0: width / 96 inch
  bool titles = true;           // false: no figure title (the caption goes with the paper)
};

// writes path.pdf, path.svg and path.png (atomically), one drawing; throws RunError
void saveFigure(const Figure& f, const std::string& pathWithoutExtension, const SaveOptions& so = {});

// one axes of a figure as saveFigure lays it out, in points from the page's top left (the PDF's units):
// its plot area, data range and legend. The legend sits inside the plot area where nothing drawn there
// (curves with half their width, markers, tubes, shapes, notes) comes within 2 layout units of its box,
// at the corner asked for (Axes::legendPos) when that is free, else at the free place nearest it; where
// no place is free it goes under the axes, its entries in rows
struct AxesLayout {
  std::array<double, 4> plot{};    // x, y, width, height
  std::array<double, 4> legend{};  // x, y, width, height (width 0: no legend)
  bool legendInside = true;        // false: under the axes
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  bool logX = false, yDown = false;
};
std::vector<AxesLayout> figureLayout(const Figure& f, const SaveOptions& so = {});
// the page point [pt] of data point (x, y) in axes laid out as l
std::array<double, 2> pagePoint(const AxesLayout& l, double x, double y);

// colours of a qualitative palette (Okabe-Ito)
Rgb paletteColor(int i);

}  // namespace rootsim
