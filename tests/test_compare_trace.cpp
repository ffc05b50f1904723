// a run as the trace sees it (src/analysis/compare_trace.cpp): its height off the plate dropped, and the
// snapshot a trace of one time is compared with chosen by the root's length on the plate

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "rootsim/compare_trace.hpp"
#include "rootsim/units.hpp"

using namespace rootsim;
using namespace rootsim::app;

namespace {

// a straight root of length L [mm] from the plate's origin, rising off the plate by the fraction rise of
// its length per unit length, downhill otherwise (lab frame [m])
Snapshot risingRoot(const Model& m, double lengthMm, double rise, int step) {
  const PlateFrame pf = m.env.plane.frame();
  const Eigen::Vector3d dir = (std::sqrt(1.0 - rise * rise) * pf.downhill + rise * pf.normal).normalized();
  Snapshot s;
  s.step = step;
  s.timeH = 0.1 * step;
  const int n = 40;
  s.x.resize(3, n + 1);
  for (int i = 0; i <= n; ++i) s.x.col(i) = dir * (lengthMm * i / n) * units::mm;
  return s;
}

}  // namespace

TEST_CASE("a run is compared as the plate shows it: its height dropped and its snapshot as long on the plate as the trace") {
  Model m;
  // every 0.1 mm from 10 to 12 mm, a fifth of it off the plate: on the plate 0.98 of it
  const double rise = 0.2, onPlate = std::sqrt(1.0 - rise * rise);
  std::vector<Snapshot> snaps;
  for (int k = 0; k <= 20; ++k) snaps.push_back(risingRoot(m, 10.0 + 0.1 * k, rise, k));
  const SimRoot s = simRootOf(m, snaps[10], TraceTarget{});
  CHECK(s.plateMm.row(2).cwiseAbs().maxCoeff() == 0.0);
  CHECK(s.traits.lengthMm == doctest::Approx(11.0 * onPlate).epsilon(1e-12));
  CHECK(s.plateMm(1, s.plateMm.cols() - 1) == doctest::Approx(11.0 * onPlate).epsilon(1e-12));
  // a trace 10.9 mm long: the snapshot whose root is nearest 10.9 mm on the plate (11.12 mm of root: the
  // 11th, 11.1 mm), not the one 10.9 mm long in three dimensions (the 9th)
  const int k = snapshotOfLength(m, snaps, 10.9);
  CHECK(k == 11);
  CHECK(std::abs((10.0 + 0.1 * k) * onPlate - 10.9) <= 0.05 * onPlate);
  // a trace longer than every snapshot on the plate: the last; shorter than all: the first
  CHECK(snapshotOfLength(m, snaps, 11.9) == 20);
  CHECK(snapshotOfLength(m, snaps, 5.0) == 0);
}
