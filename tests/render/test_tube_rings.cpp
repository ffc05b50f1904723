// The root as a tube (src/render/tube_rings.cpp): one ring per node at the node, its tangent, d1 and d2 in
// the top view's plate axes and its radius in mm; snapshots the tube cannot be built from are refused.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "rootsim/environment.hpp"
#include "rootsim/image.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/tube_rings.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;

namespace {
Snapshot straightRoot(const Plane& plane, int elements) {
  RodParams p;
  InitialShape sh;
  sh.length = elements * 1e-4;
  sh.elementLength = 1e-4;
  sh.perturbation = 0.0;
  return makeSnapshot(p, makeInitialRod(p, plane, sh), RodStrains{}, 3);
}
}  // namespace

TEST_CASE("tube rings: a straight root's rings sit at its nodes, t downhill (-v), a = d1 along +u, b = t x a out of the plate, r = R") {
  Plane plane;
  const PlateFrame pf = plane.frame();
  const Snapshot s = straightRoot(plane, 8);
  const std::vector<TubeRing> rings = tubeRings(s, pf);
  REQUIRE(rings.size() == 9);
  for (std::size_t i = 0; i < rings.size(); ++i) {
    const TubeRing& g = rings[i];
    INFO("node " << i);
    CHECK((g.c - pf.toPlateMm(s.x.col(static_cast<Eigen::Index>(i)))).norm() < 1e-14);
    CHECK((g.t - Eigen::Vector3d(0, -1, 0)).norm() < 1e-12);
    CHECK((g.a - Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);
    CHECK((g.b - g.t.cross(g.a)).norm() < 1e-12);
    CHECK((g.b - Eigen::Vector3d(0, 0, 1)).norm() < 1e-12);
    CHECK(std::abs(g.r - 0.1) < 1e-15);  // R = 0.1 mm
  }
  // the nodes are 0.1 mm apart along -v
  CHECK(std::abs((rings[1].c - rings[0].c).y() + 0.1) < 1e-12);
}

TEST_CASE("tube rings: a snapshot of inconsistent shapes or non-finite values is refused naming what and the step") {
  Plane plane;
  Snapshot s = straightRoot(plane, 4);
  CHECK_NOTHROW(checkTubeSnapshot(s, "render"));
  Snapshot bad = s;
  bad.radius.resize(3);
  CHECK_THROWS_WITH_AS(checkTubeSnapshot(bad, "render"), doctest::Contains("render: snapshot of step 3 has inconsistent shapes"),
                       RenderError);
  bad = s;
  bad.x(1, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(checkTubeSnapshot(bad, "glTF"), doctest::Contains("glTF: snapshot of step 3 has non-finite values"),
                       RenderError);
}
