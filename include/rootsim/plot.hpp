#pragma once
// Publication plots (cairo): the same drawing goes to PNG and to SVG. Data in, files out; no physics.
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
  char marker = 'o';            // 'o' circle, 's' square, '^' triangle, 'x' cross
  std::string label;            // legend entry ("" = none)
};

struct Shape2D {                // a root drawn on the plate: a polyline with a width, in plot units
  std::vector<double> x, y;
  double width = 0.2;           // [plot units], e.g. 2R in mm
  Rgb color{0.25, 0.25, 0.25};
};

struct Fill {                   // a filled polygon in data coordinates (background regions)
  std::vector<double> x, y;
  Rgb color{0.9, 0.9, 0.9};
  double alpha = 1.0;
  std::string label;            // legend entry ("" = none)
};

struct Raster {                 // an RGBA picture placed at a data-coordinate rectangle
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;  // top row first, straight alpha
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;  // extent: left, right, bottom, top
};

struct Axes {
  std::string title, xlabel, ylabel;
  std::string panelLabel;       // bold letter at the top left ("A", "B", ...)
  bool frameOnly = false;       // no ticks or grid: for pictures
  std::vector<Fill> fills;
  std::vector<Raster> rasters;
  bool autoX = true, autoY = true;
  double xmin = 0, xmax = 1, ymin = 0, ymax = 1;
  bool equalAspect = false;     // for shapes on the plate
  bool grid = true;
  std::vector<Series> series;
  std::vector<Shape2D> shapes;
  std::vector<std::pair<std::array<double, 2>, std::string>> notes;  // text at data coordinates
  std::string legendPos = "ne"; // ne, nw, se, sw, none
};

// a figure: a row-major grid of axes, drawn at width x height pixels
struct Figure {
  int width = 1200, height = 800;
  int rows = 1, cols = 1;
  std::string title;
  std::vector<Axes> axes;
};

// height / width of the plot area of axes a in figure f, in pixels (the layout saveFigure uses)
double plotAspect(const Figure& f, const Axes& a);

// writes path.png and path.svg (atomically); throws RunError
void saveFigure(const Figure& f, const std::string& pathWithoutExtension);

// colours of a qualitative palette (Okabe-Ito)
Rgb paletteColor(int i);

}  // namespace rootsim
