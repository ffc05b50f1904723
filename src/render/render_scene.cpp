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

#include "rootsim/image.hpp"

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

void checkSnapshot(const Snapshot& s) {
  const long n = s.radius.size();
  if (n < 1 || s.x.cols() != n + 1 || s.d1.cols() != n || s.d3.cols() != n)
    throw RenderError("render: snapshot of step " + std::to_string(s.step) +
                      " has inconsistent shapes (elements " + std::to_string(n) + ", nodes " +
                      std::to_string(s.x.cols()) + ", d1 " + std::to_string(s.d1.cols()) + ", d3 " +
                      std::to_string(s.d3.cols()) + ")");
  if (!s.x.allFinite() || !s.d1.allFinite() || !s.d3.allFinite() || !s.radius.allFinite())
    throw RenderError("render: snapshot of step " + std::to_string(s.step) + " has non-finite values");
}

// a ring of the tube: centre, unit tangent t, unit d1 normal to t, radius, all in plate mm
struct Ring {
  V3 c, t, a, b;  // b = t x a (d2)
  double r;
};

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

// node frames from the element directors, averaged at interior nodes (smooth shading and stripes)
std::vector<Ring> nodeRings(const Snapshot& s, const PlateFrame& pf) {
  const int n = s.elements();
  std::vector<Ring> rings(static_cast<size_t>(n + 1));
  for (int i = 0; i <= n; ++i) {
    V3 t = V3::Zero(), a = V3::Zero();
    double r = 0.0;
    int cnt = 0;
    for (int e : {i - 1, i}) {
      if (e < 0 || e >= n) continue;
      t += pf.dirToPlate(s.d3.col(e));
      a += pf.dirToPlate(s.d1.col(e));
      r += s.radius[e];
      ++cnt;
    }
    Ring& g = rings[static_cast<size_t>(i)];
    g.c = pf.toPlateMm(s.x.col(i));
    if (t.norm() < 1e-12) t = V3::UnitY();
    g.t = t.normalized();
    a -= a.dot(g.t) * g.t;
    if (a.norm() < 1e-12) a = g.t.unitOrthogonal();
    g.a = a.normalized();
    g.b = g.t.cross(g.a);
    g.r = r / cnt / units::mm;
  }
  return rings;
}

void addTube(RenderScene& rs, const std::vector<Ring>& rings) {
  const std::array<float, 3> body = rs.material.body;
  // side wall
  const auto first = static_cast<std::uint32_t>(rs.vertices.size());
  for (const Ring& g : rings)
    for (int k = 0; k < kSides; ++k) {
      const double phi = 2 * kPi * k / kSides, cs = std::cos(phi), sn = std::sin(phi);
      const V3 dir = cs * g.a + sn * g.b;
      addVertex(rs, g.c + g.r * dir, dir, cs, sn, body, true);
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
      addVertex(rs, tip.c + tip.r * nrm, nrm, cs, sn, body, true);
    }
  }
  stitchRings(rs, tipFirst, kTipRings + 1, kSides);

  // base: a flat disc facing back along the axis
  const Ring& base = rings.front();
  const auto centre = static_cast<std::uint32_t>(rs.vertices.size());
  addVertex(rs, base.c, -base.t, 1, 0, body, false);
  for (int k = 0; k < kSides; ++k) {
    const double phi = 2 * kPi * k / kSides;
    addVertex(rs, base.c + base.r * (std::cos(phi) * base.a + std::sin(phi) * base.b), -base.t, 1, 0,
              body, false);
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

// a round bar length: 1, 2 or 5 times a power of ten [mm], at most maxMm
double niceLength(double maxMm) {
  const double p = std::pow(10.0, std::floor(std::log10(maxMm)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= maxMm) return m * p;
  return p;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void addOverlays(RenderScene& rs, const Snapshot& s, const SceneInfo& info, const View& view) {
  if (!view.overlays) return;
  // text scales with the shorter side, so portrait frames get the same text as landscape ones
  const float font = std::max(12.0f, static_cast<float>(std::min(view.width, view.height)) / 26.0f);
  const bool portrait = view.height > view.width;
  const float m = 0.7f * font;
  if (view.showTime)
    rs.texts.push_back({"t = " + fmt("%.1f", s.timeH) + " h", m, m, font, OverlayText::Anchor::TopLeft});
  if (view.showParams) {
    std::string p = "\xCE\xB1 = " + fmt("%.0f", info.alphaDeg) + "\xC2\xB0    \xCE\xB2 = " + fmt("%.3g", info.beta) +
                    "    \xCE\xB3 = " + fmt("%.3g", info.gamma);
    if (info.rTau != 0.0) p += "    R\xCF\x84 = " + fmt("%.3g", info.rTau);
    // landscape: top right, beside the time; portrait: a second line under the time
    if (portrait)
      rs.texts.push_back({p, m, m + (view.showTime ? 1.5f * font : 0.0f), font, OverlayText::Anchor::TopLeft});
    else
      rs.texts.push_back({p, static_cast<float>(view.width) - m, m, font, OverlayText::Anchor::TopRight});
  }
  if (view.showTitle && !info.title.empty())
    rs.texts.push_back({info.title, m, static_cast<float>(view.height) - m, font,
                        OverlayText::Anchor::BottomLeft});
  if (view.showScaleBar && rs.pxPerMm > 0) {
    const double lenMm = niceLength(0.22 * view.width / rs.pxPerMm);
    const float len = static_cast<float>(lenMm * rs.pxPerMm);
    const float h = std::max(3.0f, std::round(0.22f * font));
    const float x = std::round(static_cast<float>(view.width) - m - len);
    const float y = std::round(static_cast<float>(view.height) - m - h);
    rs.rects.push_back({x, y, std::round(len), h});
    const std::string label = (lenMm >= 1 ? fmt("%.0f", lenMm) : fmt("%.1f", lenMm)) + " mm";
    rs.texts.push_back({label, x + 0.5f * len, y - 0.35f * font, font, OverlayText::Anchor::BottomCentre});
  }
}

}  // namespace

Framing frameFor(const std::vector<Snapshot>& snaps, const SceneInfo& info, const View& view) {
  checkSize(view);
  if (snaps.empty()) throw RenderError("render: no snapshots to frame");
  const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
  const double inf = std::numeric_limits<double>::infinity();
  double u0 = inf, u1 = -inf, v0 = inf, v1 = -inf, wTop = 0.0, rMax = 0.0;
  for (const Snapshot& s : snaps) {
    checkSnapshot(s);
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
    f.widthMm = std::max({2 * hu, 2 * hv / usable * aspect, 1.0});
  }
  f.heightMm = f.widthMm / aspect;
  f.topW = wTop + rMax;
  return f;
}

Eigen::Vector2d topViewPixel(const Framing& f, const View& view, double u, double v) {
  return {(u - (f.centreU - 0.5 * f.widthMm)) / f.widthMm * view.width,
          ((f.centreV + 0.5 * f.heightMm) - v) / f.heightMm * view.height};
}

RenderScene buildRenderScene(const Snapshot& snap, const SceneInfo& info, const View& view,
                             const Framing& framing) {
  checkSize(view);
  checkSnapshot(snap);
  if (!(framing.widthMm > 0) || !(framing.heightMm > 0))
    throw RenderError("render: framing must have a positive width and height (got " +
                      std::to_string(framing.widthMm) + " x " + std::to_string(framing.heightMm) + " mm)");
  RenderScene rs;
  rs.width = view.width;
  rs.height = view.height;
  rs.fontPath = view.fontPath;
  rs.material.stripeCos = static_cast<float>(std::cos(view.stripeHalfWidthDeg * units::deg));

  // the root
  const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
  const std::vector<Ring> rings = nodeRings(snap, pf);
  rs.vertices.reserve(static_cast<size_t>((rings.size() + kTipRings + 2) * kSides));
  rs.indices.reserve(rs.vertices.capacity() * 6);
  addTube(rs, rings);
  if (view.whiskers) addWhiskers(rs, rings);

  // camera
  const auto cu = static_cast<float>(framing.centreU), cv = static_cast<float>(framing.centreV);
  const auto hw = static_cast<float>(0.5 * framing.widthMm), hh = static_cast<float>(0.5 * framing.heightMm);
  const float aspect = static_cast<float>(view.width) / static_cast<float>(view.height);
  glm::vec3 light;
  if (view.kind == View::Kind::Top) {
    // orthographic along -n: u to the right, v (uphill) up, so downhill points down the image
    const float eyeW = 1000.0f;
    rs.viewMatrix = toArray(glm::lookAt(glm::vec3(cu, cv, eyeW), glm::vec3(cu, cv, 0), glm::vec3(0, 1, 0)));
    rs.projMatrix = toArray(glm::ortho(-hw, hw, -hh, hh, 1.0f, 2.0f * eyeW));
    rs.pxPerMm = view.width / framing.widthMm;
    rs.plate.u0 = cu - 1.05f * hw, rs.plate.u1 = cu + 1.05f * hw;
    rs.plate.v0 = cv - 1.05f * hh, rs.plate.v1 = cv + 1.05f * hh;
    light = glm::normalize(glm::vec3(-0.35f, 0.5f, 1.0f));
  } else {
    // oblique preset: from above the plate, in front of its lower right part, uphill up the image
    const float fovY = glm::radians(30.0f);
    const glm::vec3 target(cu, cv, 0.5f * static_cast<float>(framing.topW));
    const glm::vec3 dir = glm::normalize(glm::vec3(0.45f, -0.85f, 1.0f));
    const float fit = std::max(hh, hw / aspect);
    const float dist = 1.05f * fit / std::tan(0.5f * fovY);
    rs.viewMatrix = toArray(glm::lookAt(target + dist * dir, target, glm::vec3(0, 1, 0)));
    rs.projMatrix = toArray(glm::perspective(fovY, aspect, 0.02f * dist, 20.0f * dist));
    const float ext = 4.0f * std::max(hw, hh);
    rs.plate.u0 = cu - ext, rs.plate.u1 = cu + ext;
    rs.plate.v0 = cv - ext, rs.plate.v1 = cv + ext;
    light = glm::normalize(glm::vec3(-0.3f, 0.6f, 1.0f));
  }
  rs.lightDir = {light.x, light.y, light.z};

  // background: the plate, a plain light field without one, or nothing (transparent)
  rs.plate.visible = info.plate && !view.transparent;
  if (view.transparent)
    rs.background = {0, 0, 0, 0};
  else if (info.plate)
    rs.background = {1, 1, 1, 1};
  else
    rs.background = {rs.plate.colour[0], rs.plate.colour[1], rs.plate.colour[2], 1};

  addOverlays(rs, snap, info, view);
  return rs;
}

}  // namespace rootsim
