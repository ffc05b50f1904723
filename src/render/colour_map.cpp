// per-node fields for `--color-by`, their movie-wide range, and the viridis colour map
#include "rootsim/colour_map.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "rootsim/image.hpp"
#include "rootsim/rotation.hpp"
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
    {ColourField::Kappa0, "kappa0", "intrinsic curvature \xCE\xBA\xE2\x82\x80 [1/mm]"},
    {ColourField::Stretch, "stretch", "stretch \xCE\xBB\xE2\x82\x91 [-]"},
    {ColourField::Contact, "contact", "plate contact force [mN]"},
};

// directors of element e as the rows of a matrix (d2 = d3 x d1)
Eigen::Matrix3d directors(const Snapshot& s, int e) {
  Eigen::Matrix3d Q;
  const Eigen::Vector3d d1 = s.d1.col(e), d3 = s.d3.col(e);
  Q.row(0) = d1.transpose();
  Q.row(1) = d3.cross(d1).transpose();
  Q.row(2) = d3.transpose();
  return Q;
}

// interior Voronoi values (n-1) spread to the n+1 nodes, the ends copying their neighbour
Eigen::VectorXd toNodes(const Eigen::VectorXd& voronoi, int n) {
  Eigen::VectorXd v(n + 1);
  if (n < 2) return Eigen::VectorXd::Zero(n + 1);
  v.segment(1, n - 1) = voronoi;
  v[0] = voronoi[0];
  v[n] = voronoi[n - 2];
  return v;
}

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

std::string colourFieldLabel(ColourField f) {
  for (const FieldName& n : kFields)
    if (n.f == f) return n.label;
  return "";
}

Eigen::VectorXd nodeField(const Snapshot& s, const SceneInfo& info, ColourField f) {
  const int n = s.elements();
  switch (f) {
    case ColourField::None:
      return Eigen::VectorXd::Zero(n + 1);
    case ColourField::Curvature:
    case ColourField::Twist: {
      // kappa D = log(Q_j Q_{j+1}^T) in material components (rod.cpp), per current Voronoi length
      Eigen::VectorXd v(std::max(n - 1, 0));
      for (int j = 0; j + 1 < n; ++j) {
        const Eigen::Vector3d k = rotationToVector(directors(s, j) * directors(s, j + 1).transpose());
        const double D = 0.5 * ((s.x.col(j + 1) - s.x.col(j)).norm() + (s.x.col(j + 2) - s.x.col(j + 1)).norm());
        const double perMm = units::mm / std::max(D, 1e-300);
        v[j] = f == ColourField::Curvature ? std::hypot(k.x(), k.y()) * perMm : k.z() * perMm;
      }
      return toNodes(v, n);
    }
    case ColourField::Kappa0:
      if (s.kappa0.size() != n + 1)
        throw RenderError("--color-by kappa0: snapshot of step " + std::to_string(s.step) +
                          " carries no kappa0 (a trajectory.csv written before the kappa0 column; run again)");
      return s.kappa0 * units::mm;
    case ColourField::Stretch: {
      if (!(info.radius > 0)) throw RenderError("--color-by stretch: the scene's root radius must be > 0");
      Eigen::VectorXd v(n + 1);
      auto lambda = [&](int e) { return std::pow(info.radius / s.radius[e], 2); };
      for (int i = 0; i <= n; ++i) {
        const int a = std::max(i - 1, 0), b = std::min(i, n - 1);
        v[i] = 0.5 * (lambda(a) + lambda(b));
      }
      return v;
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
    for (double x : v) all.push_back(f == ColourField::Twist ? std::abs(x) : x);
  }
  double lo = 0.0, hi = 0.0;
  if (f == ColourField::Stretch) {
    std::vector<double> copy = all;
    lo = quantile(copy, 0.01);
    hi = quantile(all, 0.99);
  } else {
    hi = quantile(all, 0.99);
    if (f == ColourField::Twist) lo = -hi;
  }
  // a constant field still gets a usable bar
  if (!(hi - lo > 1e-12 * std::max(1.0, std::abs(hi)))) {
    const double pad = std::max(1e-9, 0.05 * std::abs(hi));
    if (f == ColourField::Stretch || f == ColourField::Twist) lo -= pad;
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

}  // namespace rootsim
