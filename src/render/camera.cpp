// the follow camera: the tip region's centre per snapshot, smoothed by a critically damped follow run
// forward and backward (zero lag), then held near the target
#include "rootsim/camera.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rootsim/image.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {

// x'' = w^2 (target - x) - 2 w x' (critically damped, w = 1 / tau) over the targets, one frame per
// step in 8 semi-implicit Euler sub-steps, the target interpolated linearly within a frame
std::vector<Eigen::Vector2d> criticallyDamped(const std::vector<Eigen::Vector2d>& target, double tau) {
  std::vector<Eigen::Vector2d> out(target.size());
  if (target.empty()) return out;
  const double w = 1.0 / std::max(tau, 1e-6);
  constexpr int kSub = 8;
  const double h = 1.0 / kSub;
  Eigen::Vector2d x = target[0], v = Eigen::Vector2d::Zero();
  out[0] = x;
  for (std::size_t k = 1; k < target.size(); ++k) {
    for (int j = 1; j <= kSub; ++j) {
      const Eigen::Vector2d tgt = target[k - 1] + (target[k] - target[k - 1]) * (j * h);
      v += h * (w * w * (tgt - x) - 2.0 * w * v);
      x += h * v;
    }
    out[k] = x;
  }
  return out;
}

}  // namespace

double tipRegionLength(double widthMm, double heightMm) { return 0.25 * std::min(widthMm, heightMm); }

Eigen::Vector2d tipRegionCentre(const Snapshot& s, const PlateFrame& pf, double lengthMm) {
  const long nn = s.x.cols();
  if (nn < 1) throw RenderError("follow camera: snapshot of step " + std::to_string(s.step) + " has no nodes");
  Eigen::Vector2d acc = Eigen::Vector2d::Zero();
  double got = 0.0;
  Eigen::Vector3d b = pf.toPlateMm(s.x.col(nn - 1));
  // the last root's nodes only (a plate's snapshot: the followed root is the last)
  const long first = s.rootStarts.empty() ? 0 : s.rootStarts.back();
  for (long i = nn - 1; i > first && got < lengthMm; --i) {
    const Eigen::Vector3d a = pf.toPlateMm(s.x.col(i - 1));
    const double len = (b - a).head<2>().norm();
    if (len > 0) {
      // the part of segment a-b within the region (measured from b)
      const double take = std::min(len, lengthMm - got);
      const Eigen::Vector2d end = b.head<2>() + (a.head<2>() - b.head<2>()) * (take / len);
      acc += take * 0.5 * (b.head<2>() + end);
      got += take;
    }
    b = a;
  }
  if (got <= 0.0) return pf.toPlateMm(s.x.col(nn - 1)).head<2>();
  return acc / got;
}

std::vector<Framing> followFramings(const std::vector<Snapshot>& snaps, const SceneInfo& info, int width,
                                    int height, const FollowOptions& opt) {
  if (!(opt.fieldMm > 0)) throw RenderError("follow camera: field width must be > 0 mm (got " + std::to_string(opt.fieldMm) + ")");
  if (width <= 0 || height <= 0) throw RenderError("follow camera: size must be positive");
  if (snaps.empty()) throw RenderError("follow camera: no snapshots");
  const PlateFrame pf = PlateFrame::tilted(info.alphaDeg * units::deg);
  const double wMm = opt.fieldMm, hMm = opt.fieldMm * height / width;
  const double region = tipRegionLength(wMm, hMm);
  std::vector<Eigen::Vector2d> target;
  target.reserve(snaps.size());
  double wTop = 0.0, rMax = 0.0;  // as frameFor: highest node and largest radius [mm]
  for (const Snapshot& s : snaps) {
    target.push_back(tipRegionCentre(s, pf, region));
    for (long i = 0; i < s.x.cols(); ++i) wTop = std::max(wTop, pf.toPlateMm(s.x.col(i)).z());
    if (s.radius.size() > 0) rMax = std::max(rMax, s.radius.maxCoeff() / units::mm);
  }
  const double topW = wTop + rMax;
  // forward, then backward over the forward result: a zero-lag, smooth path
  std::vector<Eigen::Vector2d> fwd = criticallyDamped(target, opt.smoothFrames);
  std::reverse(fwd.begin(), fwd.end());
  std::vector<Eigen::Vector2d> path = criticallyDamped(fwd, opt.smoothFrames);
  std::reverse(path.begin(), path.end());
  std::vector<Framing> out(snaps.size());
  for (std::size_t k = 0; k < snaps.size(); ++k) {
    Eigen::Vector2d c = path[k];
    const Eigen::Vector2d lim(opt.keepCentral * wMm, opt.keepCentral * hMm);
    c = target[k] + (c - target[k]).cwiseMax(-lim).cwiseMin(lim);
    Framing& f = out[k];
    f.centreU = c.x();
    f.centreV = c.y();
    f.widthMm = wMm;
    f.heightMm = hMm;
    f.topW = topW;
  }
  return out;
}

}  // namespace rootsim
