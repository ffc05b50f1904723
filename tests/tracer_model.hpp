#pragma once
// A root drawn as a tracer draws it (docs/experiments.md, "Validation on roots degraded as a tracer
// degrades them"): the tracer's error is not white. Its centreline sits anywhere across the root's image
// and drifts slowly along it, snaps to an edge for a few points at a time, steps in whole pixels held
// over several rows, and jitters. Shared by the physics tests that validate the trace measurement.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Core>

#include "rootsim/traits.hpp"

namespace rootsim::test {

// a deterministic uniform in (0, 1) and a Gaussian by Box-Muller (the same numbers on every platform)
struct TracerRng {
  unsigned long long s;
  double uniform() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(s >> 11) + 0.5) / 9007199254740992.0;
  }
  double normal() { return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * std::numbers::pi * uniform()); }
};

struct TracerModel {
  double pxPerMm = 24;
  double stepPx = 4;          // a point every stepPx of the root's arc length
  double jitterPx = 1;        // white Gaussian jitter per image coordinate
  double radiusMm = 0.1;      // the root's radius: the centreline's placement stays within +-R of it
  double offsetCorrMm = 1.0;  // correlation length of the placement offset along the root
  double snapEvery = 20;      // one point in snapEvery starts a snap: the point and the next 0-3 sit on
                              // the nearer edge of the root (offset +-R)
  double holdPx = 1.0;        // whole-pixel coordinates; the tracer keeps its previous pixel in a
                              // coordinate until the target is holdPx or more away (0.5: plain rounding)
  unsigned long long seed = 1;
};

// the truth curve (plate coordinates [mm], base first) traced by t, in plate coordinates [mm]. The
// placement offset is R (2 Phi(g) - 1) with g a unit Gaussian AR(1) process of correlation length
// offsetCorrMm: uniform across the root's width at every point, correlated along it
inline Eigen::Matrix3Xd traceLikeTracer(const Eigen::Matrix3Xd& truthMm, const TracerModel& t) {
  const Eigen::Matrix3Xd p = resampleByArcLength(truthMm, t.stepPx / t.pxPerMm);
  TracerRng rng{t.seed * 0x9E3779B97F4A7C15ULL + 7};
  const int n = static_cast<int>(p.cols());
  const double ds = t.stepPx / t.pxPerMm, rho = std::exp(-ds / t.offsetCorrMm);
  double g = rng.normal();
  int snapLeft = 0;
  Eigen::Matrix3Xd q(3, n);
  Eigen::Vector2d prev(0, 0);
  for (int i = 0; i < n; ++i) {
    if (i > 0) g = rho * g + std::sqrt(1.0 - rho * rho) * rng.normal();
    double offsetMm = t.radiusMm * std::erf(g / std::sqrt(2.0));  // R (2 Phi(g) - 1)
    if (snapLeft == 0 && rng.uniform() < 1.0 / t.snapEvery) snapLeft = 1 + static_cast<int>(4.0 * rng.uniform());
    if (snapLeft > 0) {
      offsetMm = offsetMm >= 0 ? t.radiusMm : -t.radiusMm;
      --snapLeft;
    }
    const int a = std::max(0, i - 1), b = std::min(n - 1, i + 1);
    const Eigen::Vector2d tan = (p.col(b) - p.col(a)).head<2>().normalized();
    const Eigen::Vector2d nrm(-tan.y(), tan.x());
    Eigen::Vector2d px = (p.col(i).head<2>() + offsetMm * nrm) * t.pxPerMm + Eigen::Vector2d(100.3, 57.6);  // an image's offset
    px += t.jitterPx * Eigen::Vector2d(rng.normal(), rng.normal());
    Eigen::Vector2d at(std::round(px.x()), std::round(px.y()));
    if (i > 0)
      for (int c = 0; c < 2; ++c)
        if (std::abs(px[c] - prev[c]) < t.holdPx) at[c] = prev[c];
    prev = at;
    q.col(i) = Eigen::Vector3d(at.x(), at.y(), 0.0) / t.pxPerMm;
  }
  return q;
}

}  // namespace rootsim::test
