#pragma once
// shared helpers of the renderer tests: synthetic rods in the frame of docs/model.md (Frames and signs),
// colour classes of the tube's material, scratch folders, and an MP4 read back with libavformat
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <unistd.h>

#include "../scratch_support.hpp"
#include "rootsim/image.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"

namespace rtest {

constexpr double kDeg = std::numbers::pi / 180.0;

// a straight rod of n elements, length lengthMm, radius radiusMm, lying on a plate tilted by
// alphaDeg, base at the origin, axis along downhill g_par, touching the plate (centre at R n);
// d1 of the element centred at arc length s is x rotated by theta(s) [rad] about d3, so theta = 0 puts
// d1 on the lateral axis and theta = +90 deg puts it on d2 = n (toward the viewer of the top view)
inline rootsim::Snapshot straightRod(double alphaDeg, int n, double lengthMm, double radiusMm,
                                     const std::function<double(double)>& theta = {}) {
  const double a = alphaDeg * kDeg;
  const Eigen::Vector3d normal(0, -std::cos(a), std::sin(a)), downhill(0, -std::sin(a), -std::cos(a)),
      lateral(1, 0, 0);
  rootsim::Snapshot s;
  s.step = 7;
  s.timeH = 1.5;
  s.x.resize(3, n + 1);
  s.d1.resize(3, n);
  s.d3.resize(3, n);
  s.radius = Eigen::VectorXd::Constant(n, radiusMm * 1e-3);
  const double len = lengthMm * 1e-3, r = radiusMm * 1e-3;
  for (int i = 0; i <= n; ++i) s.x.col(i) = (len * i / n) * downhill + r * normal;
  for (int e = 0; e < n; ++e) {
    const double th = theta ? theta((e + 0.5) / n * lengthMm) : 0.0;
    s.d3.col(e) = downhill;
    s.d1.col(e) = std::cos(th) * lateral + std::sin(th) * downhill.cross(lateral);
  }
  return s;
}

// a view of w x h pixels, everything else as View's defaults
inline rootsim::View viewOf(int w, int h) {
  rootsim::View v;
  v.width = w;
  v.height = h;
  return v;
}

inline rootsim::SceneInfo info(double alphaDeg) {
  rootsim::SceneInfo si;
  si.alphaDeg = alphaDeg;
  si.beta = 0.2;
  si.gamma = 0.1;
  si.radius = 1e-4;
  si.title = "test";
  return si;
}

// what a tube pixel shows: by chromaticity, nearest of body / +d1 stripe / -d1 stripe
enum class Paint { Body, Plus, Minus };
inline Paint paint(const std::uint8_t* p) {
  const rootsim::RenderScene::Material m;
  auto chroma = [](double r, double g, double b) {
    const double s = r + g + b + 1e-9;
    return Eigen::Vector3d(r / s, g / s, b / s);
  };
  const Eigen::Vector3d c = chroma(p[0], p[1], p[2]);
  const double dBody = (c - chroma(m.body[0], m.body[1], m.body[2])).norm();
  const double dPlus = (c - chroma(m.plus[0], m.plus[1], m.plus[2])).norm();
  const double dMinus = (c - chroma(m.minus[0], m.minus[1], m.minus[2])).norm();
  if (dPlus < dBody && dPlus < dMinus) return Paint::Plus;
  if (dMinus < dBody && dMinus < dPlus) return Paint::Minus;
  return Paint::Body;
}
inline const char* name(Paint p) { return p == Paint::Plus ? "pink" : p == Paint::Minus ? "orange" : "body"; }

// a fresh scratch folder per test (ctest runs test cases in parallel processes), removed when the process ends
inline std::filesystem::path scratch(const std::string& testName) { return rootsim::test::scratchDir("render", testName); }

// FNV-1a of the pixels: printed when a determinism check fails
inline std::uint64_t hash(const rootsim::Image& img) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : img.rgba) h = (h ^ b) * 1099511628211ull;
  return h;
}

// an MP4 decoded back with libavformat / libavcodec
struct Decoded {
  int frames = 0;                 // decoded frames
  int width = 0, height = 0;      // [px]
  double durationS = 0.0;         // container duration [s]
  std::string codec, pixFmt;      // "h264", "yuv420p"
  int colorspace = 0;             // AVColorSpace of the stream
  rootsim::Image first;           // first frame converted back to RGBA with BT.709
};
Decoded decodeMp4(const std::string& path);

}  // namespace rtest
