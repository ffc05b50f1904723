// A plate of roots (docs/plate.md): each root relaxes in its own frame with the other roots near it as
// capsules it cannot enter (ContactWorkspace::neighbours); the roots within reach of another then relax
// together as one Newton system (relaxNewtonCoupled), so every root is in equilibrium with the others'
// final shapes.
#include "rootsim/plate.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "rootsim/contact.hpp"
#include "rootsim/high_water.hpp"
#include "rootsim/initial.hpp"
#include "rootsim/tolerance.hpp"
#include "rootsim/units.hpp"

namespace rootsim {

namespace {

// Verlet skin of the lists between roots, in contact distances Ra + Rb: a capsule is listed for an
// element within Ra + Rb + skin; the lists are built again before every relaxation, so the skin only
// covers what one relaxation moves (a growth step's snap: checked after it by the next sweep)
constexpr double kPlateSkin = 1.0;
// explicit joint relaxations (after the coupled Newton stalled) before a step fails; sub-steps of a joint
// relaxation between its lists' rebuilds
constexpr int kJointRelaxations = 3;
constexpr long kJointRelist = 256;
// Before those, the first stalls of a step hand the roots back to the coupled Newton after a short
// explicit relaxation (PlateSimulation::kJointBudget, kJointHandBacks): where the coupled Newton crawls
// from where growth left the roots, a few sub-steps move them into its reach and it converges from there
// to the same tolerance (docs/plate.md, Solving); a snap runs through the longer ones, and the full joint
// relaxations after them

long long cellKey(long long cx, long long cy) { return (cx + (1LL << 30)) * (1LL << 31) + (cy + (1LL << 30)); }

// a root's error naming its seedling; a scene of one root alone (a plate of one, no name) keeps its own text
RelaxError namedError(const std::string& root, const std::exception& e) {
  return RelaxError(root.empty() ? std::string(e.what()) : "seedling " + root + ": " + e.what());
}

}  // namespace

PlateSimulation::PlateSimulation(const PlateParams& plate, std::vector<Seedling> seedlings)
    : plate_(plate), seedlings_(std::move(seedlings)) {
  frame_ = seedlings_.empty() ? PlateFrame{} : seedlings_.front().model.env.plane.frame();
  for (const Seedling& sd : seedlings_) offset_.push_back(sd.position.x() * frame_.lateral + sd.position.y() * frame_.downhill);
  // each root is built (and relaxed once) alone: the initial roots lie apart (checked by the scene)
  for (const Seedling& sd : seedlings_) {
    try {
      roots_.push_back(std::make_unique<Simulation>(sd.model));
    } catch (const RelaxError& e) {
      throw namedError(sd.name, e);
    }
  }
  nextSite_.assign(roots_.size(), 0);
  sideStream_ = plate_.laterals.seed;
  last_ = observe(1);
}

PlateSimulation::PlateSimulation(const PlateParams& plate, std::vector<Seedling> seedlings, const PlateCarry& c)
    : plate_(plate), seedlings_(std::move(seedlings)) {
  const size_t n = seedlings_.size();
  if (c.roots.size() != n + c.laterals.size() || c.nextSite.size() != c.roots.size())
    throw std::invalid_argument("a plate's carry does not fit its seedlings (roots, laterals or sites)");
  frame_ = seedlings_.empty() ? PlateFrame{} : seedlings_.front().model.env.plane.frame();
  for (const Seedling& sd : seedlings_) offset_.push_back(sd.position.x() * frame_.lateral + sd.position.y() * frame_.downhill);
  for (size_t r = 0; r < n; ++r)
    roots_.push_back(std::make_unique<Simulation>(seedlings_[r].model, c.roots[r].state, c.roots[r].carry));
  nextSite_.assign(n, 0);
  // the laterals in the order they emerged, each from its parent (an earlier root) as emergeLaterals built it
  for (size_t i = 0; i < c.laterals.size(); ++i) {
    const LateralBirth& b = c.laterals[i];
    if (b.parent < 0 || b.parent >= size() || b.site < 0)
      throw std::invalid_argument("a plate's carry names a lateral's parent that is not before it");
    addLateral(b, &c.roots[n + i]);
  }
  nextSite_ = c.nextSite;
  sideStream_ = c.sideStream;
  restore(coupled_, c.coupled);
  last_ = c.last;
  // the lists of nearby elements as the last step left them (growthStep)
  if (size() > 1) {
    indexElements();
    for (int r = 0; r < size(); ++r) listNeighbours(r);
  }
}

PlateCarry PlateSimulation::carry() const {
  PlateCarry c;
  c.last = last_;
  for (const auto& sim : roots_) c.roots.push_back({sim->state(), sim->carry()});
  c.laterals = births_;
  c.nextSite = nextSite_;
  c.sideStream = sideStream_;
  c.coupled = save(coupled_);
  return c;
}

Vec3 PlateSimulation::offset(int r) const { return offset_[static_cast<size_t>(r)]; }

void PlateSimulation::setTropism(int r, const TropismParams& t) {
  roots_[static_cast<size_t>(r)]->setTropism(t);
  seedlings_[static_cast<size_t>(r)].model.tropism = t;
}

void PlateSimulation::indexElements() {
  // which roots come within reach of another at all: their boxes in the plate, each widened by its reach
  // (1 + skin) R, overlap (O(nodes) and O(roots^2) box tests; roots apart skip the grid entirely)
  const int n = size();
  boxes_.resize(static_cast<size_t>(n));
  for (int r = 0; r < n; ++r) {
    const Eigen::Matrix3Xd& x = root(r).state().x;
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for (int i = 0; i < x.cols(); ++i) {
      const Vec3 p = x.col(i) + offset(r);
      const Eigen::Vector2d q(frame_.lateral.dot(p), frame_.downhill.dot(p));
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const double w = (1.0 + kPlateSkin) * seedling(r).model.rod.radius;
    boxes_[static_cast<size_t>(r)] = {lo.array() - w, hi.array() + w};
  }
  near_.assign(static_cast<size_t>(n), 0);
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const auto& A = boxes_[static_cast<size_t>(a)];
      const auto& B = boxes_[static_cast<size_t>(b)];
      if ((A.first.array() <= B.second.array()).all() && (B.first.array() <= A.second.array()).all())
        near_[static_cast<size_t>(a)] = near_[static_cast<size_t>(b)] = 1;
    }
  grid_.clear();
  firstElement_.clear();
  double reach = 0;
  int total = 0;
  for (int r = 0; r < size(); ++r) {
    const Eigen::Matrix3Xd& x = root(r).state().x;
    firstElement_.push_back(total);
    total += static_cast<int>(x.cols()) - 1;
  }
  // every list of elements at its bound, the plate's element count (it changes when elements split)
  reserveHighWater(grid_, static_cast<size_t>(total));
  reserveHighWater(capsules_, static_cast<size_t>(total));
  for (int r = 0; r < size(); ++r) {
    const Eigen::Matrix3Xd& x = root(r).state().x;
    if (!near_[static_cast<size_t>(r)]) continue;
    const double R = seedling(r).model.rod.radius;
    for (int i = 0; i + 1 < x.cols(); ++i) reach = std::max(reach, (x.col(i + 1) - x.col(i)).norm() + 2.0 * R);
  }
  // two elements within Ra + Rb + skin of each other have midpoints within half their lengths plus that:
  // at most `reach` (each term at most half of it), with the skin of the larger radius
  double rMax = 0;
  for (const Seedling& sd : seedlings_) rMax = std::max(rMax, sd.model.rod.radius);
  cellSize_ = reach + 2.0 * kPlateSkin * rMax;
  for (int r = 0; r < size(); ++r) {
    if (!near_[static_cast<size_t>(r)]) continue;
    const Eigen::Matrix3Xd& x = root(r).state().x;
    for (int i = 0; i + 1 < x.cols(); ++i) {
      const Vec3 mid = 0.5 * (x.col(i) + x.col(i + 1)) + offset(r);
      const auto cx = static_cast<long long>(std::floor(frame_.lateral.dot(mid) / cellSize_));
      const auto cy = static_cast<long long>(std::floor(frame_.downhill.dot(mid) / cellSize_));
      grid_.push_back({cellKey(cx, cy), r, i});
    }
  }
  std::sort(grid_.begin(), grid_.end(), [](const Element& a, const Element& b) {
    return a.cell != b.cell ? a.cell < b.cell : (a.root != b.root ? a.root < b.root : a.index < b.index);
  });
  capsuleOf_.assign(static_cast<size_t>(total), -1);
}

void PlateSimulation::listNeighbours(int r) {
  NeighbourCapsules& nb = roots_[static_cast<size_t>(r)]->neighbours();
  nb.pairs.clear();
  if (!near_[static_cast<size_t>(r)]) {
    nb.source.clear();
    return;
  }
  const RodState& s = root(r).state();
  const double Ra = seedling(r).model.rod.radius;
  std::vector<int>& capsules = capsules_;  // global element indices, in the order they are first listed
  capsules.clear();
  // a capsule per element of the other roots at most; the pairs have no such bound short of elements times
  // capsules: they start at a few per element and double when more are within reach
  reserveHighWater(nb.source, capsuleOf_.size());
  reserveHighWater(nb.first, capsuleOf_.size());
  reserveHighWater(nb.pairs, 4 * static_cast<size_t>(s.elements()));
  for (int i = 0; i < s.elements(); ++i) {
    const Vec3 a0 = s.x.col(i) + offset(r), a1 = s.x.col(i + 1) + offset(r);
    const Vec3 mid = 0.5 * (a0 + a1);
    const double ha = 0.5 * (a1 - a0).norm();
    const auto cx = static_cast<long long>(std::floor(frame_.lateral.dot(mid) / cellSize_));
    const auto cy = static_cast<long long>(std::floor(frame_.downhill.dot(mid) / cellSize_));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const long long key = cellKey(cx + dx, cy + dy);
        auto it = std::lower_bound(grid_.begin(), grid_.end(), key, [](const Element& e, long long k) { return e.cell < k; });
        for (; it != grid_.end() && it->cell == key; ++it) {
          if (it->root == r) continue;
          const Eigen::Matrix3Xd& o = root(it->root).state().x;
          const Vec3 b0 = o.col(it->index) + offset(it->root), b1 = o.col(it->index + 1) + offset(it->root);
          const double Rb = seedling(it->root).model.rod.radius;
          const double hb = 0.5 * (b1 - b0).norm();
          if ((0.5 * (b0 + b1) - mid).norm() >= ha + hb + (1.0 + kPlateSkin) * (Ra + Rb)) continue;
          if (nearJunction(r, i, it->root, it->index)) continue;
          const int g = firstElement_[static_cast<size_t>(it->root)] + it->index;
          int& c = capsuleOf_[static_cast<size_t>(g)];
          if (c < 0) {
            c = static_cast<int>(capsules.size());
            capsules.push_back(g);
          }
          nb.pairs.push_back({i, c});
        }
      }
  }
  std::sort(nb.pairs.begin(), nb.pairs.end());
  const int m = static_cast<int>(capsules.size());
  // the capsules' arrays only grow (a resize to another length reallocates): columns past source.size()
  // are unused, every capsule is named by its index
  if (nb.a.cols() < m) {
    const int room = std::max(m, 2 * static_cast<int>(nb.a.cols()));
    nb.a.resize(3, room);
    nb.b.resize(3, room);
    nb.radius.resize(room);
  }
  nb.first.assign(static_cast<size_t>(m), 0);
  nb.source.resize(static_cast<size_t>(m));
  for (int c = 0; c < m; ++c) {
    const int g = capsules[static_cast<size_t>(c)];
    capsuleOf_[static_cast<size_t>(g)] = -1;
    const int o = static_cast<int>(std::upper_bound(firstElement_.begin(), firstElement_.end(), g) - firstElement_.begin()) - 1;
    const int j = g - firstElement_[static_cast<size_t>(o)];
    const Eigen::Matrix3Xd& os = root(o).state().x;
    // the other root's capsule in this root's frame
    const Vec3 shift = offset(o) - offset(r);
    nb.a.col(c) = os.col(j) + shift;
    nb.b.col(c) = os.col(j + 1) + shift;
    nb.radius[c] = seedling(o).model.rod.radius;
    nb.first[static_cast<size_t>(c)] = r < o ? 1 : 0;
    nb.source[static_cast<size_t>(c)] = {o, j};
  }
}

void PlateSimulation::refreshCapsules(int r) {
  NeighbourCapsules& nb = roots_[static_cast<size_t>(r)]->neighbours();
  for (size_t c = 0; c < nb.source.size(); ++c) {
    const auto [o, j] = nb.source[c];
    const Eigen::Matrix3Xd& x = root(o).state().x;
    const Vec3 shift = offset(o) - offset(r);
    nb.a.col(static_cast<int>(c)) = x.col(j) + shift;
    nb.b.col(static_cast<int>(c)) = x.col(j + 1) + shift;
  }
}

double PlateSimulation::sweep() {
  double change = 0;
  listCluster();
  for (const CoupledRoot& c : cluster_) {
    const int r = c.plateIndex;
    refreshCapsules(r);  // the roots before it in the sweep may have moved
    Simulation& sim = *roots_[static_cast<size_t>(r)];
    before_ = sim.state().x;
    try {
      sim.relaxAgain();
    } catch (const RelaxError& e) {
      throw namedError(seedling(r).name, e);
    }
    change = std::max(change, (sim.state().x - before_).cwiseAbs().maxCoeff());
  }
  return change;
}

void PlateSimulation::listCluster() {
  indexElements();
  cluster_.clear();
  for (int r = 0; r < size(); ++r) {
    listNeighbours(r);
    if (!roots_[static_cast<size_t>(r)]->neighbours().empty()) cluster_.push_back(roots_[static_cast<size_t>(r)]->coupled(r));
  }
}

RelaxResult PlateSimulation::relaxCoupled() {
  const std::function<void()> refresh = [this] {
    for (const CoupledRoot& c : cluster_) refreshCapsules(c.plateIndex);
  };
  RelaxResult r;
  try {
    r = relaxNewtonCoupled(cluster_, refresh, coupled_);
  } catch (const RelaxError& e) {
    throw RelaxError("growth step " + std::to_string(root(0).step()) + ": the roots in contact (" +
                     seedling(cluster_.front().plateIndex).name + ", ...): " + e.what());
  }
  for (const CoupledRoot& c : cluster_) roots_[static_cast<size_t>(c.plateIndex)]->addCoupled(r);
  return r;
}

Eigen::MatrixXd PlateSimulation::coupledJacobian() {
  listCluster();
  const std::function<void()> refresh = [this] {
    for (const CoupledRoot& c : cluster_) refreshCapsules(c.plateIndex);
  };
  return cluster_.empty() ? Eigen::MatrixXd() : coupledStiffness(cluster_, refresh, coupled_);
}

Eigen::VectorXd PlateSimulation::coupledResidual(int k, double h) {
  listCluster();
  const std::function<void()> refresh = [this] {
    for (const CoupledRoot& c : cluster_) refreshCapsules(c.plateIndex);
  };
  return cluster_.empty() ? Eigen::VectorXd() : rootsim::coupledResidual(cluster_, refresh, coupled_, k, h);
}

std::vector<int> PlateSimulation::coupledRoots() const {
  std::vector<int> r;
  for (const CoupledRoot& c : cluster_) r.push_back(c.plateIndex);
  return r;
}

void PlateSimulation::relaxJointly(long budget) {
  indexElements();
  std::vector<int>& cluster = jointRoots_;
  cluster.clear();
  for (int r = 0; r < size(); ++r) {
    listNeighbours(r);
    if (!roots_[static_cast<size_t>(r)]->neighbours().empty()) cluster.push_back(r);
  }
  for (int r : cluster) roots_[static_cast<size_t>(r)]->beginJoint();
  try {
    for (long sub = 1; budget <= 0 || sub <= budget; ++sub) {
      bool all = true;
      for (int r : cluster) {
        refreshCapsules(r);
        all &= roots_[static_cast<size_t>(r)]->jointStep();
      }
      if (all) break;
      // the lists again now and then: the roots move further in one relaxation than in a Newton step
      if (sub % kJointRelist == 0) {
        indexElements();
        for (int r : cluster) listNeighbours(r);
      }
    }
  } catch (const RelaxError& e) {
    for (int r : cluster) roots_[static_cast<size_t>(r)]->endJoint();
    throw RelaxError(std::string("the roots in contact (") + seedling(cluster.front()).name + ", ...): " + e.what());
  }
  for (int r : cluster) roots_[static_cast<size_t>(r)]->endJoint();
}

const PlateStepRecord& PlateSimulation::growthStep() {
  const int n = size();
  int sweeps = 1;
  if (n == 1) {
    try {
      roots_[0]->growthStep();
    } catch (const RelaxError& e) {
      throw namedError(seedling(0).name, e);
    }
  } else {
    sweeps = settleStep();
  }
  emergeLaterals();
  // every root's lists as the final shapes stand (what the contact counts read)
  if (size() > 1) {
    indexElements();
    for (int r = 0; r < size(); ++r) listNeighbours(r);
  }
  last_ = observe(sweeps);
  return last_;
}

int PlateSimulation::settleStep() {
  const int n = size();
  // every root grows; then the roots apart relax alone (each its own banded Newton: a root apart is the
  // single root's run), the roots within reach of another together, as one Newton system from where growth
  // left them (their blocks coupled by their contacts' stiffness: relaxNewtonCoupled)
  for (int r = 0; r < n; ++r) roots_[static_cast<size_t>(r)]->beginStep();
  listCluster();
  listed_.resize(static_cast<size_t>(n));
  for (int r = 0; r < n; ++r) listed_[static_cast<size_t>(r)] = root(r).state().x;
  for (int r = 0; r < n; ++r) {
    if (!roots_[static_cast<size_t>(r)]->neighbours().empty()) continue;
    try {
      roots_[static_cast<size_t>(r)]->finishStep();
    } catch (const RelaxError& e) {
      throw namedError(seedling(r).name, e);
    }
  }
  // Then each root of the cluster finishes its step alone, with the others where they now are (its own
  // relaxation confirms the equilibrium, with its stability check, and commits). Where that moves a root
  // by more than a displacement whose contact force is half the equilibrium tolerance, or a root moved
  // further than the lists' skin covers, sweeps (relaxAgain, the lists built anew) and coupled solves
  // follow until none does: each root is then in equilibrium with the others' final shapes. Where the
  // coupled Newton finds no acceptable step (a snap), the roots in contact relax together explicitly,
  // every root one sub-step in turn, and Newton starts again from there (as one root's Newton falls back
  // to the explicit relaxation).
  double tolerance = std::numeric_limits<double>::infinity(), rMin = tolerance;
  for (int r = 0; r < n; ++r) {
    const Model& m = seedling(r).model;
    tolerance = std::min(tolerance, 0.5 * equilibriumTolerance(m.rod, m.env, m.solver, root(r).state()).force / m.env.selfContact.k);
    rMin = std::min(rMin, m.rod.radius);
  }
  bool open = !cluster_.empty();  // the cluster's roots have begun their step and not finished it
  int sweeps = 1;
  int handBacks = 0;  // short joint relaxations of this step (kJointHandBacks)
  for (int joint = 0;;) {
    double change = 0;
    if (!cluster_.empty()) {
      const RelaxResult rc = relaxCoupled();
      if (rc.stalled) {
        if (joint == kJointRelaxations) {
          std::ostringstream os;
          os << "growth step " << root(0).step() << ": the roots in contact did not settle (" << kJointRelaxations
             << " joint relaxations; " << coupled_.stallReason.data() << ")";
          throw RelaxError(os.str());
        }
        if (handBacks < kJointHandBacks) {
          relaxJointly(kJointBudget << (2 * handBacks));
          ++handBacks;
        } else {
          relaxJointly(0);
          ++joint;
        }
        continue;
      }
      if (open) {
        for (const CoupledRoot& c : cluster_) {
          const int r = c.plateIndex;
          refreshCapsules(r);
          Simulation& sim = *roots_[static_cast<size_t>(r)];
          before_ = sim.state().x;
          try {
            sim.finishStep();
          } catch (const RelaxError& e) {
            throw namedError(seedling(r).name, e);
          }
          change = std::max(change, (sim.state().x - before_).cwiseAbs().maxCoeff());
        }
        open = false;
      }
    }
    // a root that moved further than the skin since the lists were built may have met one not listed
    double moved = 0;
    for (int r = 0; r < n && sweeps == 1; ++r)
      moved = std::max(moved, (root(r).state().x - listed_[static_cast<size_t>(r)]).colwise().norm().maxCoeff());
    if (sweeps == 1 && change <= tolerance && moved <= kPlateSkin * rMin) {
      ++sweeps;  // nothing to sweep: counted as the sweep that found so
      break;
    }
    change = std::max(change, sweep());  // the lists anew (cluster_ too: listCluster)
    ++sweeps;
    if (change <= tolerance) break;
    if (sweeps > plate_.maxSweeps) {
      std::ostringstream os;
      os << "growth step " << root(0).step() << ": the roots in contact did not settle (" << plate_.maxSweeps
         << " sweeps; the last moved them by " << change << " m, tolerance " << tolerance << " m)";
      throw RelaxError(os.str());
    }
  }
  return sweeps;
}

bool PlateSimulation::nearJunction(int r, int i, int o, int j) const {
  auto near = [&](int lat, int li, int par, int pj) {
    const Seedling& sd = seedling(lat);
    if (sd.parent != par) return false;
    const double reach = 3.0 * (sd.model.rod.radius + seedling(par).model.rod.radius);
    const RodState& ls = root(lat).state();
    const RodState& ps = root(par).state();
    return 0.5 * (ls.S[li] + ls.S[li + 1]) < reach && std::abs(0.5 * (ps.S[pj] + ps.S[pj + 1]) - sd.siteS) < reach;
  };
  return near(r, i, o, j) || near(o, j, r, i);
}

double siteDelay(const LateralParams& lp, int root, int site) {
  if (lp.delaySpread == 0.0) return lp.delay;
  std::uint64_t state = lp.seed ^ (0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(root + 1));
  (void)splitmixUniform(state);  // mixes the root in before the site
  state ^= 0xbf58476d1ce4e5b9ULL * static_cast<std::uint64_t>(site + 1);
  for (;;) {
    const double d = lp.delay + lp.delaySpread * splitmixNormal(state);
    if (d >= 0.0) return d;
  }
}

const LateralParams& lateralsOf(const Seedling& sd, const PlateParams& plate) {
  return sd.laterals ? *sd.laterals : plate.laterals;
}

Model lateralModel(const Model& parent, const LateralParams& lp) {
  Model m = parent;
  m.rod.radius = lp.radius;
  m.growth.rate = lp.rate;
  m.growth.zoneLength = lp.zoneLength;
  m.tropism.beta = lp.beta;
  m.tropism.gamma = lp.gamma;
  m.tropism.rTau = lp.rTau;
  m.tropism.setPoint = lp.setPoint;
  m.tropism.setPointFinal = lp.setPointFinal;
  m.tropism.setPointDrift = lp.setPointDrift;
  m.tropism.setPointDriftTime = lp.setPointDriftTime;
  m.initial.length = lp.initialLength;
  return m;
}

PlateSpec plateOfOne(const Model& m) {
  PlateSpec spec;
  Seedling sd;
  sd.model = m;
  spec.seedlings.push_back(std::move(sd));
  spec.base = m;
  return spec;
}

std::string lateralName(const std::string& parent, int site) { return parent + "." + std::to_string(site + 1); }

void PlateSimulation::emergeLaterals() {
  emerged_.clear();
  const int existing = size();
  for (int r = 0; r < existing; ++r) {
    // the root's own lateral parameters (its seedling's; a lateral's are its parent's), a copy: a lateral
    // emerging below grows seedlings_, which would leave a reference into it dangling
    const LateralParams lp = lateralsOf(seedling(r), plate_);
    if (!lp.enabled || seedling(r).order >= lp.maxOrder) continue;
    for (;;) {
      const Seedling& parent = seedling(r);
      const RodState& s = root(r).state();
      const int k = nextSite_[static_cast<size_t>(r)];
      const double site = lp.first + k * lp.spacing;
      // the site emerges once the parent's tip is apicalUnbranched beyond it, and delay after that (the
      // parent's tip advances by its zone's growth, rate * zone per second)
      const double beyond = s.restLength() - site - lp.apicalUnbranched;
      if (beyond < 0.0) break;
      const double delay = siteDelay(lp, r, k);
      if (delay > 0.0 && beyond < delay * parent.model.growth.rate * parent.model.growth.zoneLength) break;
      ++nextSite_[static_cast<size_t>(r)];
      // the parent's node at the site, and its direction in the plate there
      int i = 1;
      while (i < s.nodes() - 2 && s.S[i] < site) ++i;
      if (i > 1 && site - s.S[i - 1] < s.S[i] - site) --i;  // the nearer node: within half an element
      const Vec3 p = s.x.col(i) + offset(r);
      const Vec3 t = s.x.col(i + 1) - s.x.col(i - 1);
      const double theta = std::atan2(frame_.downhill.cross(t).dot(frame_.normal), t.dot(frame_.downhill));
      const double side = lp.alternate ? (k % 2 == 0 ? 1.0 : -1.0) : (splitmixUniform(sideStream_) < 0.0 ? -1.0 : 1.0);
      LateralBirth b;
      b.parent = r;
      b.site = k;
      b.lateral = frame_.lateral.dot(p);
      b.downhill = frame_.downhill.dot(p);
      b.siteS = s.S[i];
      b.angle = std::remainder((lp.fromParent ? theta : 0.0) + side * lp.insertion, 2.0 * units::pi);
      b.time = s.time;
      addLateral(b, nullptr);
      emerged_.push_back(size() - 1);
    }
  }
}

Seedling PlateSimulation::lateralSeedling(const LateralBirth& b) const {
  const Seedling& parent = seedling(b.parent);
  const LateralParams& lp = lateralsOf(parent, plate_);
  Seedling sd;
  sd.laterals = lp;
  sd.name = lateralName(parent.name, b.site);
  sd.genotype = parent.genotype;
  sd.position = Eigen::Vector2d(b.lateral, b.downhill);
  sd.parent = b.parent;
  sd.order = parent.order + 1;
  sd.siteS = b.siteS;
  sd.emergedH = b.time / units::hour;
  Model& m = sd.model;
  m = lateralModel(parent.model, lp);
  m.initial.angle = b.angle;
  m.initial.startTime = b.time;
  // its own initial perturbation (each organ its own noise: with its parent's, every lateral would lean
  // the same way relative to its frame, and the laterals of one side would all curl back)
  std::uint64_t seed = parent.model.initial.seed ^ (0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(b.site + 1));
  m.initial.seed = static_cast<std::uint64_t>((splitmixUniform(seed) + 1.0) * 0x1.0p51);
  // the obstacles in the lateral's own frame (from the parent's)
  const Eigen::Vector2d shift = sd.position - parent.position;
  for (Obstacle& ob : m.env.obstacles) {
    ob.from -= shift;
    ob.to -= shift;
  }
  completeModel(m);
  return sd;
}

void PlateSimulation::addLateral(const LateralBirth& b, const RootCarry* from) {
  Seedling sd = lateralSeedling(b);
  try {
    roots_.push_back(from ? std::make_unique<Simulation>(sd.model, from->state, from->carry)
                          : std::make_unique<Simulation>(sd.model));
  } catch (const RelaxError& e) {
    throw namedError(sd.name, e);
  }
  offset_.push_back(sd.position.x() * frame_.lateral + sd.position.y() * frame_.downhill);
  seedlings_.push_back(std::move(sd));
  nextSite_.push_back(0);
  births_.push_back(b);
}

PlateStepRecord PlateSimulation::observe(int sweeps) const {
  PlateStepRecord rec;
  rec.step = size() > 0 ? root(0).step() : 0;
  rec.timeH = size() > 0 ? root(0).state().time / units::hour : 0.0;
  rec.sweeps = sweeps;
  for (int r = 0; r < size(); ++r) {
    const Simulation& sim = root(r);
    const NeighbourCapsules& nb = sim.neighbours();
    const RodState& s = sim.state();
    const double Ra = seedling(r).model.rod.radius;
    for (const auto& [i, c] : nb.pairs) {
      if (!nb.first[static_cast<size_t>(c)]) continue;  // each pair once, from its first root
      double sa = 0, sb = 0;
      contactSegmentPoints(s.x.col(i), s.x.col(i + 1), nb.a.col(c), nb.b.col(c), sa, sb);
      const Vec3 pa = s.x.col(i) + sa * (s.x.col(i + 1) - s.x.col(i));
      const Vec3 pb = nb.a.col(c) + sb * (nb.b.col(c) - nb.a.col(c));
      const double gap = (pa - pb).norm() / (Ra + nb.radius[c]);
      rec.touchingPairs += gap < 1.0;
      if (std::isnan(rec.minGap) || gap < rec.minGap) rec.minGap = gap;
    }
  }
  return rec;
}

RootPairForces PlateSimulation::pairForces(int a, int b) const {
  if (a > b) {
    RootPairForces f = pairForces(b, a);
    std::swap(f.onA, f.onB);
    return f;
  }
  const RodState& sa = root(a).state();
  const RodState& sb = root(b).state();
  const double Ra = seedling(a).model.rod.radius, Rb = seedling(b).model.rod.radius;
  const double k = seedling(a).model.env.selfContact.k;
  RootPairForces f;
  f.onA = Eigen::Matrix3Xd::Zero(3, sa.nodes());
  f.onB = Eigen::Matrix3Xd::Zero(3, sb.nodes());
  RootPairForce pf;
  for (int i = 0; i < sa.elements(); ++i)
    for (int j = 0; j < sb.elements(); ++j) {
      if (nearJunction(a, i, b, j)) continue;
      if (!rootPairForce(Ra, Rb, k, frame_.normal, sa.x.col(i) + offset(a), sa.x.col(i + 1) + offset(a),
                         sb.x.col(j) + offset(b), sb.x.col(j + 1) + offset(b), pf))
        continue;
      ++f.contacts;
      f.onA.col(i) += (1.0 - pf.sa) * pf.F;
      f.onA.col(i + 1) += pf.sa * pf.F;
      f.onB.col(j) -= (1.0 - pf.sb) * pf.F;
      f.onB.col(j + 1) -= pf.sb * pf.F;
    }
  return f;
}

}  // namespace rootsim
