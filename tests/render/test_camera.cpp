// The follow camera (src/render/camera.cpp): the tip region's centre is the arc-length centroid of the
// last part of the centreline (of the last root of a plate), its length a quarter of the shorter side,
// and a root that does not move is followed without drift.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "rootsim/camera.hpp"
#include "rootsim/environment.hpp"
#include "rootsim/image.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/render_scene.hpp"
#include "rootsim/snapshot.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;

namespace {
// a straight root 3 mm long on a plate at 40 deg, 0.1 mm elements, downhill from the origin
Snapshot straightRoot(const Plane& plane, double angle = 0.0) {
  RodParams p;
  InitialShape sh;
  sh.length = 3e-3;
  sh.elementLength = 1e-4;
  sh.perturbation = 0.0;
  sh.angle = angle;
  Snapshot s = makeSnapshot(p, makeInitialRod(p, plane, sh), RodStrains{}, 0);
  s.plateForce = Eigen::VectorXd::Zero(s.x.cols());  // a run's snapshots carry it beside kappa0
  return s;
}
}  // namespace

TEST_CASE("follow camera: the tip region is a quarter of the shorter side") {
  CHECK(tipRegionLength(4.0, 3.0) == 0.75);
  CHECK(tipRegionLength(2.0, 8.0) == 0.5);
}

TEST_CASE("follow camera: the tip region's centre of a straight root lies half the region back from the tip") {
  Plane plane;
  const PlateFrame pf = plane.frame();
  const Snapshot s = straightRoot(plane);
  const Eigen::Vector3d tip = pf.toPlateMm(s.x.col(s.x.cols() - 1));
  // downhill is -v in the top view: half a millimetre back from the tip is +0.5 mm in v
  const Eigen::Vector2d c = tipRegionCentre(s, pf, 1.0);
  CHECK((c - (tip.head<2>() + Eigen::Vector2d(0.0, 0.5))).norm() < 1e-12);
  // a region longer than the root: the centroid of the whole root
  const Eigen::Vector3d base = pf.toPlateMm(s.x.col(0));
  CHECK((tipRegionCentre(s, pf, 50.0) - 0.5 * (tip + base).head<2>()).norm() < 1e-12);
  // a root sown at 90 deg runs along +u
  const Snapshot side = straightRoot(plane, 90.0 * units::deg);
  const Eigen::Vector3d sideTip = pf.toPlateMm(side.x.col(side.x.cols() - 1));
  CHECK((tipRegionCentre(side, pf, 1.0) - (sideTip.head<2>() - Eigen::Vector2d(0.5, 0.0))).norm() < 1e-12);
}

TEST_CASE("follow camera: of a plate's merged roots only the last is followed") {
  Plane plane;
  const PlateFrame pf = plane.frame();
  const Snapshot a = straightRoot(plane), b = straightRoot(plane, 90.0 * units::deg);
  const Snapshot merged = mergeRoots({a, b});
  CHECK((tipRegionCentre(merged, pf, 50.0) - tipRegionCentre(b, pf, 50.0)).norm() < 1e-12);
}

TEST_CASE("follow camera: a root that does not move is framed at its tip region in every frame, the field as asked") {
  Plane plane;
  const std::vector<Snapshot> snaps(5, straightRoot(plane));
  SceneInfo info;
  FollowOptions opt;
  opt.fieldMm = 2.0;
  const std::vector<Framing> f = followFramings(snaps, info, 640, 480, opt);
  REQUIRE(f.size() == 5);
  const Eigen::Vector2d want = tipRegionCentre(snaps[0], plane.frame(), tipRegionLength(2.0, 1.5));
  for (const Framing& g : f) {
    CHECK(std::abs(g.centreU - want.x()) < 1e-12);
    CHECK(std::abs(g.centreV - want.y()) < 1e-12);
    CHECK(g.widthMm == 2.0);
    CHECK(g.heightMm == doctest::Approx(1.5).epsilon(1e-15));
  }
  opt.fieldMm = 0.0;
  CHECK_THROWS_AS(followFramings(snaps, info, 640, 480, opt), RenderError);
  opt.fieldMm = 2.0;
  CHECK_THROWS_AS(followFramings({}, info, 640, 480, opt), RenderError);
}
