#pragma once
// State -> abstract render scene (no GL here; docs/architecture.md, "Data flow"). The scene is what the GL
// renderer draws and nothing more: triangle meshes, a plate with a grid, a camera, lights, overlay items.
//
// Plate coordinates [mm], used throughout the scene (docs/model.md, Frames and signs):
//   u = x . p           lateral, to the right in the top view
//   v = -g_par . p      uphill, so downhill points down the top view
//   w = n . p           height above the plate, towards the viewer of the top view
// with n = (0, -cos a, sin a), g_par = (0, -sin a, -cos a); (u, v, w) is right-handed.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rootsim/environment.hpp"
#include "rootsim/colour_map.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

class RootFootprint;  // rootsim/overlay_layout.hpp

// what to draw and how; plain data, every field has a usable default
struct View {
  enum class Kind { Top, Perspective };
  Kind kind = Kind::Top;         // Top: orthographic along -n; Perspective: oblique 3-D preset
  int width = 1280;              // [px] (even for MP4)
  int height = 720;              // [px] (even for MP4)
  bool whiskers = false;         // thin +d1 (pink) / -d1 (orange) spikes along the root
  bool transparent = false;      // no plate, alpha 0 outside the root (PNG only; MP4 has no alpha)
  double stripeHalfWidthDeg = 38.0;  // half the angular width of each stripe around +-d1 [deg]
  ColourField colourBy = ColourField::None;   // colour the body along the tube (stripes stay on top)
  std::array<double, 2> colourRange{0.0, 1.0}; // field values at the two ends of the map (fieldRange)
  bool shadows = false;          // the root's shadow on the plate and on itself (shadow map)
  int shadowMapPx = 4096;        // largest shadow map side [px]; the map gets about one texel per
                                 // picture pixel over the root's box, a power of two up to this
  // overlays, preferably in the margins the framing keeps free (top: time, parameters; bottom left: title,
  // stripe legend; bottom right: downhill arrow, scale bar; right edge: colour bar); the layout step
  // (rootsim/overlay_layout.hpp) moves each off the root's footprint, and nothing painted over the
  // picture but a trace changes a pixel of the footprint
  bool overlays = true;          // master switch
  bool showTime = true;          // "t = 12.0 h"
  bool showScaleBar = true;      // top view: a bar of 1, 2, 5, 10 ... mm with its label; 3-D: the grid's
                                 // pitch ("grid 1 mm")
  bool showLegend = true;        // a pink swatch "+d1" and an orange one "−d1"
  bool showDownhill = true;      // an arrow down the plate's slope as the picture shows it, "downhill"
  bool showParams = true;        // alpha, beta, gamma, and R tau when nonzero
  bool showTitle = false;        // SceneInfo::title
  bool showColourBar = true;     // with colourBy: the map, its range and the field's unit
  // a traced root drawn over the picture as a dark blue line (`render --trace`, docs/experiments.md):
  // its points in plate (u, v) [mm], empty for none; drawn with or without the other overlays, and named
  // "trace" in the stripe legend
  std::vector<std::array<double, 2>> traceUvMm;
  // a time-lapse trace (RSML 2D+t): the hour each of traceUvMm's points was reached; each frame draws the
  // trace as it was at the frame's time (the points reached by then, the last interpolated). Empty: the
  // whole trace on every frame
  std::vector<double> traceTimeH;
  // a plate's whole plate (`render --plate-view`, docs/plate.md): the plate drawn over this rectangle
  // (u0, v0, u1, v1) [mm] only, outlined, on a grey surround; unset: the plate fills the picture
  std::optional<std::array<double, 4>> plateRectMm;
  // a plate's seedlings (`render --plate-view`, docs/plate.md): each one's label (its name, and under it
  // its genotype when set) centred on its seed at (u, v) [mm], on the plate above it (uphill: the root
  // grows down from the seed and the label would hide it); its own values (beta, R tau) as a line of a
  // legend at the right edge under the header, which then shows alpha and gamma only
  struct SeedLabel {
    std::string label, sub;
    double u = 0, v = 0;
    std::string values;
  };
  std::vector<SeedLabel> seedLabels;
  // a scanner's look (`render --scan`): light roots without stripes on a dark plate without a grid,
  // no overlays (what a plate-scan pipeline reads)
  bool scanLook = false;
  std::string fontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";  // fonts-dejavu-core
  // the overlay font's pixel height; unset: from the view's size (overlayFontPx). A montage's tiles take
  // the montage's label size, so the common scale bar and downhill arrow match the labels
  std::optional<float> fontPx;
  // the root's footprint over the frames this picture's overlays hold still over (a movie's, for a fixed
  // camera); unset: this snapshot's own
  std::shared_ptr<const RootFootprint> footprint;
  // rectangles [x0, y0, x1, y1] px the overlays keep clear of (an inset drawn over the view)
  std::vector<std::array<float, 4>> keepClearPx;
  // framing; unset fields are computed from the snapshots' bounding box
  std::optional<std::array<double, 2>> centreMm;  // picture centre, plate (u, v) [mm]
  std::optional<double> widthMm;                  // visible plate width [mm]
  double marginMm = 1.0;         // added around the bounding box on every side [mm]
};

// the visible part of the plate, fixed for a whole movie so the picture does not jump
struct Framing {
  double centreU = 0.0;          // picture centre, plate u [mm]
  double centreV = 0.0;          // picture centre, plate v [mm]
  double widthMm = 10.0;         // visible width [mm]
  double heightMm = 5.625;       // visible height [mm] = widthMm * height / width
  double topW = 0.5;             // highest point of the root above the plate [mm] (3-D camera)
};

// plate coordinates: PlateFrame (environment.hpp), the one plate frame of sim, render and figure

// one vertex of the lit meshes (root tube, caps, whiskers); positions in plate coordinates [mm]
struct TubeVertex {
  float pos[3];      // [mm]
  float normal[3];   // unit
  float side[2];     // (cos phi, sin phi): direction of the surface normal in the (d1, d2) plane
  float colour[3];   // linear 0..1; used where striped == 0
  float striped;     // 1: body colour with +-d1 stripes chosen from side; 0: plain colour
};

struct OverlayText {
  enum class Anchor { TopLeft, TopRight, BottomLeft, BottomRight, BottomCentre };
  std::string text;                     // UTF-8 (Greek letters are in DejaVu Sans)
  float x = 0, y = 0;                   // anchor point [px], from the top-left corner
  float sizePx = 20;                    // font pixel height
  Anchor anchor = Anchor::TopLeft;
  std::array<std::uint8_t, 4> colour{40, 40, 40, 255};
};

struct OverlayRect {
  float x = 0, y = 0, w = 0, h = 0;     // [px], from the top-left corner
  std::array<std::uint8_t, 4> colour{40, 40, 40, 255};
};

// an anti-aliased polyline (a single point draws a round dot)
struct OverlayLine {
  std::vector<std::array<float, 2>> points;   // [px], from the top-left corner
  float widthPx = 2;
  std::array<std::uint8_t, 4> colour{40, 40, 40, 255};
  bool overRoot = false;                      // drawn over the root's footprint too (a trace)
};

struct RenderScene {
  int width = 0, height = 0;            // [px]
  std::array<float, 16> viewMatrix{};   // plate [mm] -> eye, column-major
  std::array<float, 16> projMatrix{};   // eye -> clip, column-major
  std::array<float, 3> lightDir{};      // towards the key light, eye space, unit
  std::array<float, 4> background{};    // clear colour RGBA 0..1 (alpha 0 when transparent)

  // lit meshes: triangles (3 indices each) into vertices
  std::vector<TubeVertex> vertices;
  std::vector<std::uint32_t> indices;

  struct Material {
    std::array<float, 3> body{0.95f, 0.93f, 0.86f};    // neutral ivory
    std::array<float, 3> plus{0.90f, 0.20f, 0.55f};    // +d1 stripe: pink
    std::array<float, 3> minus{0.98f, 0.52f, 0.05f};   // -d1 stripe: orange
    float stripeCos = 0.788f;  // cos of the stripe half width
    float ambient = 0.42f, diffuse = 0.62f, specular = 0.22f, shininess = 48.0f;
  } material;

  struct Plate {
    bool visible = true;
    float u0 = 0, v0 = 0, u1 = 1, v1 = 1;              // extent in plate coordinates [mm]
    float gridMm = 1.0f;                               // grid spacing [mm]
    int majorEvery = 10;                               // every n-th line is darker
    std::array<float, 3> colour{0.97f, 0.97f, 0.96f};
    std::array<float, 3> line{0.80f, 0.82f, 0.86f};
    std::array<float, 3> major{0.62f, 0.65f, 0.72f};
    float lineWidthPx = 1.0f;                          // grid line width [px] (anti-aliased); grows with
                                                     // the picture: min(width, height) / 1080, >= 1
  } plate;

  // shadows: a depth map of the root seen from the key light, sampled by the plate
  bool shadows = false;
  std::array<float, 16> lightViewProj{};  // plate [mm] -> light clip space, column-major
  std::array<float, 3> lightPlate{};      // towards the key light, plate axes, unit
  float shadowTexelMm = 0.0f;             // one shadow-map texel on the light's view [mm]
  int shadowMapPx = 2048;                 // [px]
  std::array<float, 8> shadowQuad{};      // the plate region the map covers: 4 corners (u, v) [mm],
                                          // in triangle-strip order

  std::vector<OverlayRect> rects;       // drawn first
  std::vector<OverlayLine> lines;       // then the lines
  std::vector<OverlayText> texts;       // drawn over the rects and lines
  std::string fontPath;                 // TrueType font for texts
  // this snapshot's footprint: rects, texts and lines (but overRoot ones) leave its pixels as drawn
  std::shared_ptr<const RootFootprint> keepOut;

  double pxPerMm = 0.0;                 // top view scale [px/mm]; 0 in perspective
};

// a picture's camera: plate [mm] -> eye -> clip, column-major (what buildRenderScene draws with)
struct CameraMatrices {
  std::array<float, 16> view{};
  std::array<float, 16> proj{};
};
CameraMatrices cameraFor(const View& view, const Framing& framing);

// the overlay font's pixel height for a view: View::fontPx, or its shorter side / 26, at least 12
float overlayFontPx(const View& view);
// the legend's labels and the downhill arrow's label
inline constexpr const char* kLegendPlus = "+d1";
inline constexpr const char* kLegendMinus = "\xE2\x88\x92" "d1";  // U+2212 minus
inline constexpr const char* kDownhillLabel = "downhill";

// framing for a whole movie: the bounding box of every node of every snapshot in plate (u, v),
// plus the element radius and View::marginMm on each side, widened to the picture's aspect
// (View::centreMm / widthMm override). In the 3-D view (whose oblique camera shows that box smaller)
// the window is then fitted to the nodes' projection (fitFramingsToBox) in the part of the picture the
// top view keeps for the root. Throws RenderError on an empty list or a bad view size.
Framing frameFor(const std::vector<Snapshot>& snaps, const SceneInfo& info, const View& view);

// windows refined together so that points[k] (plate mm, seen through framings[k] by view's camera)
// projected, widened by padMm at the windows' scale, fill the goal box [x0, y0, x1, y1] px of the
// picture: the windows keep one size (scaled by one factor) and move by one offset; a few rounds, as
// the perspective projection is not linear (one for the top view)
void fitFramingsToBox(std::vector<Framing>& framings, const std::vector<std::vector<Eigen::Vector3d>>& points,
                      const View& view, const std::array<double, 4>& goal, double padMm);

// the scene for one snapshot. Throws RenderError on inconsistent snapshot shapes or sizes <= 0.
RenderScene buildRenderScene(const Snapshot& snap, const SceneInfo& info, const View& view,
                             const Framing& framing);

// where plate point (u, v, w) [mm] appears in the picture of scene (either camera) [px, from the
// top-left corner]; false if it is behind the camera
bool projectToPixel(const RenderScene& scene, const Eigen::Vector3d& plateMm, Eigen::Vector2d& px);

// where plate point (u, v) [mm] appears in the top view [px, from the top-left corner, continuous:
// pixel (i, j) covers [i, i+1) x [j, j+1)]
Eigen::Vector2d topViewPixel(const Framing& framing, const View& view, double u, double v);

}  // namespace rootsim
