#pragma once
// The root as a tube: one ring per node (centre, material frame, radius) in the top view's plate
// coordinates [mm] (PlateFrame::toPlateMm). The one place the tube's frames are computed: the renderer
// (render_scene.cpp) and the glTF writer (src/app/gltf.cpp) both sweep their surfaces round these rings.
// No GL here.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rootsim/environment.hpp"
#include "rootsim/snapshot.hpp"

namespace rootsim {

// a ring of the tube: centre, unit tangent t, unit d1 normal to t, b = t x a (d2), radius; plate mm
struct TubeRing {
  Eigen::Vector3d c, t, a, b;
  double r;
};

// a snapshot the tube can be built from: n >= 1 elements, n + 1 nodes, finite values; else RenderError
// "<what>: snapshot of step N has inconsistent shapes (...)" or "... has non-finite values"
void checkTubeSnapshot(const Snapshot& s, const std::string& what);

// node rings from the element directors, averaged at interior nodes (smooth shading and stripes); a
// surface point at angle phi from d1 towards d2 is c + r (cos phi a + sin phi b). The snapshot's shapes
// must be consistent (n elements, n + 1 nodes).
std::vector<TubeRing> tubeRings(const Snapshot& s, const PlateFrame& pf);

}  // namespace rootsim
