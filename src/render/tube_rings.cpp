// the tube's rings (include/rootsim/tube_rings.hpp): shared by the renderer and the glTF writer
#include "rootsim/tube_rings.hpp"

#include <Eigen/Geometry>

#include "rootsim/image.hpp"

namespace rootsim {

void checkTubeSnapshot(const Snapshot& s, const std::string& what) {
  const long n = s.radius.size();
  if (n < 1 || s.x.cols() != n + 1 || s.d1.cols() != n || s.d3.cols() != n)
    throw RenderError(what + ": snapshot of step " + std::to_string(s.step) +
                      " has inconsistent shapes (elements " + std::to_string(n) + ", nodes " +
                      std::to_string(s.x.cols()) + ", d1 " + std::to_string(s.d1.cols()) + ", d3 " +
                      std::to_string(s.d3.cols()) + ")");
  if (!s.x.allFinite() || !s.d1.allFinite() || !s.d3.allFinite() || !s.radius.allFinite())
    throw RenderError(what + ": snapshot of step " + std::to_string(s.step) + " has non-finite values");
}

std::vector<TubeRing> tubeRings(const Snapshot& s, const PlateFrame& pf) {
  using V3 = Eigen::Vector3d;
  const int n = s.elements();
  std::vector<TubeRing> rings(static_cast<size_t>(n + 1));
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
    TubeRing& g = rings[static_cast<size_t>(i)];
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

}  // namespace rootsim
