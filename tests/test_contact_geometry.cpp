// The geometry of the contact pieces (src/sim/contact_geometry.cpp): the closest points of two segments
// and the self-contact Verlet list, against brute force over every element pair.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "contact_geometry.hpp"
#include "physics_support.hpp"
#include "rootsim/contact.hpp"

using namespace rootsim;

namespace {
// a hairpin of elements 0.5 R long: up along +y at x = 0 for 12 R, across to x = gap, back down
RodState hairpin(const RodParams& p, double gap) {
  const double R = p.radius, l = 0.5 * R;
  std::vector<Vec3> pts;
  for (int i = 0; i <= 24; ++i) pts.push_back(Vec3(0, i * l, 0));
  const int across = static_cast<int>(std::ceil(gap / l));
  for (int i = 1; i <= across; ++i) pts.push_back(Vec3(gap * i / across, 24 * l, 0));
  for (int i = 1; i <= 24; ++i) pts.push_back(Vec3(gap, (24 - i) * l, 0));
  RodState s;
  s.resize(static_cast<int>(pts.size()) - 1);
  s.S[0] = 0.0;
  for (int i = 0; i < s.nodes(); ++i) s.x.col(i) = pts[static_cast<size_t>(i)];
  for (int i = 0; i < s.elements(); ++i) s.S[i + 1] = s.S[i] + (s.x.col(i + 1) - s.x.col(i)).norm();
  return s;
}
// every pair not excluded along the rod whose segments come within 2R + skin, by brute force
std::vector<std::array<int, 2>> bruteForcePairs(const RodParams& p, const RodState& s) {
  const double reach = 2.0 * p.radius + contact_detail::kSkinRadii * p.radius;
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i < s.elements(); ++i)
    for (int j = i + 2; j < s.elements(); ++j) {
      if (s.S[j] - s.S[i + 1] < kSelfExclusionRadii * p.radius) continue;
      double a = 0, b = 0;
      closestSegmentPoints(s.x.col(i), s.x.col(i + 1), s.x.col(j), s.x.col(j + 1), a, b);
      const Vec3 d = (s.x.col(i) + a * (s.x.col(i + 1) - s.x.col(i))) - (s.x.col(j) + b * (s.x.col(j + 1) - s.x.col(j)));
      if (d.norm() < reach) pairs.push_back({i, j});
    }
  return pairs;
}
}  // namespace

TEST_CASE("segment closest points: crossing, parallel overlap and end cases") {
  double a = 0, b = 0;
  closestSegmentPoints(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -1, 1), Vec3(0.5, 1, 1), a, b);
  CHECK(a == doctest::Approx(0.75));
  CHECK(b == doctest::Approx(0.5));
  // parallel, overlapping over x in [0, 1]: the middle of the overlap
  closestSegmentPoints(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(-1, 0, 1), Vec3(1, 0, 1), a, b);
  CHECK(a == doctest::Approx(0.25));
  CHECK(b == doctest::Approx(0.75));
  // end to end
  closestSegmentPoints(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 2, 0), a, b);
  CHECK(a == doctest::Approx(1.0));
  CHECK(b == doctest::Approx(0.0));
}

TEST_CASE("self-contact list: the Verlet list holds exactly the pairs within 2R + skin, sorted, and serves until a node moves skin/2") {
  RodParams p;
  size_t listedNear = 0;
  for (const double gap : {2.5, 3.5}) {
    INFO("legs " << gap << " R apart");
    RodState s = hairpin(p, gap * p.radius);
    ContactWorkspace cw;
    cw.resize(s.elements());
    contact_detail::updatePairs(p, s, cw);
    const auto want = bruteForcePairs(p, s);
    CHECK(cw.pairs == want);
    CHECK(std::is_sorted(cw.pairs.begin(), cw.pairs.end()));
    CHECK(cw.builds == 1);
    if (gap == 2.5) {
      listedNear = cw.pairs.size();
      CHECK(listedNear >= 20);  // every element of one leg lies within 3R of the other leg
    } else {
      CHECK(cw.pairs.size() < listedNear / 4);
    }
    // a rigid shift by 0.4 skin keeps the list; 0.6 skin rebuilds it
    const double skin = contact_detail::kSkinRadii * p.radius;
    s.x.colwise() += Vec3(0, 0, 0.4 * skin);
    contact_detail::updatePairs(p, s, cw);
    CHECK(cw.builds == 1);
    s.x.colwise() += Vec3(0, 0, 0.2 * skin);
    contact_detail::updatePairs(p, s, cw);
    CHECK(cw.builds == 2);
    CHECK(cw.pairs == want);
    // a grown rod (a longer rest length) rebuilds whatever moved
    s.S[s.elements()] += 1e-9;
    contact_detail::updatePairs(p, s, cw);
    CHECK(cw.builds == 3);
  }
}
