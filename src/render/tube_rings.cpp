// the tube's rings (include/rootsim/tube_rings.hpp): shared by the renderer and the glTF writer
#include "rootsim/tube_rings.hpp"

#include <Eigen/Geometry>

#include "rootsim/image.hpp"
#include "rootsim/node_fields.hpp"
#include "rootsim/units.hpp"

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
  // the material frame at the nodes (node_fields.hpp), its directions in the top view's plate axes
  const std::vector<NodeFrame> frames = nodeFrames(s, [&](const Eigen::Vector3d& d) { return pf.dirToPlate(d); });
  std::vector<TubeRing> rings(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    TubeRing& g = rings[i];
    g.c = pf.toPlateMm(s.x.col(static_cast<Eigen::Index>(i)));
    g.t = frames[i].t;
    g.a = frames[i].d1;
    g.b = frames[i].d2;
    g.r = frames[i].radius / units::mm;
  }
  return rings;
}

}  // namespace rootsim
