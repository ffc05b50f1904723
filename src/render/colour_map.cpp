// per-node fields for `--color-by`, their movie-wide range, and the viridis colour map
#include "rootsim/colour_map.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "rootsim/image.hpp"
#include "rootsim/node_fields.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {

struct FieldName {
  ColourField f;
  const char* name;
  const char* label;
};
constexpr FieldName kFields[] = {
    {ColourField::Curvature, "curvature", "curvature [1/mm]"},
    {ColourField::Twist, "twist", "twist \xCE\xBA\xE2\x82\x83 [rad/mm]"},
    {ColourField::Kappa1, "kappa1", "bending \xCE\xBA\xE2\x82\x81 [1/mm]"},
    {ColourField::Kappa2, "kappa2", "bending \xCE\xBA\xE2\x82\x82 [1/mm]"},
    {ColourField::Kappa0, "kappa0", "intrinsic curvature \xCE\xBA\xE2\x82\x80 [1/mm]"},
    {ColourField::Stretch, "stretch", "stretch \xCE\xBB\xE2\x82\x91 [-]"},
    {ColourField::Contact, "contact", "plate contact force [mN]"},
};

double quantile(std::vector<double>& v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

bool parseColourField(const std::string& name, ColourField& out) {
  if (name == "none") {
    out = ColourField::None;
    return true;
  }
  for (const FieldName& f : kFields)
    if (name == f.name) {
      out = f.f;
      return true;
    }
  return false;
}

std::string colourFieldNames() {
  std::string s;
  for (const FieldName& f : kFields) s += (s.empty() ? "" : ", ") + std::string(f.name);
  return s;
}

bool colourFieldSigned(ColourField f) {
  return f == ColourField::Twist || f == ColourField::Kappa1 || f == ColourField::Kappa2;
}

std::string colourFieldLabel(ColourField f) {
  for (const FieldName& n : kFields)
    if (n.f == f) return n.label;
  return "";
}

Eigen::VectorXd nodeField(const Snapshot& s, const SceneInfo& info, ColourField f) {
  if (!s.rootStarts.empty()) {
    // a plate's roots: each root's field, in turn (nothing across the elements that join them)
    Eigen::VectorXd all(s.x.cols());
    long at = 0;
    for (int k = 0; k < rootCount(s); ++k) {
      const Eigen::VectorXd v = nodeField(rootOf(s, k), info, f);
      all.segment(at, v.size()) = v;
      at += v.size();
    }
    return all;
  }
  const int n = s.elements();
  switch (f) {
    case ColourField::None:
      return Eigen::VectorXd::Zero(n + 1);
    case ColourField::Curvature:
    case ColourField::Twist:
    case ColourField::Kappa1:
    case ColourField::Kappa2: {
      // kappa D = log(Q_j Q_{j+1}^T) in material components (rod.cpp), per current Voronoi length
      const std::vector<VoronoiBend> bends = voronoiBends(s);
      Eigen::VectorXd v(std::max(n - 1, 0));
      for (int j = 0; j + 1 < n; ++j) {
        const Eigen::Vector3d& k = bends[static_cast<std::size_t>(j)].kappa;
        const double D = bends[static_cast<std::size_t>(j)].length;
        const double perMm = units::mm / std::max(D, 1e-300);
        const double c = f == ColourField::Curvature ? std::hypot(k.x(), k.y())
                         : f == ColourField::Kappa1  ? k.x()
                         : f == ColourField::Kappa2  ? k.y()
                                                     : k.z();
        v[j] = c * perMm;
      }
      return voronoiToNodes(v, n);
    }
    case ColourField::Kappa0:
      if (s.kappa0.size() != n + 1)
        throw RenderError("--color-by kappa0: snapshot of step " + std::to_string(s.step) +
                          " carries no kappa0 (a trajectory.csv written before the kappa0 column; run again)");
      return s.kappa0 * units::mm;
    case ColourField::Stretch: {
      if (!(info.radius > 0)) throw RenderError("--color-by stretch: the scene's root radius must be > 0");
      return nodeStretch(s, info.radius);
    }
    case ColourField::Contact:
      if (s.plateForce.size() != n + 1)
        throw RenderError("--color-by contact: snapshot of step " + std::to_string(s.step) +
                          " carries no plate force (a trajectory.csv written before the plate_force column; run again)");
      return s.plateForce * 1e3;  // N -> mN
  }
  return Eigen::VectorXd::Zero(n + 1);
}

std::array<double, 2> fieldRange(const std::vector<Snapshot>& snaps, const SceneInfo& info, ColourField f) {
  if (f == ColourField::None) return {0.0, 1.0};
  std::vector<double> all;
  for (const Snapshot& s : snaps) {
    const Eigen::VectorXd v = nodeField(s, info, f);
    for (double x : v) all.push_back(colourFieldSigned(f) ? std::abs(x) : x);
  }
  double lo = 0.0, hi = 0.0;
  if (f == ColourField::Stretch) {
    std::vector<double> copy = all;
    lo = quantile(copy, 0.01);
    hi = quantile(all, 0.99);
  } else {
    hi = quantile(all, 0.99);
    if (colourFieldSigned(f)) lo = -hi;
  }
  // a constant field still gets a usable bar
  if (!(hi - lo > 1e-12 * std::max(1.0, std::abs(hi)))) {
    const double pad = std::max(1e-9, 0.05 * std::abs(hi));
    if (f == ColourField::Stretch || colourFieldSigned(f)) lo -= pad;
    hi += pad;
  }
  return {lo, hi};
}

std::array<float, 3> viridis(double t) {
  // the 11 published stops of viridis at t = 0, 0.1, ..., 1 (#440154 ... #fde725)
  static constexpr unsigned kStops[11] = {0x440154, 0x482475, 0x414487, 0x355f8d, 0x2a788e, 0x21918c,
                                          0x22a884, 0x44bf70, 0x7ad151, 0xbddf26, 0xfde725};
  if (!(t >= 0.0)) t = 0.0;  // NaN -> 0
  t = std::min(t, 1.0);
  const double x = t * 10.0;
  const int i = std::min(static_cast<int>(x), 9);
  const double w = x - i;
  std::array<float, 3> c{};
  for (int k = 0; k < 3; ++k) {
    const double a = static_cast<double>((kStops[i] >> (16 - 8 * k)) & 0xFF) / 255.0;
    const double b = static_cast<double>((kStops[i + 1] >> (16 - 8 * k)) & 0xFF) / 255.0;
    c[static_cast<std::size_t>(k)] = static_cast<float>(a + w * (b - a));
  }
  return c;
}

std::array<float, 3> coolWarm(double t) {
  // Moreland's 33 published control points (8-bit sRGB) at t = 0, 1/32, ..., 1; the middle one is
  // the neutral grey (221, 221, 221)
  static constexpr unsigned char kStops[33][3] = {
      {59, 76, 192},   {68, 90, 204},   {77, 104, 215},  {87, 117, 225},  {98, 130, 234},  {108, 142, 241},
      {119, 154, 247}, {130, 165, 251}, {141, 176, 254}, {152, 185, 255}, {163, 194, 255}, {174, 201, 253},
      {184, 208, 249}, {194, 213, 244}, {204, 217, 238}, {213, 219, 230}, {221, 221, 221}, {229, 216, 209},
      {236, 211, 197}, {241, 204, 185}, {245, 196, 173}, {247, 187, 160}, {247, 177, 148}, {247, 166, 135},
      {244, 154, 123}, {241, 141, 111}, {236, 127, 99},  {229, 112, 88},  {222, 96, 77},   {213, 80, 66},
      {203, 62, 56},   {192, 40, 47},   {180, 4, 38}};
  if (!(t >= 0.0)) t = 0.0;  // NaN -> 0
  t = std::min(t, 1.0);
  const double x = t * 32.0;
  const int i = std::min(static_cast<int>(x), 31);
  const double w = x - i;
  std::array<float, 3> c{};
  for (int k = 0; k < 3; ++k)
    c[static_cast<std::size_t>(k)] =
        static_cast<float>((kStops[i][k] + w * (kStops[i + 1][k] - kStops[i][k])) / 255.0);
  return c;
}

namespace {

constexpr double kXn = 0.95047, kYn = 1.0, kZn = 1.08883;  // D65 white

double srgbToLinear(double u) { return u <= 0.04045 ? u / 12.92 : std::pow((u + 0.055) / 1.055, 2.4); }
double linearToSrgb(double u) { return u <= 0.0031308 ? 12.92 * u : 1.055 * std::pow(u, 1.0 / 2.4) - 0.055; }

std::array<double, 3> toLab(const std::array<float, 3>& c) {
  const double r = srgbToLinear(c[0]), g = srgbToLinear(c[1]), b = srgbToLinear(c[2]);
  const double X = 0.4124 * r + 0.3576 * g + 0.1805 * b, Y = 0.2126 * r + 0.7152 * g + 0.0722 * b,
               Z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
  auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; };
  const double fx = f(X / kXn), fy = f(Y / kYn), fz = f(Z / kZn);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

std::array<float, 3> fromLab(double L, double a, double b) {
  auto fInv = [](double t) { return t > 0.206893 ? t * t * t : (t - 16.0 / 116.0) / 7.787; };
  const double fy = (L + 16) / 116, fx = fy + a / 500, fz = fy - b / 200;
  const double X = kXn * fInv(fx), Y = kYn * fInv(fy), Z = kZn * fInv(fz);
  const double r = 3.2406 * X - 1.5372 * Y - 0.4986 * Z, g = -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
               bl = 0.0557 * X - 0.2040 * Y + 1.0570 * Z;
  auto out = [&](double u) { return static_cast<float>(std::clamp(linearToSrgb(std::max(u, 0.0)), 0.0, 1.0)); };
  return {out(r), out(g), out(bl)};
}

double hueDeg(const std::array<double, 3>& lab) {
  const double h = std::atan2(lab[2], lab[1]) * 180.0 / units::pi;
  return h < 0 ? h + 360.0 : h;
}

}  // namespace

std::array<float, 3> blueGreen(double t) {
  if (!(t >= 0.0)) t = 0.0;  // NaN -> 0
  t = std::min(t, 1.0);
  const double x = std::abs(2.0 * t - 1.0);
  const double L = 88.0 - 50.0 * x, C = 44.0 * x, h = (t < 0.5 ? 290.0 : 150.0) * units::pi / 180.0;
  return fromLab(L, C * std::cos(h), C * std::sin(h));
}

std::array<float, 3> sequential(double t) {
  if (!(t >= 0.0)) t = 0.0;
  return viridis(0.1 + 0.8 * std::min(t, 1.0));
}

double stripeHueDistanceDeg(const std::array<float, 3>& c) {
  const std::array<double, 3> lab = toLab(c);
  if (std::hypot(lab[1], lab[2]) < 10.0) return 180.0;
  const RenderScene::Material m;
  double best = 180.0;
  for (const auto& s : {m.plus, m.minus}) {
    const double d = std::abs(hueDeg(lab) - hueDeg(toLab(s)));
    best = std::min(best, std::min(d, 360.0 - d));
  }
  return best;
}

std::array<float, 3> fieldColour(ColourField f, double v, const std::array<double, 2>& range) {
  const double t = (v - range[0]) / (range[1] - range[0]);
  return colourFieldSigned(f) ? blueGreen(t) : sequential(t);
}

}  // namespace rootsim
