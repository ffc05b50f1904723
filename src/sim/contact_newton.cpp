// The Newton solver's view of self-contact (contact_newton.hpp): the window's reach back to a contact,
// the nodes a contact couples off the band, and each pair's stiffness.
#include "rootsim/contact_newton.hpp"

#include <algorithm>
#include <array>

#include "contact_geometry.hpp"
#include "rootsim/high_water.hpp"

namespace rootsim {

using namespace contact_detail;

namespace {
// K = -dF/dx of a contact's forces on its nodes, by central differences over the four nodes' 12
// coordinates x (each moved by +-h, then restored): forces(f) evaluates F at the current x
template <class Forces, class Stiffness>
void stiffnessByCentralDifferences(std::array<Vec3, 4>& x, double h, Forces& forces, Stiffness& K) {
  Eigen::Matrix<double, Stiffness::RowsAtCompileTime, 1> fp, fm;
  for (int col = 0; col < 12; ++col) {
    double& xc = x[static_cast<size_t>(col / 3)][col % 3];
    const double x0 = xc;
    xc = x0 + h;
    forces(fp);
    xc = x0 - h;
    forces(fm);
    xc = x0;
    K.col(col) = -(fp - fm) / (2.0 * h);
  }
}
}  // namespace

int firstNodeNearContact(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw,
                         int from) {
  int first = s.nodes();
  if (!env.selfContact.enabled) return first;
  if (static_cast<int>(cw.order.size()) != s.elements()) cw.resize(s.elements());
  cw.invalidate();  // the pairs within 2R + skin of this very state (not of when the list was built)
  updatePairs(p, s, cw);
  for (const auto& [i, j] : cw.pairs)
    if (j + 1 >= from) first = std::min(first, i);  // i < j: the younger element reaches node `from`
  return first;
}

void markSelfContactNodes(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw) {
  if (static_cast<int>(cw.order.size()) != s.elements()) cw.resize(s.elements());
  std::fill(cw.contactNode.begin(), cw.contactNode.end(), 0);
  if (!env.selfContact.enabled) return;
  updatePairs(p, s, cw);
  for (const auto& [i, j] : cw.pairs) {
    if (pairGeometry(s, i, j).dist >= 2.0 * p.radius) continue;
    for (int a : {i, i + 1, j, j + 1}) cw.contactNode[static_cast<size_t>(a)] = 1;
  }
}

void selfContactStiffness(const RodParams& p, const Environment& env, const RodState& s, double h,
                          ContactWorkspace& cw) {
  cw.stiffness.clear();
  if (!env.selfContact.enabled) return;
  if (static_cast<int>(cw.order.size()) != s.elements()) cw.resize(s.elements());
  updatePairs(p, s, cw);
  const double k = env.selfContact.k;
  const Vec3 up = env.plane.normal();
  PairContact g;
  for (const auto& [i, j] : cw.pairs) {
    const std::array<int, 4> nodes{i, i + 1, j, j + 1};
    std::array<Vec3, 4> x;
    for (int a = 0; a < 4; ++a) x[static_cast<size_t>(a)] = s.x.col(nodes[static_cast<size_t>(a)]);
    if (!pairContact(p.radius, k, up, x[0], x[1], x[2], x[3], g)) continue;
    // forces on the four nodes of the pair at positions x (zero when apart)
    auto forces = [&](Eigen::Matrix<double, 12, 1>& f) {
      f.setZero();
      if (!pairContact(p.radius, k, up, x[0], x[1], x[2], x[3], g)) return;
      const Vec3 F = g.fn * g.nrm;
      f.segment<3>(0) = (1.0 - g.sa) * F;
      f.segment<3>(3) = g.sa * F;
      f.segment<3>(6) = -(1.0 - g.sb) * F;
      f.segment<3>(9) = -g.sb * F;
    };
    PairStiffness& ps = cw.stiffness.emplace_back();
    ps.i = i;
    ps.j = j;
    stiffnessByCentralDifferences(x, h, forces, ps.K);
  }
}

void neighbourContactStiffness(const RodParams& p, const Environment& env, const RodState& s, double h,
                                ContactWorkspace& cw) {
  cw.neighbourStiffness.clear();
  const NeighbourCapsules& nb = cw.neighbours;
  // a stiffness per listed pair at most: room for as many as the pairs' list has (the plate sizes it)
  reserveHighWater(cw.neighbourStiffness, nb.pairs.capacity());
  const Vec3 up = env.plane.normal();
  for (const std::array<int, 2>& pair : nb.pairs) {
    // plain ints, not a structured binding: the lambda below captures c (clang rejects capturing bindings)
    const int i = pair[0], c = pair[1];
    std::array<Vec3, 4> x{s.x.col(i), s.x.col(i + 1), nb.a.col(c), nb.b.col(c)};
    Vec3 F;
    double w1 = 0;
    if (!neighbourPairForce(p, env, up, nb, c, x[0], x[1], x[2], x[3], F, w1)) continue;
    // the forces on this root's two nodes at positions x (zero when apart)
    auto forces = [&](Eigen::Matrix<double, 6, 1>& f) {
      f.setZero();
      if (!neighbourPairForce(p, env, up, nb, c, x[0], x[1], x[2], x[3], F, w1)) return;
      f.segment<3>(0) = (1.0 - w1) * F;
      f.segment<3>(3) = w1 * F;
    };
    NeighbourStiffness& ns = cw.neighbourStiffness.emplace_back();
    ns.i = i;
    ns.c = c;
    stiffnessByCentralDifferences(x, h, forces, ns.K);
  }
}

}  // namespace rootsim
